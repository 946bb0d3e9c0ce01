(Fanuc G85 face boring: feed in from the R point Z3 to Z-20, dwell P200 = 0.2 s, feed out)
(to Z3, rapid to the initial level Z5.)
%
O0001
G21 G99
T0202
G97 S600 M03
G00 X20. Z5.
G85 Z-20. R-2. P200 F0.08
G80
G00 X200. Z100.
M30
%
