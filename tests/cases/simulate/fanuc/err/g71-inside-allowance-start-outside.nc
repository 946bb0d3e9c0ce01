(An inside G71, allowance U-1, started outside the part at X60 Z2, as a student program in)
(the corpus does: seen from X60 the bore profile, X40 at the mouth down to X20, is an)
(outside shape that is not monotonic, and the control alarms. The error names the start)
(point and the fix: inside the bore, at X19 or less, the profile's smallest X, X20, with)
(U-1; from there the same profile is a plain inside Type I shape that N20 Z2. leaves.)
%
O0022
G21 G99
T0101
G97 S800 M03
G00 X60. Z2.
G71 U1. R0.5
G71 P10 Q20 U-1. W0.1 F0.2
N10 G00 X40.
G01 Z-10. F0.1
X30. Z-15.
Z-25.
X20.
N20 G00 Z2.
G70 P10 Q20
G00 X200. Z100.
M30
%
