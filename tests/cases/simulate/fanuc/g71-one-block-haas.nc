(Haas one-block G71 with D: the same profile as g71-type1-outside, depth 2.5 mm.)
%
O0004
G20 G99
T0101
G97 S1000 M03
G00 X2.4 Z0.1
G71 P10 Q20 U0.016 W0.004 D0.1 F0.01
N10 G00 X0.8
G01 Z-0.8 F0.004
X1.6 Z-1.2
Z-2.
N20 X2.4
G70 P10 Q20
G00 X8. Z4.
M30
%
