$LAPF.MIN%
(G87 finishing: the contour as written, with its own F, S, G42 and G40; no return.)
(Tool 3 has no entry in the tool table, so compensation moves nothing: the moves are the)
(programmed contour. First call, longitudinal, first block G00: from X40 Z3 rapid X16,)
(G01 Z0 at F0.1, X20 Z-2, Z-15, G02 fillet to X26 Z-18 about X26 Z-15, X34 at S250,)
(X38 Z-20, X42, where the tool stays: the contour right after the call is consumed.)
(Second call, transverse, first block G01: from X60 Z5 fed to Z0 at F0.15, X20, X16 Z2,)
(where the tool stays.)
G50 S3000
G00 X40 Z3 T030303
G96 S200 M03
G87 NFIN1
NFIN1 G81
G00 X16
G01 Z0 G42 F0.1
X20 Z-2
Z-15
G02 X26 Z-18 I3
G01 X34 S250
X38 Z-20
G40 G01 X42
G80
G00 X60 Z5
G87 NFIN2
NFIN2 G82
G01 Z0 F0.15
X20
X16 Z2
G80
G00 X200 Z100
M02
