(Issue 27: a Denford control reads G83 as a Fanuc does [not verified]: the point in Q3. is)
(warned of with both readings, as on a Fanuc.)
O0007
G21 G98
T0101
G97 S1200 M03
G00 X0. Z5.
G83 Z-10. R-2. Q3. F100.
G80
G00 X100. Z100.
M30
