(The thread height P300 = 0.3 mm is less than the first depth Q400 = 0.4 mm: the control)
(rejects the cycle.)
%
O0017
G21 G99
T0101
G97 S800 M03
G00 X36. Z3.
G76 P010060 Q100 R0.05
G76 X30. Z-20. P300 Q400 F1.5
G00 X200. Z100.
M30
%
