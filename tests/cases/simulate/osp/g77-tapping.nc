(G77 right-hand tapping, M8x1.25, from X0 Z10 at 300 rpm.)
(Hand check: rapid K5 to Z5, tap to Z-15 at 1.25 x 300 = 375 mm/min: 20 mm in 3.2 s, dwell 0.3 s,)
(tap back to Z5 in 3.2 s, rapid to Z10. The tap's moves follow the spindle: expand keeps G77, with a note.)
(G78, left-hand, makes the same moves.)
G97 S300 M03
G00 X0 Z10
G77 X0 Z-15 K5 F1.25 E0.3
G00 X0 Z10 M04
G78 X0 Z-15 K5 F1.25
G00 X200 Z100
M02
