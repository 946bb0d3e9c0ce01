(Feeds far outside what their mode makes plausible: G98 F0.05 is 0.05 mm/min, a feed per)
(revolution written under feed per minute, and the 50 mm cut takes 17 hours; G99 F150. is)
(150 mm/rev, a feed per minute written under feed per revolution. Each is warned once.)
%
O0001
G21
T0101
G97 S1000 M03
G00 X50. Z2.
G98 G01 Z-50. F0.05
X52.
G99 G01 Z2. F150.
X54.
G00 X200. Z100.
M30
%
