$LAPE6.MIN%
(The AP start point inside the contour plus allowance: X30.2 lies below the contour)
(start X30 + U0.4; a pass would cut into the part.)
G00 X30.2 Z2 T010101
G97 S800 M03
G85 NLAP1 D4 F0.3 U0.4
NLAP1 G81
G00 X30
G01 Z-20 F0.15
X60
G80
G00 X200 Z100
M02
