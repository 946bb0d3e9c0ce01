(G71 with pattern 1 M73 and H - U = 1.84 - 0.9 = 0.94 less than D = 1: the control rejects it.)
G97 S400 M03
G00 X24 Z5
G71 X18.16 Z-25 B60 D1 U0.9 H1.84 F1.5 M32 M73
M02
