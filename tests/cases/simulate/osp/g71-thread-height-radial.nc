(Issue 27: an M20x1.5 thread with the height written as Fanuc's radial G76 height, H0.92.)
(OSP gives H, D and U of the G71 thread cycle as diameters [3277-E P-166...170; for G88)
(5238-E P-175]: H0.92 cuts 0.46 mm deep, half the 0.92 mm height of the thread, whose)
(height as a diameter is 2 x 0.6134 x 1.5 = 1.840. H is under 1.840 / sqrt 2 = 1.301, so)
(it reads as the radial height: a warning at H, whose fix writes H1.84. The passes are)
(those of the reading, as diameters: D0.35 a pass [M73] to H - U = 0.87, then U0.05:)
(0.35 0.70 0.87 0.92, X18.73 X18.38 X18.21 X18.16.)
G50 S2000
G97 S400 M03
G00 X24 Z5
G71 X18.16 Z-25 B60 D0.35 U0.05 H0.92 F1.5 M32 M73
G00 X200 Z100
M02
