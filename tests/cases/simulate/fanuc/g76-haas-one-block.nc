(Haas one-block G76, constant depth with alternating flanks, P4: K1.2 height, D0.3 per pass,)
(A60 tool, lead 2. X20 root, radius 10; A = X26 Z4, radius 13. No first block: no allowance,)
(one finishing pass, no chamfer.)
(Hand check, depths 0.3, 0.6, 0.9, 1.2 and the finishing pass at 1.2: 5 passes at radius 10.9,)
(10.6, 10.3, 10, 10. The pass at D lies 1.2 - D times tan 30 off, alternately toward and away)
(from the start: +0.5196, -0.3464, +0.1732, 0, 0. So the first runs Z4.5196 to Z-14.4804,)
(the second Z3.6536 to Z-15.3464.)
%
O0016
G21 G99
T0101
G97 S500 M03
G00 X26. Z4.
G76 X20. Z-15. K1.2 D0.3 F2. A60 P4
G00 X200. Z100.
M30
%
