(G71 Type II whose profile ends on a taper below the start point's level: after following)
(the taper to its end, the tool cuts straight up to the previous level before it retracts,)
(instead of retracting at 45 degrees through the corner of stock over the taper.)
(Hand check, radius, no allowance: A = 25, 2. Profile 15,2 -> 15,-10 -> 22,-20. U2 R0.5:)
(levels at 23, 21, 19, 17. Level 23 cuts Z2 to the end, Z-20. Level 21 cuts to the taper at)
(Z-18.571 = -10 - 10 x 6/7, follows it to its end 22,-20, cuts up to 23 and retracts to)
(23.5,-19.5. Level 19 cuts to Z-15.714 and follows the taper up to 21 at Z-18.571; level 17)
(cuts to Z-12.857 and follows up to 19 at Z-15.714. Then the profile from 15,2 to 22,-20,)
(up to A's level at Z-20 and back to A.)
%
O0015
G21 G99
T0101
G97 S800 M03
G00 X50. Z2.
G71 U2. R0.5
G71 P10 Q20 U0. W0. F0.2
N10 G00 X30. Z2.
G01 Z-10. F0.1
N20 X44. Z-20.
G70 P10 Q20
G00 X200. Z100.
M30
%
