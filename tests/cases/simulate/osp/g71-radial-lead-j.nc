(G71 with radial infeed B0, lead F3 J2 = 1.5, its own S300, and M22 in the block after an M23.)
(Hand check: the G33 before it chamfers, one lead: r9.5 to Z-23.5, then r11 Z-25.)
(G71: M73 D0.6, H 1.84, no U: 0.6 1.2 1.8, then 1.84; r9.7 9.4 9.1 9.08 at Z5, no shift with B0.)
(Thread at 1.5 x 300 = 450 mm/min, 30 mm in 4 s; M22 in the block ends chamfering, so no chamfer,)
(and the G33 after it has none either. expand copies F3 J2 and S300 onto each pass and writes M22,)
(since the program turns chamfering on elsewhere.)
G50 S2000
G97 S400 M03
G00 X24 Z5
M23
G33 X19 Z-25 F1.5
G71 X18.16 Z-25 B0 D0.6 H1.84 F3 J2 S300 M22 M73
G33 X18.16 Z-25 F1.5
G00 X200 Z100
M02
