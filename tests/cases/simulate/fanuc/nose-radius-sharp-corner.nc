(G42 with tool 2: nose radius 0.4 mm, tip 3; reference = nose centre less 0.4 in X and)
(Z. Points are X as radius, Z. F0.1 at 1000 rpm = 100 mm/min. Up the face to the edge)
(20/-10, then back down under it to 12/-12: the path turns left 180 - atan 2/8 = 165.964)
(degrees, a convex corner sharper than 150 degrees. The face's path ends at 20/-9.6,)
(reference X19.6 Z-10; the nose rolls G03 over the edge about 20/-10 through 2.8966 rad)
(to 0.4 off the back line, 20.0970/-10.3881: reference X19.6970 Z-10.7881, centre X19.6)
(Z-10.4, length 0.4 x 2.8966 = 1.1587 mm at 100 mm/min = 0.695 s. Concave corner 12/-12)
(into Z-20: the back line's path and x=12.4 cross at 12.4/-12.3123, reference X12)
(Z-12.7123. Earlier: start-up reference X10 Z1.6, concave corner 10/-10 at reference)
(X10 Z-10. Z-20 ends at reference X12 Z-20.4; G40 leaves to X25 Z2.)
%
O0104
G21 G99
T0202
G97 S1000 M03
G00 X40. Z5.
G42 G00 X20. Z2.
G01 Z-10. F0.1
X40.
X24. Z-12.
Z-20.
G40 G00 X50. Z2.
G00 X200. Z100.
M30
%
