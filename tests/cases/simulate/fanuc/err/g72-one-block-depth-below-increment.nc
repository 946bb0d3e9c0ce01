(A one-block G72 in inch whose D, 0.00001 in, is below the least increment of 0.0001 in:)
(the control reads it as 0. The error is on the D word, line 8.)
%
O0014
G20 G99
T0101
G97 S1000 M03
G72 P10 Q20 U0.016 W0.004 D0.00001 F0.01
N10 G00 Z-0.8
G01 X0.8 F0.004
Z0.1
N20 X2.4
G00 X8. Z4.
M30
%
