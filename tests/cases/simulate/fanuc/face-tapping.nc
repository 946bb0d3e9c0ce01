(Fanuc G84 face tapping, sources in grammar/fanuc.toml: an M10x1.5 tap rapids to the)
(R point Z2, taps to Z-15 at the lead F1.5 per revolution, the spindle reverses and it backs)
(out to Z2 the same way, then rapids to the initial level Z5. The tap's moves are thread)
(moves; expand keeps the cycle.)
%
O0001
G21 G99
T0202
G97 S300 M03
G00 X0. Z5.
G84 Z-15. R-3. F1.5
G80
G00 X200. Z100.
M30
%
