(Issue 27: every decimal point in a word the control counts is an error whose hint and)
(quick fix give the word meant, from what the word counts: G76's height and first depth)
(in least increments [P0.92 is P920, 0.92 mm], its minimum depth [Q80. as a length would)
(be 80 mm, so it is Q80 with a stray point], a dwell in milliseconds [P0.3 is P300, or)
(X0.3], a sequence number [P100. is P100], and G74's peck in least increments [Q3. is)
(Q3000]. A Fanuc refuses the point in each: the block does not run.)
O0006
G21 G99
T0101
G97 S600 M03
G00 X30. Z5.
G76 P010060 Q80. R0.02
G76 X18.16 Z-25. P0.92 Q0.35 F1.5
G04 P0.3
G00 X0. Z2.
G74 R1.
G74 Z-20. Q3. F0.1
G70 P100. Q200
G00 X100. Z100.
M30
