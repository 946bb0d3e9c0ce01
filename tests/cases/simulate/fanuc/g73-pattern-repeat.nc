(G73 two-block form: relief U3. W0.5, that is 3 mm radius in X and 0.5 mm in Z, R3 passes;)
(allowance U0.4 W0.1, that is 0.2 mm radius and 0.1 mm. A = X60 Z5, radius 30. Pass k of 3)
(is the profile shifted by 0.2, 0.1 plus 3, 0.5 times 3 - k over 2:)
(  pass 1 by 3.2, 0.6: rapid to radius 13.2 Z2.6, Z-9.4, arc to radius 18.2 Z-14.4 about the)
(  centre 15, -10 shifted: 18.2, -9.4; line to 23.2 Z-24.4, out to 31.2; back at rapid along)
(  Z5 at 31.2, in to 30; pass 2 by 1.7, 0.35: radius 11.7 Z2.35, Z-9.65, arc to 16.7 Z-14.65,)
(    21.7 Z-24.65, 29.7; back out to 30, along to Z5;)
(  pass 3 by 0.2, 0.1, at the allowance: radius 10.2 Z2.1, Z-9.9, arc to 15.2 Z-14.9,)
(    20.2 Z-24.9, 28.2; back out to 30, along to Z5.)
(Then G70 finishes the profile itself; the program goes on after N20.)
%
O0007
G21 G99
T0101
G97 S800 M03
G00 X60. Z5.
G73 U3. W0.5 R3
G73 P10 Q20 U0.4 W0.1 F0.25
N10 G00 X20. Z2.
G01 Z-10. F0.1
G02 X30. Z-15. R5.
G01 X40. Z-25.
N20 X56.
G70 P10 Q20
G00 X200. Z100.
M30
%
