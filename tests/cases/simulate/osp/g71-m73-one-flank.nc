(G71 compound thread, infeed pattern 1 M73, along one flank M32: M20x1.5 outside, from X24 Z5.)
(Hand check: root r9.08, H 1.84 dia = 0.92 radius, U 0.1, so rough to H - U = 1.74 dia.)
(Passes at D = 0.4 per pass: 0.4 0.8 1.2 1.6, then 1.74, then the finishing pass at 1.84: 6 passes.)
(A pass at depth d cuts at r = 9.08 + [1.84 - d]/2: r9.8 9.6 9.4 9.2 9.13 9.08.)
(M32 shifts the start toward Z+ by [1.84 - d]/2 x tan 30 deg:)
(  +0.415692 +0.300222 +0.184752 +0.069282 +0.028868 0: start Z5.415692 ... Z5.)
(Each pass: rapid to r and the shifted Z, thread to Z-25 at 1.5 x 400 = 600 mm/min, rapid to r12, rapid to S.)
(expand writes six G33 blocks with K for the shift, the K rounded to 0.001.)
G50 S2000
G97 S400 M03
G00 X24 Z5
G71 X18.16 Z-25 B60 D0.4 U0.1 H1.84 F1.5 M32 M73
G00 X200 Z100
M02
