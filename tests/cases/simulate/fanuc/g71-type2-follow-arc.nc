(G71 Type II: the far side of the pocket rises along a convex arc; after each level the)
(tool follows the arc itself up to the previous level, not a straight line to its end.)
(Hand check, radius, no allowance: A = 25, 2. Profile 23,2 -> 23,-5 -> 18,-10 -> 18,-15,)
(G03 to 23,-20 about 18,-20, then 23,-25 -> 25,-25. U1.5 R0.5: levels at 23.5, 22, 20.5 and)
(19; 17.5 is below the pocket's 18. Level 23.5 cuts Z2 to Z-25. Level 22 cuts the pocket)
(from the taper, Z-6, to the arc, Z-17, where 22 = 18 + sqrt of 25 - 9; the arc to 23,-20,)
(the land to Z-25, up to 23.5; retract. Level 20.5: Z-7.5 to Z-15.670, the arc up to 22,-17.)
(Level 19: Z-9 to Z-15.101, the arc up to 20.5,-15.670. Each arc piece is about 18,-20.)
(Then up to A's level, the shifted profile from 23,2 and back to A.)
%
O0014
G21 G99
T0101
G97 S800 M03
G00 X50. Z2.
G71 U1.5 R0.5
G71 P10 Q20 U0. W0. F0.2
N10 G00 X46. Z2.
G01 Z-5. F0.1
X36. Z-10.
Z-15.
G03 X46. Z-20. R5.
G01 Z-25.
N20 X50.
G70 P10 Q20
G00 X200. Z100.
M30
%
