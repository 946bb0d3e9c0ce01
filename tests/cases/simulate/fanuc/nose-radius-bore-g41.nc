(G41 boring toward the chuck with tool 3: nose radius 0.4 mm, tip 2. Points are X as)
(radius, Z; the reference point is the nose centre plus 0.4 in X, less 0.4 in Z. F0.1 at)
(1000 rpm = 100 mm/min. Start-up: ends perpendicular to Z-10 at its start: centre)
(19.6/2, reference X20 Z1.6. Concave corner 20/-10, Z- into the face down: x=19.6 and)
(z=-9.6 cross at the centre 19.6/-9.6, reference X20 Z-10. Convex edge 15/-10: the)
(face's path ends at 15/-9.6, reference X15.4 Z-10; the nose rolls G02 round the edge)
(through 90 degrees to 14.6/-10: reference X15 Z-10.4, centre X15.4 Z-10.4, length 0.4)
(pi/2 = 0.6283 mm at 100 mm/min = 0.377 s. Z-25 at x=14.6 meets the R2 fillet, G03)
(about 13/-25, tangentially at 14.6/-25, reference X15 Z-25.4; the nose runs inside it)
(on radius 1.6 to 13/-26.6: reference X13.4 Z-27, centre X13.4 Z-25.4. The fillet is)
(the last element: G40 leaves from there to X10 Z-27.)
%
O0102
G21 G99
T0303
G97 S1000 M03
G00 X24. Z5.
G41 G00 X40. Z2.
G01 Z-10. F0.1
X30.
Z-25.
G03 X26. Z-27. R2.
G40 G01 X20.
G00 Z5.
G00 X200. Z100.
M30
%
