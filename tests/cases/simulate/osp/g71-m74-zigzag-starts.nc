(G71 compound thread, infeed pattern 2 M74 constant area, zigzag M33, 2 starts Q2, chamfer M23 L1.)
(Hand check: root r9.08, H 1.84 dia, no U: no finishing pass, the last pass at H.)
(Passes at D x sqrt n, D 0.8: 0.8 1.131371 1.385641 1.6 1.788854, then 1.84 as n = 6 gives 1.9596.)
(Cut areas grow with the depth squared: every pass but the last removes D^2 = 0.64.)
(r = 9.08 + [1.84 - d]/2: 9.6 9.434315 9.307180 9.2 9.105573 9.08.)
(Zigzag alternates flanks from M32's: shift +0.300222 -0.204564 +0.131162 -0.069282 +0.014764 0.)
(Each depth twice, once per start, phase C0 and C180 in the expansion: 12 passes.)
(Lead 3: 900 mm/min at 300 rpm. Chamfer: thread to Z-24, then to r + 1 at Z-25.)
G50 S2000
G97 S300 M03
G00 X24 Z5
G71 X18.16 Z-25 B60 D0.8 H1.84 L1 F3 Q2 M33 M74 M23
G00 X200 Z100
M02
