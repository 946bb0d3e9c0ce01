$SYSVAR.MIN%
(VTOFX[6] is the tool offset table, machine state the simulation does not have: it reads as)
(0 with one warning where the program first reads it, however often it is read, as in)
(OSP7000L.nc. Hand check: rapid from home X300 Z200 to X100 Z5, cut to Z-20 at F0.2 and)
(500 rpm, 25 mm in 15 s, then VTOFX[6] read again in X=100+VTOFX[6], a rapid to X100 Z5.)
G50 S2000
G97 S500 M03
VTOFX[16]=VTOFX[6]
G00 X100 Z5
G01 Z-20 F0.2
G00 X=100+VTOFX[6] Z5
G00 X300 Z200
M02
