(A G76 whose end Z is its start Z: the passes plunge and back out, and no thread is cut.)
%
O0019
G21 G99
T0101
G97 S800 M03
G00 X36. Z3.
G76 P010060 Q100 R0.05
G76 X30. W0 P900 Q350 F1.5
G00 X200. Z100.
M30
%
