(An inch program, G20, on a metric machine: the finishing pass's feed per revolution in the)
(summary is F0.008 in/rev = 0.2032 mm/rev, and the roughness follows from it: eq. 9.1 with)
(the 0.8 mm nose and 5 degree minor edge of tool 1.)
%
O0001
G20 G99
T0101
G50 S2000
G97 S1000 M03
G00 X1.8 Z0.1
G01 G42 Z0. F0.008
X2. Z-0.1
Z-1.
G40 X2.2
G00 X7. Z3.
M30
%
