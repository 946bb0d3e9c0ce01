(G71 with D0: no first depth, no passes.)
G97 S400 M03
G00 X24 Z5
G71 X18.16 Z-25 B60 D0 U0.1 H1.84 F1.5 M32 M74
M02
