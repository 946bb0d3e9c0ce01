(Two-block G71 whose F is the only F of the program: it stays the modal feed, so the G70)
(without F of its own and with no F in the profile finishes at it, as on the control.)
(Hand check: start X40 Z2, radius 20. Profile N10 X20, Z-20, N20 X40 shifted by U0.4 W0.1)
(to radius 10.2 from Z2.1 to Z-19.9, then up to radius 20.2. U2: levels at radius 18, 16,)
(14 and 12, each from Z2 to Z-19.9 at F0.25, 250 mm/min at 1000 rpm, retract R0.5 at 45)
(degrees; 4 passes, then the final pass along the shifted profile. G70 cuts X20 Z2 to)
(Z-20 to X40 at the modal F0.25: 22 mm in 5.28 s, then 10 mm in 2.4 s.)
%
O0008
G21 G99
T0101
G97 S1000 M03
G00 X40. Z2.
G71 U2. R0.5
G71 P10 Q20 U0.4 W0.1 F0.25
N10 G00 X20.
G01 Z-20.
N20 X40.
G70 P10 Q20
G00 X200. Z100.
M30
%
