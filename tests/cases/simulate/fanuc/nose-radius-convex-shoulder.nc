(G42 outside turning with tool 1: nose radius 0.8 mm, tip 3. Points are X as radius, Z;)
(the reference point is the nose centre less 0.8 in X and in Z. F0.1 at 1000 rpm = 100)
(mm/min. Start-up: ends perpendicular to Z-15 at its start: centre 10.8/2, reference X10)
(Z1.2. Concave corner 10/-15, Z- into the face up: the offset lines x=10.8 and z=-14.2)
(cross at the centre 10.8/-14.2, reference X10 Z-15. Convex shoulder edge 15/-15: the)
(face's path ends perpendicular at 15/-14.2, reference X14.2 Z-15; the nose rolls round)
(the edge on a G03 arc of radius 0.8 about it through 90 degrees to 15.8/-15: reference)
(X15 Z-15.8, centre X14.2 Z-15.8, length 0.8 pi/2 = 1.2566 mm at 100 mm/min = 0.754 s.)
(The last element Z-30 ends perpendicular at 15.8/-30, reference X15 Z-30.8, and G40)
(leaves from there to X25 Z2.)
%
O0101
G21 G99
T0101
G97 S1000 M03
G00 X40. Z5.
G42 G00 X20. Z2.
G01 Z-15. F0.1
X30.
Z-30.
G40 G00 X50. Z2.
G00 X200. Z100.
M30
%
