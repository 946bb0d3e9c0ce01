(Issue 27: a Haas reads a dwell P written with a decimal point in seconds [grammar/)
(fanuc.toml, from memory of the Haas manual, not verified]: P0.3 is 0.3 s and P300 is)
(300 ms, the same dwell twice; a Fanuc refuses P0.3 [integer-expected-hints.nc].)
O0009
G21 G99
T0101
G97 S600 M03
G00 X30. Z5.
G04 P0.3
G04 P300
G00 X100. Z100.
M30
