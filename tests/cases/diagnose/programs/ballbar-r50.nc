(Ball bar test on the lathe: a 50 mm bar in the XZ plane, pivot at X100 Z-50 on the)
(diameter, so the circle is about x 50 z -50 as a radius; it starts at the top, angle 0.)
(One turn G03 then one turn G02 at 1000 mm/min: each 18.85 s.)
G21 G98
T0100
G00 X100. Z5.
G01 X100. Z0. F500.
G03 X100. Z0. I0. K-50. F1000.
G02 X100. Z0. I0. K-50.
G00 X150. Z20.
M30
