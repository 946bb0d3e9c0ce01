(G33/G32/G34 single-pass thread cycles, one pass per block, from S = X30 Z5.)
(Hand check, X as radius, S = r15 Z5, 500 rpm:)
( N1 G33 X18 Z-20 F1.5: rapid r9 Z5, thread r9 Z-20 at 750 mm/min = 2 s, rapid r15 Z-20, rapid to S.)
( N2 K-0.2 shifts the start: rapid r8.9 Z4.8, thread r8.9 Z-20, out, back.)
( N3 I-0.5, radius start minus end: rapid r8.3 Z5, thread r8.8 Z-20.)
( N4 M23 L2, 45 deg chamfer: rapid r8.7 Z5, thread r8.7 Z-18, thread r10.7 Z-20, out, back.)
( N5 F1 J2, lead 0.5, 250 mm/min; chamfer one lead: thread r8.7 Z-19.5, thread r9.2 Z-20.)
( N6 M22, A-2: I = tan -2 deg times 25 = -0.87302: rapid r7.82698 Z5, thread r8.7 Z-20.)
( N7 G34 E0.05, lead 1.5 growing 0.05 per rev: 1.5n + 0.025n^2 = 25, n = 13.5890 rev, 1.6307 s.)
( N8 G32 face pass from X60 Z5: rapid r30 Z-1, thread along X to r10 Z-1 at 1000 mm/min,)
(    rapid out to r10 Z5, rapid back to r30 Z5. expand keeps every block: each is one pass.)
G50 S2000
G97 S500 M03
G00 X30 Z5
N1 G33 X18 Z-20 F1.5
N2 G33 X17.8 Z-20 K-0.2 F1.5
N3 G33 X17.6 Z-20 I-0.5 F1.5
M23
N4 G33 X17.4 Z-20 L2 F1.5
N5 G33 X17.4 Z-20 F1 J2
M22
N6 G33 X17.4 Z-20 A-2 F1.5
N7 G34 X17.4 Z-20 F1.5 E0.05
G00 X60 Z5
N8 G32 X20 Z-1 F2
G00 X200 Z100
M02
