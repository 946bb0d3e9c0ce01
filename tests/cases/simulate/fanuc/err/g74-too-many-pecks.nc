(A peck of Q1, one least increment of 0.001 mm, over a 20 mm drilling depth would be 20000)
(pecks: more than turnpass simulates, which it reports instead.)
%
O0013
G21 G99
T0202
G97 S600 M03
G00 X0. Z2.
G74 R0.5
G74 Z-18. Q1 F0.08
G00 X200. Z100.
M30
%
