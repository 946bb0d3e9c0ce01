(G71 Type II that faces a step 0.3 mm behind the start point, Haas style: the profile ends)
(N20 G00 Z0.5, back to the start point's Z. With W0.2 that exit, shifted, ends 0.2 past the)
(start point's plane: it still leaves the part toward the start point and is the exit, not)
(a turn back in Z.)
(Hand check, radius: A = 25, 0.5. Shape with U0.4 W0.2: 22.2,0.4, wall to 25.2,0.4. U1:)
(levels at 24 and 23, each from Z0.5 to the wall at Z0.4, retract 0.5 at 45 degrees, up to)
(A's level and back to Z0.5; 22 is below 22.2. Then the P block's rapid to 22.2,0.4, the)
(wall, back to A. G70 runs the exit.)
%
O0021
G21 G99
T0101
G97 S800 M03
G00 X50. Z0.5
G71 U1. R0.5
G71 P10 Q20 U0.4 W0.2 F0.2
N10 G00 X44. Z0.2
G01 X50. F0.1
N20 G00 Z0.5
G70 P10 Q20
G00 X200. Z100.
M30
%
