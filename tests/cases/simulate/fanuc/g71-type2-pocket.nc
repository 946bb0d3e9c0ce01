(G71 Type II: the P block names X and Z, the profile dips into a pocket between Z-20 and Z-30.)
%
O0002
G21 G99
T0101
G97 S800 M03
G00 X50. Z2.
G71 U1.5 R0.5
G71 P10 Q20 U0.2 W0.05 F0.2
N10 G00 X30. Z2.
G01 Z-15. F0.1
X20. Z-20.
Z-30.
X36. Z-35.
Z-45.
N20 X50.
G70 P10 Q20
G00 X200. Z100.
M30
%
