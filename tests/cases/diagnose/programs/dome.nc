(A turned part whose finishing pass never reverses X: a 20 mm radius dome from the pole,)
(a 20 mm radius cylinder and a shoulder out to 30 mm, under G42 with T0101 at 1000 rpm.)
G21 G99
T0101
G97 S1000 M03
G00 X60. Z2.
G42 G01 X0. Z0. F0.1
G03 X40. Z-20. R20.
G01 Z-40.
X60.
G40 G00 X80. Z5.
M30
