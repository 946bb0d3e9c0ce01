(G76 two-block form with the numbers of the leohiei-1 corpus program: P010060 is one)
(finishing pass, no chamfer, a 60 degree tool; Q80 = 0.08 mm minimum cut, R0.08 allowance;)
(X34.3 root, P812 = 0.812 mm height, Q270 = 0.27 mm first depth, lead 1.25; A = X38.5 Z2.5.)
(Hand check, depths: 0.27, 0.27 x sqrt 2 = 0.3818, 0.27 x sqrt 3 = 0.4677, then the square)
(root steps fall under 0.08 and the minimum rules: 0.5477, 0.6277, 0.7077, then 0.7877 would)
(pass 0.812 - 0.08 = 0.732, the last roughing pass; the finishing pass at 0.812. 8 passes.)
(Radius of a pass at depth D: 17.15 + 0.812 - D, from 17.692 down to 17.15. Flank infeed:)
(the pass lies 0.812 - D times tan 30 toward the start, 0.3129 for the first, 0 for the last,)
(which runs Z2.5 to Z-70. Each pass: rapid in, thread, rapid out to radius 19.25, back to A.)
%
O0014
G21 G99
T0101
G97 S1000 M03
G00 X38.5 Z2.5
G76 P010060 Q80 R0.08
G76 X34.3 Z-70. P812 Q270 F1.25
G00 X200. Z100.
M30
%
