(Inside G71 Type II whose start point, X20 Z5, lies at the X of the P block's point, X20 Z2:)
(the bore is X20 and an inner groove with tapered sides is roughed from it. Level with the)
(P block, the start point is inside because the rest of the profile lies at larger X.)
(Hand check, radius: A = 10, 5. Shape with W0.1: 10,2.1 -> 10,-4.9 -> 13,-7.9 -> 13,-14.9)
(-> 10,-17.9 -> 10,-24.9. U1: levels at 11 and 12; 13 is the groove bottom. Level 11)
(cuts the groove from Z-5.9 to Z-16.9, entered along the bore at A's level, then follows)
(the rising side back to 10 at Z-17.9 and retracts 0.5 at 45 degrees to 9.5,-17.4.)
(Level 12: along at 9.5 to Z-6.9, rapid to 10.5, feed to 12, cut to Z-15.9, follow the)
(side up to 11 at Z-16.9, retract to 10.5,-16.4. Then up to A's level, along it to Z5,)
(the P block's rapid to 10,2.1, the shifted profile, and back to A along the bore.)
%
O0012
G21 G99
T0101
G97 S800 M03
G00 X20. Z5.
G71 U1. R0.5
G71 P10 Q20 U0. W0.1 F0.15
N10 G00 X20. Z2.
G01 Z-5. F0.1
X26. Z-8.
Z-15.
X20. Z-18.
N20 Z-25.
G70 P10 Q20
G00 X200. Z100.
M30
%
