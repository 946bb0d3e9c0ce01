(turnpass: dialect=fanuc)
(An axis given both as a position and as a distance in one block: refused, the error on the)
(second word. A G65 call's X and U are arguments and stay valid.)
G00 X30. Z2.
W110 G02 X19. Z-73.602 R30. F0.1
G01 X20. U2. F0.1
G00 U4. Z5. X40.
G01 Y1. V1.
G65 P9001 X10. U2. Z3. W4.
M30
