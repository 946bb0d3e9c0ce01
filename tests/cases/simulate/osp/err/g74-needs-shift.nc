(G74 from X40 to X30 with no I to step there.)
G97 S800 M03
G00 X40 Z2
G74 X30 Z-3 D2 F0.08
M02
