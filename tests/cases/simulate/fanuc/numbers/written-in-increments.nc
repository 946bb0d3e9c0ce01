(Issue 27: a program written wholly in least increments, as some posts write for a)
(control with DPI = 0: X52000 is 52 mm, F250 0.25 mm/rev, the 0.5 mm chamfer Z-500, the)
(approach Z2000 and the G71 retract R500. Nothing is written with a point, so nothing says)
(the words mean other than they read: quiet.)
O0003
G21 G99
T0101
G96 S180 M03
G50 S2000
G00 X52000 Z2000
G71 U1500 R500
G71 P10 Q20 U400 W100 F250
N10 G00 X19000
G01 Z0 F100
X20000 Z-500
Z-30000
X36000 W-1000
Z-45000
G02 X48000 Z-51000 R6000
N20 G01 X52000
G70 P10 Q20
G00 X100000 Z100000
M30
