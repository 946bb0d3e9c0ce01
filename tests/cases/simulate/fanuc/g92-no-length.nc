(A G92 pass whose end Z is its start Z, after one that cuts: the second cuts no thread.)
%
O0020
G21 G99
T0101
G97 S800 M03
G00 X36. Z3.
G92 X33.2 Z-20. F1.5
X32.6 Z3.
G00 X200. Z100.
M30
%
