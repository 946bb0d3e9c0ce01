(Fanuc G87 side drilling with a live tool at C90: across the axis, off the XZ plane of the)
(turned part. The cycle is warned and its moves are left out; the tool is back at the)
(initial level after it.)
%
O0001
G21 G98
T0202
M45 S1500
G00 X60. Z-10. C90.
G87 X20. R-3. F50.
G80
G00 X200. Z100.
M30
%
