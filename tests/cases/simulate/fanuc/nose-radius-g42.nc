(G42 finishing with tool 2: nose radius 0.4 mm, tip 3. Hand check: along Z-, the nose)
(centre runs 0.4 mm above the contour, so the reference point, 0.4 mm below and 0.4 mm)
(toward -Z from the centre, runs on the contour's X: radius 10 on the first line. At the)
(corner into the 45-degree chamfer the offset lines meet at the centre (10.4, -19.834);)
%
O0008
G21 G99
T0202
G97 S1200 M03
G00 X30. Z5.
G42 G00 X20. Z2.
G01 Z-20. F0.1
X30. Z-25.
Z-40.
G02 X40. Z-45. R5.
G01 X50.
G40 G00 X60. Z5.
G00 X200. Z100.
M30
%
