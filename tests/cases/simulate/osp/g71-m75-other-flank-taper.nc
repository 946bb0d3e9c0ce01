(G71 compound thread, infeed pattern 3 M75, along the other flank M34, taper I-0.5.)
(Hand check: root r9.08 at Z-25, H 1.84, U 0.1: rough to 1.74, then finish at 1.84.)
(D 0.6: D^2 = 0.36 is at least H^2 - [H - U]^2 = 3.3856 - 3.0276 = 0.358, so pattern 3 is D x sqrt n:)
(0.6 0.848528 1.039230 1.2 1.341641 1.469694 1.587451 1.697056, then 1.74 and 1.84: 10 passes.)
(M34 shifts the start toward Z-: -[1.84 - d]/2 x tan 30 deg: -0.357957 ... -0.028868 and 0.)
(Taper: the start radius is the end radius - 0.5: first pass rapid r9.2 Z4.642043, thread to r9.7 Z-25.)
G50 S2000
G97 S400 M03
G00 X24 Z5
G71 X18.16 Z-25 I-0.5 B60 D0.6 U0.1 H1.84 F1.5 M34 M75
G00 X200 Z100
M02
