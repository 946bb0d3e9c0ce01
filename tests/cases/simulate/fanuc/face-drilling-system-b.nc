(G-code system B: G99 makes the drilling cycle return to the R point, G98 to the initial)
(level; feed per revolution is G95 there. From Z5 the first hole returns to R at Z2, the)
(second, after G98, to Z5.)
%
O0001
G21 G95
T0202
G97 S800 M03
G00 X0. Z5.
G99 G83 Z-20. R-3. F0.1
G98 G83 Z-20. R-3. F0.1
G80
G00 X200. Z100.
M30
%
