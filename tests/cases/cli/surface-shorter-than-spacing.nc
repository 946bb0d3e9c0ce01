(A finishing pass 0.46 mm long: shorter than a CMM profile's 0.5 mm spacing)
G21 G99
T0101
G97 S1000 M03
G00 X7. Z2.
G01 X4. Z0. F0.1
G01 X4.08 Z-0.46
G00 X5.08 Z5.
M30
