(One turning pass, for cases about the machine settings a program is read with.)
G21 G99
T0101
G97 S500 M03
G00 X20. Z2.
G01 Z-5. F0.1
G00 X30.
M30
