(G71 with B180: the infeed angle must be 0 <= B < 180.)
G97 S400 M03
G00 X24 Z5
G71 X18.16 Z-25 B180 D0.4 U0.1 H1.84 F1.5 M32 M73
M02
