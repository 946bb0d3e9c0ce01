(Constant surface speed with no G50 clamp, facing to X0, on a machine whose settings give)
(no spindle limit: the spindle reaches the documented default top speed, 4000 rpm, and the)
(block is warned; no row runs at an infinite speed.)
%
O0001
G21 G99
T0101
G96 S200 M03
G00 X50. Z2.
G01 Z0. F0.2
X0.
G00 Z5.
X200. Z100.
M30
%
