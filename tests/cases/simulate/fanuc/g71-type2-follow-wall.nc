(G71 Type II: a level that ends at a shoulder follows the shoulder up, along the diameter)
(beyond it and up the next wall to the previous level before it retracts.)
(Hand check, radius: A = 25, 2. Shape with U0.4: 15.2,2 -> 15.2,-10 -> 20.2,-10 -> 20.2,-20)
(-> 25.2,-20. U2 R0.5: levels at 23, 21, 19 and 17; 15 is below 15.2. Levels 23 and 21 cut)
(from Z2 to the last wall at Z-20. Level 19 cuts from Z2 to the shoulder at Z-10, then)
(follows it up to 20.2, along to Z-20 and up the wall to 21, and retracts to 21.5,-19.5.)
(Level 17 cuts to Z-10, follows the shoulder up to 19 and retracts to 19.5,-9.5. Then the)
(shifted profile from 15.2,2 and back to A. G70: the profile, back to A.)
%
O0013
G21 G99
T0101
G97 S800 M03
G00 X50. Z2.
G71 U2. R0.5
G71 P10 Q20 U0.4 W0. F0.2
N10 G00 X30. Z2.
G01 Z-10. F0.1
X40.
Z-20.
N20 X50.
G70 P10 Q20
G00 X200. Z100.
M30
%
