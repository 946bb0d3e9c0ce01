(A profile written before its cycle and jumped over with GOTO: after the cycle the program)
(goes on after the G73 block, since N20 lies behind it; jumping back would run it forever.)
(Hand check: R2 passes, relief U2. = 2 mm radius, no allowance; A = X50 Z3, radius 25.)
(  pass 1 by 2, 0: rapid to radius 17 Z3, feed to Z-15, rapid out to radius 25, back to Z3;)
(  pass 2 by 0, on the profile: radius 15 Z3, Z-15, out to 25, back to Z3. Then X200 Z100.)
%
O0021
G21 G99
T0101
G97 S800 M03
GOTO 100
N10 G00 X30.
N20 G01 Z-15. F0.1
N100 G00 X50. Z3.
G73 U2. W0. R2
G73 P10 Q20 F0.2
G00 X200. Z100.
M30
%
