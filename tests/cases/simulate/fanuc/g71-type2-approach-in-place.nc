(G71 Type II whose P block goes nowhere: N10 G00 X50. W0. from the start point X50 Z2. That)
(block is still the approach; the profile's first element is the taper that follows it.)
(Hand check, radius: A = 25, 2. Shape with W0.1: 25,2.1 -> 20,-2.9 -> 20,-14.9 -> 25,-14.9.)
(U2: levels at 23 and 21; 19 is below the pocket's 20. Level 23 cuts from the taper, Z0.1,)
(to the wall, Z-14.9, fed down from A's level; level 21 from Z-1.9, fed down from 23.5, the)
(retract height over level 23's cut. Each retracts 0.5 at 45 degrees; the first element is)
(the taper, so no pass cuts through it. Then up to A's level, the P block's rapid to 25,2.1,)
(the shifted profile at 160 mm/min, back to A. G70: the taper from A, Z-15, X50, back to A.)
%
O0011
G21 G99
T0101
G97 S800 M03
G00 X50. Z2.
G71 U2. R0.5
G71 P10 Q20 U0. W0.1 F0.2
N10 G00 X50. W0.
G01 X40. Z-3. F0.1
Z-15.
N20 X50.
G70 P10 Q20
G00 X200. Z100.
M30
%
