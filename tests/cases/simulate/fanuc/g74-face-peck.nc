(G74 face grooving, two-block form: e = R0.5. From A = X40 Z2, radius 20, to X30 Z-5, with)
(step P2500 = 2.5 mm radius, peck Q3000 = 3 mm and relief R0.2; P and Q count 0.001 mm.)
(Hand check: plunges at radius 20, 17.5 and 15, the last at the end X: 3 plunges. Each one)
(feeds Z2 to -1, rapid back to -0.5, feeds to -4, back to -3.5, feeds to -5, the last peck)
(1 mm; relieves 0.2 in +X, away from the next plunge; rapid out to Z2; steps -2.5 in X.)
(After the third plunge: rapid back to A.)
(Then axial peck drilling, X and P left out: G74 Z-12. Q4000 from X0 Z2 uses the same e:)
(feed to -2, back to -1.5, feed to -6, back to -5.5, -10, back to -9.5, -12; no relief;)
(rapid out to Z2.)
%
O0010
G21 G99
T0202
G97 S600 M03
G00 X40. Z2.
G74 R0.5
G74 X30. Z-5. P2500 Q3000 R0.2 F0.05
G00 X0. Z2.
G74 Z-12. Q4000 F0.08
G00 X200. Z100.
M30
%
