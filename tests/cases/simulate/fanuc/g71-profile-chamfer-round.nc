(G71 and G70 over a profile with a chamfer `,C` and a corner rounding `,R` in its blocks:)
(the roughing passes stop at the chamfer and the round, and G70 cuts both.)
(Hand check, radii: the profile is r10 Z2 to r10 Z0, chamfer r10 Z0 to r11 Z-1 from)
(X22.,C1. at the corner r11 Z0; Z-15.,R3. rounds about r14 Z-12 to r14 Z-15; X40. to r20.)
%
O0001
G21 G99
T0101
G50 S2000
G97 S1000 M03
G00 X44. Z2.
G71 U2. R0.5
G71 P10 Q20 U0.4 W0.1 F0.25
N10 G00 X20.
G01 Z0. F0.1
X22.,C1.
Z-15.,R3.
N20 X40.
G70 P10 Q20
G00 X200. Z100.
M30
%
