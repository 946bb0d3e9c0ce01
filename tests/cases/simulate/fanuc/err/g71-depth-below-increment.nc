(A G71 whose depth of cut, 0.000001 mm, is below the least increment of 0.001 mm: the)
(control reads it as 0 and alarms. Simulated, it would be 10 million passes. The error)
(is on the U word of the first block, line 10.)
%
O0013
G21 G99
T0101
G97 S1000 M03
G00 X60. Z2.
G71 U0.000001 R0.5
G71 P10 Q20 U0.4 W0.1 F0.25
N10 G00 X20.
G01 Z-20. F0.1
X40. Z-30.
Z-50.
N20 X60.
G70 P10 Q20
G00 X200. Z100.
M30
%
