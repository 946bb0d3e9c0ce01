(Lines and arcs, absolute, metric: R arcs of 90 and 180 degrees, I/K arcs, a chamfer.)
%
O1001
G21 G99
G97 S500 M03
G00 X80. Z5.
G00 X20. Z2.
G01 Z0. F0.2
X24. Z-2.
Z-10.
G03 X24. Z-30. R-10.
G02 X44. Z-40. I10. K0.
G01 X50.
G03 X60. Z-45. R5.
G01 Z-60.
G02 X70. Z-65. I5. K0.
G01 X80.
G00 X100. Z50.
M30
%
