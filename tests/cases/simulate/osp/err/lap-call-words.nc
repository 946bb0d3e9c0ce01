$LAPE4.MIN%
(Call words the control rejects: G85 without D and G86 without D, D0, a negative U,)
(and S, T or M words in a LAP call block; M85 is the one M code a roughing call takes.)
G00 X62 Z2 T010101
G97 S800 M03
NLAP1 G81
G00 X30
G01 Z-20 F0.15
X60
G80
G85 NLAP1 F0.3
G86 NLAP1 F0.3
G85 NLAP1 D0 F0.3
G85 NLAP1 D4 F0.3 U-0.4
G85 NLAP1 D4 F0.3 S500
G86 NLAP1 D4 F0.3 T020202
G87 NLAP1 M08
G85 NLAP1 D4 F0.3 M85
G00 X200 Z100
M02
