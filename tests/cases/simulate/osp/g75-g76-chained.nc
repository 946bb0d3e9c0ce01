(OSP automatic corners block after block, as the manual's example chains them: each corner)
(block completes the corner before it and waits for the next line in its turn.)
(Hand check, radii: from r10 Z0, G75 X40 L1 faces to r20 with a 1 mm chamfer; G76 Z-20 L2)
(turns down Z with a R2 round before the next face; G75 X60 L1 faces to r30 with a chamfer)
(before the final Z-40: line r19 Z0, chamfer r20 Z-1, line r20 Z-18, arc about r22 Z-18 to)
(r22 Z-20, line r29 Z-20, chamfer r30 Z-21, line r30 Z-40.)
G97 S500 M03
G00 X20 Z2
G01 Z0 F0.2
G75 G01 X40 L1
G76 G01 Z-20 L2
G75 G01 X60 L1
G01 Z-40
G00 X200 Z100
M02
