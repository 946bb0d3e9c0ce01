(G42 switched on in the block before an arc: tool 2, nose radius 0.4 mm, tip 3; reference)
(= nose centre less 0.4 in X and Z. Points are X as radius, Z. The start-up G01 Z0 ends)
(perpendicular to the R2 rounding, G03 about 8/-2, at its start 8/0, that is 0.4 out)
(along its radius: centre 8/0.4, reference X7.6 Z0. The nose runs outside the rounding on)
(radius 2.4 to 10.4/-2: reference X10 Z-2.4, centre X7.6 Z-2.4. Z-20 joins tangentially)
(and ends at 10.4/-20: reference X10 Z-20.4; G40 leaves to X15 Z5.)
%
O0105
G21 G99
T0202
G97 S1000 M03
G00 X16. Z5.
G42 G01 Z0. F0.1
G03 X20. Z-2. R2.
G01 Z-20.
G40 G00 X30. Z5.
G00 X200. Z100.
M30
%
