(The cycle names N30, which no block has; the control alarms, and the rest still runs.)
%
O0006
G21 G99
T0101
G97 S800 M03
G00 X50. Z2.
G71 U1.5 R0.5
G71 P10 Q30 U0.2 W0.05 F0.2
N10 G00 X30.
G01 Z-15. F0.1
N20 X50.
G00 X200. Z100.
M30
%
