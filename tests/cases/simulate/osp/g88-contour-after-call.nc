(G88 whose contour follows the call: the contour belongs to the call, as a G85 contour)
(right after its call does. The flow goes on after its G80, and expand writes the passes as)
(G33 blocks and deletes the contour with the call.)
(Hand check as the second call of g88-lap-thread: from X30 Z5, root r9 Z3 to Z-18, H 1.5,)
(D 0.5, M73 zigzag M33: depths 0.5 1.0 1.5 at r9.5 r9.25 r9, starts shifted +0.288675,)
(-0.144338 and 0 in Z; each pass rapids out to r15 and back to Z5.)
G50 S2000
G97 S400 M03
G00 X30 Z5
G88 NTH2 D0.5 H1.5 B60 F1.5 M33 M73
NTH2 G81
G00 X18 Z3
G01 Z-18
G80
G00 X200 Z100
M02
