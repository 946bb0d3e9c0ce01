(G75 OD grooving, two-block form: e = R1. From A = X50 Z-18, radius 25, to X40 Z-24 with)
(peck P2000 = 2 mm radius, step Q4000 = 4 mm, relief R0.25; P and Q count 0.001 mm.)
(Hand check: plunges at Z-18, -22 and -24, the last step 2 mm. Each plunge feeds radius 25)
(to 23, rapid back to 24, feeds to 21, back to 22, feeds to 20; relieves 0.25 in +Z, away)
(from the next plunge; rapid out to radius 25; steps. After the last: rapid back to A.)
(Then a Haas one-block part-off, G75 X0. I2. from X10 Z-30: Z and K left out, one plunge;)
(e = 1 from the first block above: feed radius 5 to 3, back to 4, to 1, back to 2, to 0;)
(no relief; rapid out to radius 5.)
%
O0011
G21 G99
T0202
G97 S600 M03
G00 X50. Z-18.
G75 R1.
G75 X40. Z-24. P2000 Q4000 R0.25 F0.1
G00 X10. Z-30.
G75 X0. I2. F0.05
G00 X200. Z100.
M30
%
