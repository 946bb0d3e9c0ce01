(G71 pattern 3 M75 zigzag M33 where the control uses its own depths: a warning, D x sqrt n used.)
(Hand check: H 1.84, U 0.3, rough to 1.54. D^2 = 0.64 < H^2 - [H - U]^2 = 3.3856 - 2.3716 = 1.014.)
(Even passes at D x sqrt[n/2]: 0.8 1.131371 1.385641, then 1.54; odd passes halfway:)
(0.4 0.965685 1.258506 1.462820; finishing pass at 1.84: 9 passes.)
(r = 9.08 + [1.84 - d]/2: 9.8 9.6 9.517157 9.434315 9.370747 9.307180 9.268590 9.23 9.08.)
(Flanks alternate from M32's: shift +0.415692 -0.300222 +0.252393 -0.204564 +0.167863 -0.131162)
(+0.108882 -0.086603 0.)
G50 S2000
G97 S400 M03
G00 X24 Z5
G71 X18.16 Z-25 B60 D0.8 U0.3 H1.84 F1.5 M33 M75
G00 X200 Z100
M02
