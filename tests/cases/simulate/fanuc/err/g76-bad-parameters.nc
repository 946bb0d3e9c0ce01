(P010045 asks for a 45 degree tool, which a Fanuc G76 does not take: the control stops at)
(the first block and its cycle block cuts nothing. A Haas A150 is beyond 120 degrees.)
%
O0020
G21 G99
T0101
G97 S800 M03
G00 X36. Z3.
G76 P010045 Q100 R0.05
G76 X30. Z-20. P900 Q350 F1.5
G76 X30. Z-20. K0.9 D0.35 F1.5 A150
G00 X200. Z100.
M30
%
