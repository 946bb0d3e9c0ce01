(Inch program: G20, I/K and R arcs, decimal points throughout.)
%
O1003
G20 G99
G97 S500 M03
G00 X2.5 Z0.2
X0.8 Z0.1
G01 Z0. F0.008
X1. Z-0.1
Z-0.6
G02 X1.4 Z-0.8 R0.2
G01 X1.6
G03 X2. Z-1. I0. K-0.2
G01 Z-1.5
G00 X3. Z1.
M30
%
