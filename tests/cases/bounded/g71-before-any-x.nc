(G71 before the tool's X is known: the machine file gives no home and no block before the)
(cycle names X, so the cycle cannot be simulated and moves nothing, with a note. Its profile)
(N10-N20 is still the cycle's: it is not run as plain moves, and the run goes on after N20.)
O0071
G21 G99
T0101
G97 S800 M03
G00 Z2.
G71 U1.5 R0.5
G71 P10 Q20 U0.4 W0.1 F0.25
N10 G00 X20.
G01 Z-15. F0.1
X32. Z-25.
N20 X44.
G70 P10 Q20
G00 X120. Z80.
M30
