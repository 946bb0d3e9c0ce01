(A thread cut while constant surface speed is on: warned, since the spindle speed changes)
(with each pass's diameter.)
%
O0001
G21 G99
T0101
G50 S2000
G96 S150 M03
G00 X24. Z5.
G92 X19.4 Z-20. F1.5
X19.
G00 X200. Z100.
M30
%
