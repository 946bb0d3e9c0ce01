(Haas-style G71 whose Q block leaves the part back to the start Z, N20 G00 Z2. as the)
(enier290188 programs and the NIMS template end their profiles: the exit lies at the start)
(level, outside the stock, and is not part of the shape the passes cut; G70 runs it.)
(Hand check as g71-feed-only-on-cycles: start X40 Z2, radius 20; the shape X20 to Z-20 to)
(X40 shifted by U0.4 W0.1; D2 levels at radius 18, 16, 14, 12 cut from Z2 to Z-19.9 at)
(250 mm/min, retract 0.5 at 45 degrees; the final pass ends at X40.4 Z-19.9 and the cycle)
(returns to X40 Z2. G70: X20 to Z-20 to X40 at F0.1, then the exit rapid to Z2.)
%
O0010
G21 G99
T0101
G97 S1000 M03
G00 X40. Z2.
G71 P10 Q20 U0.4 W0.1 D2. F0.25
N10 G00 X20.
G01 Z-20.
X40.
N20 G00 Z2.
G70 P10 Q20 F0.1
G00 X200. Z100.
M30
%
