(G71 whose profile ends on a land at the stock diameter, X50 from Z-15 to Z-25, the start)
(point's X: with U0.4 the shifted land lies 0.2 above A. After the final pass the tool goes)
(back along the shifted land's level to A's Z and only then down to A, not in a straight)
(line that would cut 0.2 deep into the shifted land.)
(Hand check, radius: A = 25, 2. Shape with U0.4: 20.2,2 -> 20.2,-10 -> 25.2,-15 -> 25.2,-25.)
(U2 R0.5: levels at 23 and 21; 19 is below 20.2. Level 23 cuts Z2 to the taper at Z-12.8;)
(level 21 to Z-10.8. Final pass from 20.2,2 to 25.2,-25, rapid to 25.2,2, rapid to 25,2.)
%
O0017
G21 G99
T0101
G97 S800 M03
G00 X50. Z2.
G71 U2. R0.5
G71 P10 Q20 U0.4 W0. F0.2
N10 G00 X40.
G01 Z-10. F0.1
X50. Z-15.
N20 Z-25.
G70 P10 Q20
G00 X200. Z100.
M30
%
