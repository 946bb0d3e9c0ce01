(Common variables the machine keeps, #500-#999, read before the program sets them: their)
(values come from the machine. With none in the settings they read as vacant, 0 in)
(arithmetic, and each read is warned with how to give the value.)
%
O0001
G21 G99
T0101
G97 S1000 M03
G00 X[#501+40.] Z2.
#100=#502+1.
G01 Z-[#100*10.] F0.2
G00 X100. Z100.
M30
%
