(A G71 with no F, and none before it: the control alarms at the cycle, feed zero. The)
(error is on the G71 block, line 11, and not on the later G01, line 16, which has its)
(own F0.2 and cuts 2 mm in X at 200 mm/min, 0.6 s.)
%
O0012
G21 G99
T0101
G97 S1000 M03
G00 X40. Z2.
G71 U2. R0.5
G71 P10 Q20 U0.4 W0.1
N10 G00 X20.
G01 Z-20.
N20 X40.
G00 X42. Z2.
G01 X38. F0.2
G00 X200. Z100.
M30
%
