(A ball bar test on the thesis lathe: the 100 mm bar of the thesis' Table 4, in the XZ)
(plane, its pivot at X200 Z-100 on the diameter, so the circle is about x 100 z -100 as a)
(radius. One turn G03 then one turn G02 at 1000 mm/min from the top of the circle.)
(Metric blocks on the inch machine: G21 selects millimetres for this program.)
G21 G98
T0400
G00 X200. Z5.
G01 X200. Z0. F500.
G03 X200. Z0. I0. K-100. F1000.
G02 X200. Z0. I0. K-100.
G00 X250. Z20.
M30
