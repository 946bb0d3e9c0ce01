(A turned part whose finishing pass reverses X: a 20 mm radius ball from the pole past its)
(equator, a 10 mm radius neck, and a shoulder out to 30 mm; the two arcs at different feeds.)
(Finished under G42 with T0101, 0.8 mm nose, tip 3, at 1000 rpm.)
G21 G99
T0101
G97 S1000 M03
G00 X60. Z2.
G42 G01 X0. Z0. F0.1
G03 X40. Z-20. R20. F0.05
G03 X20. Z-37.3205 R20. F0.2
G01 Z-50. F0.1
X60.
G40 G00 X80. Z5.
M30
