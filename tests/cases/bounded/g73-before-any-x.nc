(G73 before the tool's X is known: the pattern repeat moves nothing, with a note, and its)
(profile N30-N40 is not run as plain moves.)
O0073
G21 G99
T0101
G97 S800 M03
G00 Z3.
G73 U2. W0.5 R3
G73 P30 Q40 U0.4 W0.1 F0.2
N30 G00 X18.
G01 Z-12. F0.1
G02 X30. Z-18. R6.
N40 G01 X40.
G00 X120. Z80.
M30
