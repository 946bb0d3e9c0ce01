(G72 facing: depth 1.5 mm in Z, allowance U0.2 W0.1; profile from the face outward.)
%
O0003
G21 G99
T0101
G97 S700 M03
G00 X82. Z1.
G72 W1.5 R0.3
G72 P10 Q20 U0.2 W0.1 F0.2
N10 G00 Z-8.
G01 X60. F0.1
X40. Z-4.
X20.
Z0.
N20 X0.
G70 P10 Q20
G00 X200. Z100.
M30
%
