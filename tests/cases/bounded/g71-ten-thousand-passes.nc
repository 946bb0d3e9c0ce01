(G71 Type I, outside, at a depth of one increment: 0.001 mm from radius 30 down to the)
(profile's 20 mm, 10,000 passes. Each pass asks which stretches cut before it lie under)
(the tool; the cycle is linear in its passes when each question is asked of one level.)
%
O0001
G21 G99
T0101
G97 S500 M03
G00 X60. Z2.
G71 U0.001 R0.5
G71 P10 Q20 U0 W0 F0.25
N10 G00 X40.
G01 Z-20. F0.1
N20 X60.
G00 X200. Z100.
M30
%
