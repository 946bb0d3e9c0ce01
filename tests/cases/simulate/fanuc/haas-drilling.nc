(Haas lathe drilling cycles G81-G89; grammar/fanuc.toml takes words and motion from the Haas)
(lathe manual's G-code chapter, not re-read here. R is the R plane's position, Z2; each)
(hole returns to the start, Z5. G81 drills, G82 dwells P0.5 s at the bottom, G83 Q5. pecks)
(out to R after each 5 mm and back to 1.27 mm above the last depth, Setting 22; G83 I6. J2.)
(K3. pecks 6, 4, 3, 3 ... mm, G84 taps at F1.5 per revolution, G85 bores in and out at the)
(feed, G86 rapids out, G87 stops for a manual retract, warned; G89 dwells and feeds out.)
%
O0001
G21 G99
T0202
G97 S800 M03
G00 X0. Z5.
G81 Z-10. R2. F0.1
G82 Z-10. R2. P0.5 F0.1
G83 Z-20. R2. Q5. F0.1
G83 Z-20. R2. I6. J2. K3. F0.1
G84 Z-12. R2. F1.5
G85 Z-10. R2. F0.08
G86 Z-10. R2. F0.08
G87 Z-10. R2. F0.08
G89 Z-10. R2. P0.3 F0.08
G80
G00 X200. Z100.
M30
%
