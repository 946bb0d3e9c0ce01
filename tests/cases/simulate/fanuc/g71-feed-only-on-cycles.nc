(Haas one-block G71 whose F is on the cycle blocks only: no F before it and none in the)
(profile, as in the enier290188 programs. Reading the profile is no feed fault.)
(Hand check: start X40 Z2, radius 20. Profile N10 X20, Z-20, N20 X40, shifted by U0.4 W0.1)
(to radius 10.2 from Z2.1 to Z-19.9, then up to radius 20.2. D2: levels at radius 18, 16,)
(14 and 12, each cut at F0.25, 250 mm/min at 1000 rpm, from Z2 to Z-19.9, 45 degree)
(retract 0.5; level 10 would pass the profile's 10.2, so 4 passes. Then the final pass along)
(the shifted profile from X20.4 Z2.1 to X20.4 Z-19.9 to X40.4 Z-19.9, and back to X40 Z2.)
(G70 then cuts the profile at its F0.1, 100 mm/min.)
%
O0007
G21 G99
T0101
G97 S1000 M03
G00 X40. Z2.
G71 P10 Q20 U0.4 W0.1 D2. F0.25
N10 G00 X20.
G01 Z-20.
N20 X40.
G70 P10 Q20 F0.1
G00 X200. Z100.
M30
%
