(As leohiei-projetocnc-1: G71 and G70 name P140 and Q220, but the profile's blocks carry)
(no sequence numbers. Each word that names no block is an error on that word: two on the)
(G71, two on the G70; neither cycle moves, and the rest of the program still runs.)
%
O0011
G21 G99
T0101
G97 S1000 M03
G00 X40. Z2.
G71 U2. R0.5
G71 P140 Q220 U0.4 W0.1 F0.25
G00 X20.
G01 Z-20.
X40.
G70 P140 Q220 F0.1
G00 X200. Z100.
M30
%
