(turnpass: dialect=fanuc)
N10 /G00 X1. M08
N20/2G01 Z-1.
POPEN
DPRNT[X#1[44]*Z#2[53]]
PCLOS
M30
