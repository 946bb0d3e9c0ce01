$LAPE1.MIN%
(A LAP call naming no contour: NLAP9 names no block; N0100 names a block that does not)
(start a contour, which the diagnostic points at. Both calls are skipped.)
G00 X62 Z2 T010101
G97 S800 M03
G85 NLAP9 D4 F0.3
N0100 G00 X62 Z5
G85 N0100 D4 F0.3
G00 X200 Z100
M02
