(Issue 27: with no decimal_input in the settings the program is read with calculator)
(input, the default: X32 is 32 mm. On a control that counts least increments it would be)
(0.032 mm; the words that would then read implausibly are counted, and said once.)
O0010
G21 G99
T0101
G96 S180 M03
G50 S2000
G00 X40. Z2.
G01 Z0. F0.2
X32.
G00 X32 Z-20.
G01 X40 F0.2
G00 X100. Z100.
M30
