(G28 and G53 on a machine whose settings give no home position: the missing home is)
(noted once, on the first block that needs it; after each return, and after the G53)
(move, the toolpath resumes at the next programmed point.)
%
O0028
G21 G99
G28 U0 W0
T0101
G97 S700 M03
G00 X50. Z2.
G01 Z-20. F0.2
G28 U0
G00 X60. Z5.
G01 Z-10.
G53 X100.
G00 X70. Z5.
G28 U0 W0
M30
%
