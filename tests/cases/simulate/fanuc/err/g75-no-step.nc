(A G75 groove from Z-18 to Z-24 with no Q: the control cannot step between plunges, so the)
(cycle is reported; the next block still runs.)
%
O0012
G21 G99
T0202
G97 S600 M03
G00 X50. Z-18.
G75 R1.
G75 X40. Z-24. P2000 F0.1
G00 X200. Z100.
M30
%
