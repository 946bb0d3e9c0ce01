(Fanuc chamfer `,C`, corner rounding `,R` and direct drawing dimension `,A` in G01 blocks.)
(Hand check, radii: from r10 Z0, X26.,C1. faces to r13 with a 1 mm chamfer: line to r12 Z0,)
(chamfer to r13 Z-1; Z-10.,R2. turns to Z-10 with a R2 round: line to r13 Z-8, arc about)
(r15 Z-8 to r15 Z-10; X34. faces on to r17 Z-10; X44.,A45 climbs at 45 degrees from +Z: to)
(r22 Z-5, the line's end Z from the angle; G00 X60.,A90 rapids straight up in X.)
%
O0001
G21 G99
T0101
G50 S2000
G97 S1000 M03
G00 X20. Z2.
G01 Z0. F0.2
X26.,C1.
Z-10.,R2.
X34.
X44.,A45
G00 X60.,A90
G00 X200. Z100.
M30
%
