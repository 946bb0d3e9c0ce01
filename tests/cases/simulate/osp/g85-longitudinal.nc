$LAPA.MIN%
(G85 longitudinal, outside, contour right after the call: the call consumes it.)
(Hand check, radius mm: A = X62 Z2 = r31 Z2. Contour start Xa = 30 at Za = Zs = 2,)
(plus U0.4 W0.1 gives C0 = r15.2 Z2.1; stock 31 - 15.2 = 15.8; D8 = r4 per pass.)
(Infeed line A to C0: Zp = 2.1 - 0.1 * [level - 15.2] / 15.8.)
(Pass 1 X54 = r27: Zp 2.0253, cuts to Z-49.9 = the X60 face + W; relief r27.1 Z-49.8.)
(Pass 2 X46 = r23: Zp 2.0506, cuts to Z-49.9; relief r23.1 Z-49.8.)
(Pass 3 X38 = r19: Zp 2.0759, meets the taper X30.4 Z-19.9 to X40.4 Z-29.9 at Z-27.5.)
(X30 = r15 is below Xa + U = X30.4: no pass. 3 passes. The last pass runs X30.4 Z2.1,)
(Z-19.9, X40.4 Z-29.9, Z-49.9, X60.4 at F0.3, no E; back Z2 first, then X62.)
G50 S2000
G00 X62 Z2 T010101
G96 S150 M03
G85 NLAP1 D8 F0.3 U0.4 W0.1
NLAP1 G81
G00 X30
G01 Z-20 F0.15
X40 Z-30
Z-50
X60
G80
G00 X200 Z100
M02
