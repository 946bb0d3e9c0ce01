(G72 face compound thread from X60 Z5: the thread runs along X to X20, root at Z-1.2.)
(Hand check: H 1.2, D 0.5, W 0.1 run along Z: rough to 1.1 at 0.5 per pass: 0.5 1.0 1.1, finish 1.2.)
(Pass Z = -1.2 + [1.2 - d]: -0.5 -1.0 -1.1 -1.2.)
(M32 shifts the start along X toward the start side: [1.2 - d] x tan 30 deg radius:)
(+0.404145 +0.115470 +0.057735 0, start r30.404145 r30.115470 r30.057735 r30.)
(Each pass: rapid to the start, thread to r10 at 2 x 250 = 500 mm/min, rapid to Z5, rapid to S.)
(expand writes G32 blocks, I for the shift.)
G50 S2000
G97 S250 M03
G00 X60 Z5
G72 X20 Z-1.2 B60 D0.5 W0.1 H1.2 F2 M32 M73
G00 X200 Z100
M02
