(G71 Type I, outside: depth 2 mm, retract 0.5 mm, allowance U0.4 W0.1; then G70.)
(Hand check: A = X60 Z2 (radius 30); levels at radius 28, 26, ... 12 (9 passes); the)
(profile's lowest point is radius 10 + 0.2; the semi-finish pass runs at the profile + 0.2/0.1.)
%
O0001
G21 G99
T0101
G50 S2000
G96 S150 M03
G00 X60. Z2.
G71 U2. R0.5
G71 P10 Q20 U0.4 W0.1 F0.25
N10 G00 X20.
G01 Z-20. F0.1
X40. Z-30.
Z-50.
N20 X60.
G70 P10 Q20
G00 X200. Z100.
M30
%
