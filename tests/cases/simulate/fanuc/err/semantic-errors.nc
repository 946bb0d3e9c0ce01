(Parses cleanly, and the control rejects it: `check` reports what `simulate` does. The first)
(G01 has no feed under G99; N30's R5 arc cannot reach its 20 mm chord; the first G71's Q90)
(names no block; N130 numbers two blocks, so the second G71's Q130 is ambiguous; the profile)
(N200-N230 turns back in Z at N220, where the error is marked.)
%
O0001
G21 G99
T0101
G50 S2000
G97 S1000 M03
G00 X44. Z2.
G01 X40. Z0.
N30 G02 X40. Z-20. R5. F0.2
G00 X44. Z2.
G71 U2. R0.5
G71 P100 Q90 U0.4 W0.1 F0.25
N100 G00 X20.
N130 G01 Z-10.
N130 X40.
G00 X44. Z2.
G71 U2. R0.5
G71 P100 Q130 U0.4 W0.1 F0.25
G71 U2. R0.5
G71 P200 Q230 U0.4 W0.1 F0.25
N200 G00 X20.
G01 Z-10.
N220 X30. Z-5.
N230 X40. Z-20.
G00 X200. Z100.
M30
%
