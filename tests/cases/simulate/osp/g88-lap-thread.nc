(G88 LAP continuous thread along a contour: a straight thread running into a taper, and a straight one.)
(Hand check, first call, from X30 Z5 = r15: the root runs r10 Z2, r10 Z-10, r12 Z-20.)
(H 1.2, D 0.4, U 0.1, M73: rough to 1.1 at 0.4: 0.4 0.8 1.1, finish 1.2: 4 passes.)
(Each pass follows the root [1.2 - d]/2 outside it: 0.4 0.2 0.05 0,)
(its start shifted by M32 toward Z+ by [1.2 - d]/2 x tan 30 deg: 0.230940 0.115470 0.028868 0.)
(First pass: rapid r10.4 Z2.230940, thread r10.4 Z-10, thread r12.4 Z-20, rapid r15 Z-20, rapid to S.)
(Lead 1.5 at 400 rpm: 600 mm/min. expand keeps this call, with a note: two thread elements are no G33.)
(Second call, contour NTH2 before it, from X30 Z5: root r9 Z3 to Z-18, H 1.5, D 0.5, M73 zigzag M33:)
(0.5 1.0 1.5 at r9.5 r9.25 r9, shifts +0.288675 -0.144338 0; expand writes three G33 blocks.)
G50 S2000
G97 S400 M03
G00 X30 Z5
G88 NTH1 D0.4 H1.2 B60 U0.1 F1.5 M32 M73
NTH1 G81
G00 X20 Z2
G01 Z-10
X24 Z-20
G80
NTH2 G81
G00 X18 Z3
G01 Z-18
G80
G00 X30 Z5
G88 NTH2 D0.5 H1.5 B60 F1.5 M33 M73
G00 X200 Z100
M02
