$LAPT.MIN%
(G85 transverse, G82: passes parallel to X, stepping D in Z; contour after the call.)
(Hand check: A = X104 Z2 = r52 Z2. The first block G00 Z-12 keeps X, so the contour)
(starts at Xa = 104, Za = -12. With U0.4 W0.1: C0 = r52.2 Z-11.9; stock 13.9 in Z.)
(D3 is a Z depth: levels Z-1, Z-4, Z-7, Z-10; Z-13 is below Za + W: 4 passes.)
(Infeed line: Xp = r52.2 - 0.2 * [level + 11.9] / 13.9, as diameters)
(X104.0863, X104.1727, X104.2590, X104.3453.)
(Offset contour: X104.4 Z-11.9, X60.4, Z-5.9, X30.4, Z0.1, X0.4.)
(Z-1 and Z-4 meet the wall X30.4; Z-7 and Z-10 meet the wall X60.4. Relief 0.1 at 45 deg.)
(The last pass runs from X104.4 Z-11.9 along the offset contour; the return is X first,)
(to X104 at Z0.1, then Z2: the mirror of the longitudinal Z-then-X.)
G50 S2000
G00 X104 Z2 T010101
G96 S150 M03
G85 NFACE D3 F0.25 U0.4 W0.1
NFACE G82
G00 Z-12
G01 X60 F0.15
Z-6
X30
Z0
X0
G80
G00 X200 Z100
M02
