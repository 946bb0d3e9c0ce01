$LAPE2.MIN%
(A LAP contour with no G80: the call cannot read it, and the control stops there.)
G00 X62 Z2 T010101
G97 S800 M03
G85 NLAP1 D4 F0.3 U0.4
NLAP1 G81
G00 X30
G01 Z-20 F0.15
X60
G00 X200 Z100
M02
