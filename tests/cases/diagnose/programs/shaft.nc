(A shaft: 40 mm diameter turned over 120 mm of Z after a 2 mm chamfer, then a face out to)
(60 mm, finished in one pass under G42 with T0101, 0.8 mm nose, tip 3, at 1000 rpm.)
G21 G99
T0101
G97 S1000 M03
G00 X36. Z2.
G42 G01 X36. Z0. F0.1
X40. Z-2.
Z-120.
X60.
G40 G00 X80. Z5.
M30
