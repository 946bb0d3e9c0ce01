(Issue 27: under increment input a feed per revolution without a decimal point counts)
(least increments too: `F2` is 0.002 mm/rev, less per revolution than a cutting edge's)
(radius [0.01 mm]: no chip forms, the edge rubs. `F2.` or `F0.2` was meant.)
O0002
G21 G99
T0101
G96 S180 M03
G50 S2000
G00 X42. Z2.
G01 Z-30. F0.25
X44.
G00 Z2.
X40.
G01 Z-30. F2
X44. F0.2
G00 X100. Z100.
M30
