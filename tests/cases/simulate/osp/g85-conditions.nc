$LAPC.MIN%
(G85 with G84 condition changes on $ lines: XA=70 DA=6 FA=0.25, XB=50 DB=4 FB=0.2.)
(Hand check, diameters: A = X100 Z2; contour start X30, so Xa + U = X30.4; D10.)
(From X100, before XA: D10 to X90; from X90 to X80; from X80, before XA: D10 to X70.)
(From X70, on XA: DA6 at FA0.25 to X64, X58, X52; from X52, before XB: X46;)
(from X46, past XB: DB4 at FB0.2 to X42, X38, X34; X30 is below X30.4. 10 passes:)
(X90 80 70 at F0.3 = 240 mm/min at 800 rpm, X64 58 52 46 at 0.25, X42 38 34 at 0.2.)
(Every pass meets the face X98 Z-30 + W at Z-29.9. Zp on the line r50 Z2 to r15.2 Z2.1.)
(The last pass at FB0.2: X30.4 Z2.1, Z-29.9, X98.4; return Z2, then X100.)
G50 S2000
G00 X100 Z2 T010101
G97 S800 M03
G85 NLAP1 D10 F0.3 U0.4 W0.1
$ G84 XA=70 DA=6 FA=0.25
$ XB=50 DB=4 FB=0.2
NLAP1 G81
G00 X30
G01 Z-30 F0.15
X98
G80
G00 X200 Z100
M02
