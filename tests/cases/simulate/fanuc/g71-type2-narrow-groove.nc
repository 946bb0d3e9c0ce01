(G71 Type II with a groove 0.6 mm wide and a retract R1: from the groove the tool retracts)
(at 45 degrees only as far as the groove is wide, not 1 mm into its near wall.)
(Hand check, radius, no allowance: A = 25, 2. Profile 23,2 -> 23,-10 -> 20,-10 -> 20,-10.6)
(-> 23,-10.6 -> 23,-20 -> 25,-20. U1.5: levels at 23.5, 22 and 20.5; 19 is below the groove)
(bottom. Level 23.5 cuts Z2 to Z-20 and retracts 1 to 24.5,-19. Level 22 cuts the groove from)
(Z-10 to Z-10.6, follows the far wall and the land up to 23.5 at Z-20, retracts 1 to)
(24.5,-19. Level 20.5: over at 24.5, rapid down to 23, feed to 20.5, cut to Z-10.6, up the)
(far wall to 22, then retract 0.6, the groove's width, to 22.6,-10 and no further: the near)
(wall's corner is at 23,-10. Then up to A's level and the profile from 23,2.)
%
O0016
G21 G99
T0101
G97 S800 M03
G00 X50. Z2.
G71 U1.5 R1.
G71 P10 Q20 U0. W0. F0.2
N10 G00 X46. Z2.
G01 Z-10. F0.1
X40.
Z-10.6
X46.
Z-20.
N20 X50.
G70 P10 Q20
G00 X200. Z100.
M30
%
