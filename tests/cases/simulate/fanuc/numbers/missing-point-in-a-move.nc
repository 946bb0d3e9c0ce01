(Issue 27: on a control that counts least increments, `X32` is 0.032 mm. The rapid to)
(X32 Z-20. runs to the centre line at Z-20, through the part; `X32.` was meant.)
(The program writes its lengths with points, so its X positions are 32-100 mm: X32 reads)
(1000 times below them. One warning at the word, with both readings and the fix.)
O0001
G21 G99
T0101
G96 S180 M03
G50 S2000
G00 X40. Z2.
G01 Z0. F0.2
X32.
G00 X32 Z-20.
G01 X40. F0.2
G00 X100. Z100.
M30
