(OSP automatic chamfer G75 and rounding G76 between two G01 moves, at 0.2 mm/rev and 500 rpm.)
(Hand check: from X20 Z2, G01 Z0 then G75 X40 L1: the face to r20 Z0 with a 1 mm chamfer:)
(  line to r19 Z0, chamfer to r20 Z-1, then G01 Z-20 on to r20 Z-20.)
(G76 X60 L2 at Z-20: line to r28 Z-20, round R2 about r28 Z-22 to r30 Z-22, then Z-40.)
G97 S500 M03
G00 X20 Z2
G01 Z0 F0.2
G75 G01 X40 L1
G01 Z-20
G76 G01 X60 L2
G01 Z-40
G00 X200 Z100
M02
