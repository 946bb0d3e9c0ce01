(Issue 27: `Z-20` without its point reads -0.020 mm: the line after the ,C2. corner runs)
(back toward the face, and the corner does not fit between the lines. The error is said)
(at the word, with the corner as a second label, not as "make `,C` smaller".)
O0005
G21 G99
T0101
G96 S180 M03
G50 S2000
G00 X20. Z2.
G01 Z0. F0.2
X30.,C2.
Z-20
X50.
G00 X100. Z100.
M30
