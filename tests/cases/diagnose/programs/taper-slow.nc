(A slow taper: one finishing pass from x 10 to x 30 over 60 mm of Z at 15 mm/min, four)
(minutes of cutting in which X and Z both move steadily with the clock.)
G21 G99
T0101
G97 S1000 M03
G00 X25. Z2.
G42 G01 X20. Z0. F0.1
X60. Z-60. F0.015
G40 G00 X80. Z5.
M30
