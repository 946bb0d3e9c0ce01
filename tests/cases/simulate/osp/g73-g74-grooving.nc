(G73 grooving in X and G74 face cutting and peck drilling in Z, at 800 rpm.)
(N1, like OSP7000L's, from X52 Z-10 = r26: plunges at Z-10, Z-7.21 by K2.79, and Z-6.9, the end.)
(   each: D4 dia = 2 radius pecks over 2.5: feed r24 at 80 mm/min = 1.5 s, rapid back 0.1 to r24.1,)
(   feed r23.5, dwell 0.14 s, rapid r26; after the last plunge rapid back to S.)
(N2 from X52 Z-20, one plunge to X40 = r20: pecks of D2 = 1, clearing every L3 = 1.5, DA=0.5 = 0.25 back:)
(   feed r25, rapid r25.25, feed r24, clear: rapid r26 then r24.25, feed r23, rapid r23.25,)
(   feed r22, clear: rapid r26 then r22.25, feed r21, rapid r21.25, feed r20, rapid r26.)
(N3 G74 peck drill from X0 Z5 to Z-12, D3: Z2, back to Z2.1, Z-1, Z-0.9, Z-4, Z-3.9, Z-7, Z-6.9,)
(   Z-10, Z-9.9, Z-12, rapid Z5 at 0.12 x 800 = 96 mm/min.)
(N4 G74 face groove from X40 Z2 to X30 Z-3, I4 = 2 radius steps: r20 r18 r16 r15;)
(   each: Z0, Z0.1, Z-2, Z-1.9, Z-3, dwell 0.5 s, rapid Z2; then back to S.)
G50 S2000
G97 S800 M03
G00 X52 Z-10
N1 G73 X47 Z-6.9 K2.79 D4 L12.4 F0.1 E0.14
G00 Z-20
N2 G73 X40 Z-20 D2 L3 DA=0.5 F0.1
G00 X0 Z5
N3 G74 X0 Z-12 D3 F0.12
G00 X40 Z2
N4 G74 X30 Z-3 I4 D2 E0.5 F0.08
G00 X200 Z100
M02
