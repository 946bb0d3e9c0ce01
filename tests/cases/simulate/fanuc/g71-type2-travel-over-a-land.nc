(G71 Type II with a land at the stock diameter, X50 from Z-5 to Z-10, the start point's X,)
(between the front and a groove: with U0.4 the shifted land lies 0.2 above A. Leaving the)
(groove for the final pass, the tool climbs to the shifted land's level, not to A's level,)
(which runs 0.2 deep through it.)
(Hand check, radius: A = 25, 2. Shape with U0.4: 22.2,2 -> 22.2,-5 -> 25.2,-5 -> 25.2,-10)
(-> 20.2,-10 -> 20.2,-15 -> 25.2,-15 -> 25.2,-20. U2 R0.5: levels at 23 and 21. Level 23)
(cuts Z2 to Z-5, follows the land's wall up to 25, retracts to 25.5,-4.5, cuts the groove)
(from Z-10 to Z-15, fed down from 25.5, follows its wall up to 25, retracts to 25.5,-14.5.)
(Level 21 cuts the groove, fed down from 23.5, follows up to 23, retracts to 23.5,-14.5.)
(Then up to 25.2, along it to Z2, the profile from 22.2,2, back along 25.2 and down to A.)
%
O0018
G21 G99
T0101
G97 S800 M03
G00 X50. Z2.
G71 U2. R0.5
G71 P10 Q20 U0.4 W0. F0.2
N10 G00 X44. Z2.
G01 Z-5. F0.1
X50.
Z-10.
X40.
Z-15.
X50.
N20 Z-20.
G70 P10 Q20
G00 X200. Z100.
M30
%
