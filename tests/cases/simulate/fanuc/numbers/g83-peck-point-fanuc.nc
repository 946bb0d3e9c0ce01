(Issue 27: G83's peck Q counts least increments without a point [Q3000 is 3 mm]. With a)
(point, Q3. is 3 mm where the control takes it; whether a Fanuc lathe does is not)
(verified [grammar/fanuc.toml cites what was reached], so it is a warning with both)
(readings, not an error, and the holes are drilled in 3 mm pecks.)
O0007
G21 G98
T0101
G97 S1200 M03
G00 X0. Z5.
G83 Z-10. R-2. Q3. F100.
G80
G00 X100. Z100.
M30
