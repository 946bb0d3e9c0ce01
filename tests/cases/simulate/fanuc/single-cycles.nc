(G90 turning with modal repetition, G94 facing with a taper, G92 threading passes.)
%
O0005
G21 G99
T0101
G97 S1000 M03
G00 X52. Z2.
G90 X46. Z-30. F0.25
X42.
X38.
G00 X55. Z2.
G94 X20. Z-1. F0.2
Z-2. R-1.
G00 X42. Z5.
G92 X39.2 Z-25. F1.5
X38.7
X38.3
X38.2
G00 X200. Z100.
M30
%
