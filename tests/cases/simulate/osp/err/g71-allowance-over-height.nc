(G71 with pattern 2 M74 and U 2 larger than H 1.84: H - U < 0, the control rejects it.)
G97 S400 M03
G00 X24 Z5
G71 X18.16 Z-25 B60 D0.4 U2 H1.84 F1.5 M32 M74
M02
