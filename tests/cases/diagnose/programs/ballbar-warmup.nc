(Ball bar test repeated over a warm-up: the 50 mm circle G03 then G02, four times,)
(15 minutes apart, G04 X900. being 900 s. The bar stays mounted: one set-up for all.)
G21 G98
T0100
G00 X100. Z5.
G01 X100. Z0. F500.
G03 X100. Z0. I0. K-50. F1000.
G02 X100. Z0. I0. K-50.
G04 X900.
G03 X100. Z0. I0. K-50.
G02 X100. Z0. I0. K-50.
G04 X900.
G03 X100. Z0. I0. K-50.
G02 X100. Z0. I0. K-50.
G04 X900.
G03 X100. Z0. I0. K-50.
G02 X100. Z0. I0. K-50.
G00 X150. Z20.
M30
