(Ball bar test run one way only: a 50 mm bar about x 50 z -50, one turn G03 at 1000 mm/min.)
G21 G98
T0100
G00 X100. Z5.
G01 X100. Z0. F500.
G03 X100. Z0. I0. K-50. F1000.
G00 X150. Z20.
M30
