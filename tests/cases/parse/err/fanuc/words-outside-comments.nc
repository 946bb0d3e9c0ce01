(Words where blocks belong: a student's note, a simulator's billet line, and a number)
(with a letter l read for the digit 1. Each gets a hint for what it is, not scanning damage.)
%
O0003
G00 X40. Z2.
roughing pass
[BILLET X40 Z100
G01 X4l. F0.2
G01 Z-1o.5
M30
%
