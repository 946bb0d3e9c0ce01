(Thesis Table 7: the 25.4 mm radius quarter arc of Table 6, from X 25.4 Z 0 to X 0 Z 25.4)
(radius, about the origin, written as a metric program on the diameter: X50.8 is radius 25.4.)
(Compensate it with examples/machines/thesis-table6.toml and --strategy circle.)
%
O0007
G21 G99
T0404
G97 S500 M03
G00 X60. Z5.
X50.8 Z1.
G01 Z0. F0.1
G02 X0. Z25.4 I-25.4 K0.
G00 X60. Z30.
M30
%
