(G42 with tool 2: nose radius 0.4 mm, tip 3; reference = nose centre less 0.4 in X and)
(Z. Points are X as radius, Z. F0.1 at 1000 rpm = 100 mm/min. Start-up: centre 10.4/2,)
(reference X10 Z1.6. Concave corner 10/-15: centre 10.4/-14.6, reference X10 Z-15. The)
(face up ends at the kink 13/-15 into the convex R5 arc, G03 about 10/-19, starting at)
(3-4-5 off its centre: its path ends perpendicular at 13/-14.6, reference X12.6 Z-15.)
(Convex kink: the face heads +X, the arc starts 36.87 degrees further left, so the nose)
(rolls G03 about 13/-15 with radius 0.4 to 13.24/-14.68, 0.4 along the arc's radius:)
(reference X12.84 Z-15.08, centre X12.6 Z-15.4, length 0.4 x 0.6435 = 0.2574 mm at)
(100 mm/min = 0.154 s. The arc's path has radius 5.4 about 10/-19 and ends at)
(15.4/-19: reference X15 Z-19.4, centre X9.6 Z-19.4. Z-30 joins it tangentially and ends)
(at 15.4/-30: reference X15 Z-30.4.)
%
O0103
G21 G99
T0202
G97 S1000 M03
G00 X40. Z5.
G42 G00 X20. Z2.
G01 Z-15. F0.1
X26.
G03 X30. Z-19. R5.
G01 Z-30.
G40 G00 X40. Z2.
G00 X200. Z100.
M30
%
