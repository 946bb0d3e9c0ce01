(Fanuc G83 face drilling, words as cncprograming.blogspot.com "Drilling cycle G83 or G87")
(gives them from the 0i-T manual. From the initial level Z5 the drill rapids to the R point)
(3 mm nearer the part, Z2, feeds to Z-20, dwells P500 = 0.5 s, rapids back to Z5. With)
(Q5000, 5 mm in least increments, it pecks: 5 mm, back 1 mm, on: the high-speed peck of)
(parameter RTR = 0, the 1 mm standing in for parameter 5114. X20. alone drills the same hole)
(at X20. U10. K2 drills twice, 10 mm apart in X: at X30 and X40. G80 ends the cycle.)
%
O0001
G21 G99
T0202
G97 S800 M03
G00 X0. Z5.
G83 Z-20. R-3. P500 F0.1
G83 Z-20. R-3. Q5000 F0.1
X20.
G83 U10. Z-10. R-3. K2 F0.1
G80
G00 X200. Z100.
M30
%
