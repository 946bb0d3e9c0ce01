(G71 with no thread height H: the control rejects it, the parser already.)
G97 S400 M03
G00 X24 Z5
G71 X18.16 Z-25 B60 D0.4 U0.1 F1.5 M32 M73
M02
