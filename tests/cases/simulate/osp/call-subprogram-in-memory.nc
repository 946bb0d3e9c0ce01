$CALLS.MIN%
(CALL OCHEK and CALL OSETZ name subprograms the control keeps in its memory, as in)
(OSP7000L.nc: no program fault. Each is a warning that names it, and the run goes on:)
(hand check: from home X300 Z200 a rapid to X100 Z5, the two calls add nothing, then a cut)
(to Z-20 at F0.2 and 500 rpm, 25 mm in 15 s, and a rapid back home.)
G50 S2000
G97 S500 M03
G00 X100 Z5
CALL OCHEK
CALL OSETZ DRIV=88.5
G01 Z-20 F0.2
G00 X300 Z200
M02
