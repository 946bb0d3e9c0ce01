(Two-block G71 with F and S in its first block, as GSK-family controls write it: F and S)
(are modal words there, and the roughing cuts at F0.25 and S900 since the second block)
(gives none; G70 finishes at the profile's F0.1.)
%
O0001
G21 G99
T0101
G50 S2000
G97 S800 M03
G00 X44. Z2.
G71 U2. R0.5 F0.25 S900
G71 P10 Q20 U0.4 W0.1
N10 G00 X20.
G01 Z-10. F0.1
X40.
N20 Z-30.
G70 P10 Q20
G00 X200. Z100.
M30
%
