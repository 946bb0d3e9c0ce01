(G71 Type I with a level on a flat of the shifted profile: A X36, U1.4, so the second level)
(is 18 - 1.4 - 1.4 = 15.2 mm, the radius of the flat X30 plus U0.4, and in binary it comes)
(out a hair above it. That level still cuts up to where the flat begins.)
(Hand check, radius: A = 18, 2. Shape with U0.4: 10.2,2 -> 10.2,-2 -> 15.2,-5 -> 15.2,-40 ->)
(18.2,-40. R0.5: level 16.6 cuts Z2 to Z-40; 15.2 cuts Z2 to the flat's start, Z-5; then)
(13.8 to Z-4.16, 12.4 to Z-3.32 and 11 to Z-2.48 on the taper; 9.6 is below 10.2. Each)
(retracts 0.5 at 45 degrees. No step between levels is over 1.4 mm. Then the final pass.)
%
O0019
G21 G99
T0101
G97 S800 M03
G00 X36. Z2.
G71 U1.4 R0.5
G71 P10 Q20 U0.4 W0. F0.2
N10 G00 X20.
G01 Z-2. F0.1
X30. Z-5.
Z-40.
N20 X36.
G70 P10 Q20
G00 X200. Z100.
M30
%
