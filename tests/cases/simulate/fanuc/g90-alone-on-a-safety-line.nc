(System A: G90 is the turning cycle. A safety line that writes it alone selects the cycle)
(and moves nothing; the G00 after it takes the motion group back, so the program runs)
(as written, with a warning on the safety line. X30. alone after a G90 block runs the)
(cycle again from where the tool is.)
%
O0001
G21 G40 G90 G99
T0101
G97 S1000 M03
G00 X42. Z2.
G01 Z0. F0.2
G00 X44. Z2.
G90
X38. Z-20. F0.2
X34.
G00 X200. Z100.
M30
%
