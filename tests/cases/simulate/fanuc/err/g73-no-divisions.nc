(A G73 with no first block and no D has no number of passes; the control's parameter is)
(not known, so the cycle is reported and the program goes on after N20.)
%
O0009
G21 G99
T0101
G97 S800 M03
G00 X50. Z3.
G73 P10 Q20 U0.4 W0.1 F0.2
N10 G00 X30.
G01 Z-20. F0.1
N20 X50.
G00 X200. Z100.
M30
%
