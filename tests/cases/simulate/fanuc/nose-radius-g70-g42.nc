(G71 roughing and G70 finishing of a profile that switches G42 on and off itself: tool 1,)
(nose radius 0.8 mm, tip 3; reference = nose centre less 0.8 in X and Z. Points are X as)
(radius, Z. The roughing runs uncompensated: no G42 at the call. The G70 pass from the)
(start point 20/5: N10 is the start-up and ends perpendicular to N20 at its start: centre)
(10.8/5, reference X10 Z4.2. Concave corner 10/-15: centre 10.8/-14.2, reference X10)
(Z-15. Convex edge 15/-15: N30's path ends at 15/-14.2, reference X14.2 Z-15, then the)
(corner arc G03 about the edge, radius 0.8, 90 degrees to 15.8/-15: reference X15 Z-15.8,)
(centre X14.2 Z-15.8, length 1.2566 mm. Under G96 S150 its rpm is that of the corner's)
(radius 15: 150000 / 2 pi 15 = 1591.5, so F = 159.15 mm/min and 0.474 s. N40 ends)
(perpendicular at 15.8/-30, reference X15 Z-30.8; N50 with G40 leaves from there to X21)
(Z-30; G70 returns to 20/5. The corner arc is one of G70's moves.)
%
O0106
G21 G99
T0101
G96 S150 M03
G00 X40. Z5.
G71 U1. R0.5
G71 P10 Q50 U0.4 W0.1 F0.25
N10 G00 G42 X20.
N20 G01 Z-15. F0.1
N30 X30.
N40 Z-30.
N50 G40 X42.
G70 P10 Q50
G00 X200. Z100.
M30
%
