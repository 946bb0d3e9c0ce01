(G71 Type II whose profile starts at the top of a convex arc, X30 Z2 falling to X28 Z1 about)
(X28 Z2, with A at X40 Z6 and U2.4: the second level, 20 - 2.4 - 2.4 = 15.2 mm, is the)
(arc's top plus U0.4, in binary a hair above it. It touches the arc there and still cuts the)
(stretch beyond; the step over the flat stays 2.4 mm or less.)
(Hand check, radius: A = 20, 6. Shape with U0.4: 15.2,2, arc to 14.2,1 about 14.2,2, flat)
(to Z-1, wall to 20.2. R0.5: level 17.6 cuts Z6 to Z-1; level 15.2 cuts from the arc's top,)
(Z2, to Z-1, fed down from 18.1; 12.8 is below 14.2. Then the P block's rapid to 15.2,2, the)
(arc, the flat and the wall, and back to A.)
%
O0020
G21 G99
T0101
G97 S800 M03
G00 X40. Z6.
G71 U2.4 R0.5
G71 P10 Q20 U0.4 W0. F0.2
N10 G00 X30. Z2.
G03 X28. Z1. I-1. K0. F0.1
G01 Z-1.
N20 X40.
G70 P10 Q20
G00 X200. Z100.
M30
%
