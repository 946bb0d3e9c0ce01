(Issue 27: a Haas lathe's G83 takes Q in program units, with or without a point)
(grammar/fanuc.toml, schema haas_drilling: Q3. is a 3 mm peck and nothing is said.)
O0008
G21 G98
T0101
G97 S1200 M03
G00 X0. Z5.
G83 Z-10. R2. Q3. F100.
G80
G00 X100. Z100.
M30
