(Issue 27: `Z-45` without its point, inside a G71 profile, reads -0.045 mm: the profile)
(runs back from Z-30. to the face and the cycle refuses it. The error is said at the word)
(that reads implausibly, with the block where the profile turns back as a second label.)
O0004
G21 G99
T0101
G96 S180 M03
G50 S2000
G00 X52. Z2.
G71 U1.5 R0.5
G71 P10 Q20 U0.4 W0.1 F0.25
N10 G00 X20.
G01 Z0. F0.1
X24. Z-2.
Z-30.
X36.,C1.
Z-45
X50.
N20 X52.
G70 P10 Q20
G00 X100. Z100.
M30
