(G88 along a contour with an arc: arc threading is an option this simulation does not have.)
G97 S400 M03
G00 X30 Z5
G88 NTH1 D0.4 H1.2 B60 F1.5 M32 M73
NTH1 G81
G00 X20 Z2
G01 Z-10
G02 X24 Z-12 K-2
G80
M02
