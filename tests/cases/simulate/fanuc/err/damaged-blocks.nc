(A scanned program with a damaged value: its parse error, and the rest of the program checked.)
(N20's `X1O.` does not read, so G71 P20 is not checked and a note says why, instead of "no)
(block N20"; the position is unknown after it until both axes are named again. The arc at)
(N60 that cannot reach is still found.)
%
O0001
G21 G99
T0101
G50 S2000
G97 S1000 M03
G00 X44. Z2.
G71 U2. R0.5
G71 P20 Q40 U0.4 W0.1 F0.25
N20 G00 X1O.
G01 Z-10. F0.1
N40 X40.
G00 X44. Z2.
G01 X40. Z0. F0.2
N60 G02 X40. Z-20. R5.
G00 X200. Z100.
M30
%
