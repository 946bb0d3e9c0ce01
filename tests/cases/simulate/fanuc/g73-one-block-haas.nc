(Haas one-block G73 with D1: a single pass, at the allowance U0.5 W0.1, that is 0.25 mm)
(radius and 0.1 mm; the relief I2.5 does not matter with one pass. A = X50 Z3, radius 25.)
(Hand check: rapid to radius 15.25 Z3.1 as the P block moves X only, feed to Z-19.9, to)
(radius 25.25 = X50 + 0.5, then back at rapid: along Z to Z3 at radius 25.25, in to 25.)
%
O0008
G21 G99
T0101
G97 S1000 M03
G00 X50. Z3.
G73 P30 Q40 U0.5 W0.1 I2.5 K0. D1 F0.2
N30 G00 X30.
G01 Z-20. F0.1
N40 X50.
G00 X200. Z100.
M30
%
