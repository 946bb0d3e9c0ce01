$LAPD.MIN%
(G86 copy turning on a contour with a pocket, contour after the call; a G84 line there)
(is warned about and ignored, since condition changes belong to G85.)
(Hand check, radius: A = X50 Z2 = r25 Z2; contour start X30 at Z2; U0.4 W0.2 gives)
(C0 = r15.2 Z2.2; stock 9.8; D4 = r2: passes leave 7.8, 5.8, 3.8, 1.8 of it, then 0.)
(Share s = 0.7959, 0.5918, 0.3878, 0.1837, 0. Pass N is the contour shifted by)
(X 0.4 + 19.6 s as a diameter and Z 0.2 - 0.2 s: starts X46 Z2.0408, X42 Z2.0816,)
(X38 Z2.1224, X34 Z2.1633, X30.4 Z2.2. Pass 1: X46 Z2.0408, Z-9.9592, X40 Z-15.9592,)
(Z-21.9592, X52 Z-27.9592, Z-39.9592, X64. Then straight up to 0.1 above the pass top)
(X48.4 + 15.6 = X64, i.e. X64.2, back along Z to the next start and down at rapid: A lies)
(in front of C0 along the cut, so every descent is in air. The last pass: X30.4 Z2.2,)
(Z-9.8, X24.4 Z-15.8, Z-21.8, X36.4 Z-27.8, Z-39.8, X48.4; return Z2, then X50.)
G50 S2000
G00 X50 Z2 T010101
G97 S1000 M03
G86 NLAP1 D4 F0.25 U0.4 W0.2
$ G84 XA=40 DA=2
NLAP1 G81
G00 X30
G01 Z-10 F0.1
X24 Z-16
Z-22
X36 Z-28
Z-40
X48
G80
G00 X200 Z100
M02
