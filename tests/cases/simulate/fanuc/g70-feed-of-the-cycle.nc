(A G70 with its own F0.1 after a facing cut at F0.3 and a G71 at F0.25: the profile has no)
(F, so the finishing pass cuts at the G70's F0.1, not at an F in effect before the profile.)
(Hand check: the face from X42 to X-1 at Z0, 21.5 mm at 300 mm/min. Then as in)
(g70-feed-from-roughing: start X40 Z2, U2 levels at radius 18, 16, 14, 12 from Z2 to Z-19.9)
(at F0.25, the final pass along the profile shifted by U0.4 W0.1. G70 cuts X20 Z2 to Z-20 to)
(X40 at F0.1, 100 mm/min: 22 mm in 13.2 s, then 10 mm in 6 s.)
%
O0009
G21 G99
T0101
G97 S1000 M03
G00 X42. Z0.
G01 X-1. F0.3
G00 X40. Z2.
G71 U2. R0.5
G71 P10 Q20 U0.4 W0.1 F0.25
N10 G00 X20.
G01 Z-20.
N20 X40.
G70 P10 Q20 F0.1
G00 X200. Z100.
M30
%
