$LAPE3.MIN%
(A G85 contour that turns back in Z, an undercut: G85 cannot follow it; an arc that)
(bulges back past its end points along Z counts too: G03 X40 Z-10 I2.5 from X30 Z-10)
(reaches Z-7.5. G87 may finish such a contour.)
G00 X62 Z2 T010101
G97 S800 M03
NLAP1 G81
G00 X30
G01 Z-20 F0.15
X40 Z-15
Z-40
X60
G80
NLAP2 G81
G00 X30
G01 Z-10 F0.15
G03 X40 Z-10 I2.5
G01 Z-40
X60
G80
G85 NLAP1 D4 F0.3
G85 NLAP2 D4 F0.3
G87 NLAP1
G00 X200 Z100
M02
