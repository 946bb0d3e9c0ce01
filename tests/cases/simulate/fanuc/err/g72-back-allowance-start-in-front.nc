(A G72 with W-0.1, the allowance of a cut from the -Z side, facing a back face from Z1, in)
(front of the part: seen from there the profile falls in Z, which G72 rejects. The error)
(names the start point and the fix: behind the profile, at Z-38.1 or less, the profile's)
(smallest Z, Z-38, with W-0.1; from there the same profile rises toward the start point.)
%
O0023
G21 G99
T0101
G97 S700 M03
G00 X82. Z1.
G72 W1.5 R0.3
G72 P10 Q20 U0.2 W-0.1 F0.2
N10 G00 Z-30.
G01 X60. F0.1
X40. Z-34.
X20.
N20 Z-38.
G70 P10 Q20
G00 X200. Z100.
M30
%
