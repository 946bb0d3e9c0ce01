$LAPE5.MIN%
(G84 condition changes the control rejects: for an outside cut from X62 the points)
(must fall, X62 > XA= > XB=; XA=70 lies behind the start, XB=50 behind XA=40; a)
(longitudinal G81 contour takes no ZA=/ZB=; DA=0 is no depth.)
G00 X62 Z2 T010101
G97 S800 M03
NLAP1 G81
G00 X30
G01 Z-20 F0.15
X60
G80
G85 NLAP1 D4 F0.3
$ G84 XA=70 DA=2
G85 NLAP1 D4 F0.3
$ G84 XA=40 DA=2
$ XB=50 DB=1
G85 NLAP1 D4 F0.3
$ G84 ZA=-10 DA=2
G85 NLAP1 D4 F0.3
$ G84 XA=40 DA=0
G00 X200 Z100
M02
