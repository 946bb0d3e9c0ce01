(G76 with two finishing passes, a chamfer and a taper: P021060 is m = 2, r = 10 tenths of the)
(lead, a = 60; Q100 = 0.1 mm minimum cut; R0.05 allowance. X30 root at the end, R-0.5 taper,)
(so the root lies at radius 14.5 at the start Z; P900 = 0.9 mm height, Q350 = 0.35 mm first)
(depth, lead 1.5, chamfer 1.5 mm. A = X36 Z3, radius 18.)
(Hand check, depths: 0.35, 0.4950, 0.6062, then the minimum: 0.7062, 0.8062, then 0.85 =)
(0.9 - 0.05 last roughing; 2 passes at 0.9: 8 passes. A pass at depth D runs from radius)
(14.5 + 0.9 - D at Z3 + shift to radius 15 + 0.9 - D at Z-20 + shift, shift 0.9 - D times)
(tan 30, and pulls out 45 degrees over the last 1.5 mm: thread to Z-18.5 + shift, where the)
(radius has grown by 0.5 x 21.5/23 = 0.4674, then to radius + 1.5 at Z-20 + shift.)
(First pass: 15.05 Z3.3175, 15.5174 Z-18.1825, 17.05 Z-19.6825. Last: 14.5 Z3, 14.9674 Z-18.5,)
(16.5 Z-20. Out to radius 18 each time, back to A.)
%
O0015
G21 G99
T0101
G97 S800 M03
G00 X36. Z3.
G76 P021060 Q100 R0.05
G76 X30. Z-20. R-0.5 P900 Q350 F1.5
G00 X200. Z100.
M30
%
