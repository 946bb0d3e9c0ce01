$LAPM.MIN%
(A contour defined before its calls, shared by G85 with M85 and G87 with another tool.)
(The contour stays in place and the flow skips it; neither call consumes it.)
(Hand check G85, radius: A = X62 Z2 = r31 Z2; contour start X30 at Z2; U0.4 W0)
(gives C0 = r15.2 Z2: the infeed line is Z2. D6 = r3 per pass: X56 X50 X44 X38 X32;)
(X26 is below X30.4: 5 passes. X56 = r28 is above the contour, largest X52.4: it cuts)
(to the contour end Z-40. The others meet the taper X30.4 Z-15 to X52.4 Z-25:)
(X50 at Z-23.9091, X44 at Z-21.1818, X38 at Z-18.4545, X32 at Z-15.7273.)
(M85: no return; the tool stays at X52.4 Z-40 and the program retracts itself.)
(G87 from X70 Z5 with T020202: G00 X30 at Z5, G01 Z-15 and X52 Z-25 at F0.2,)
(Z-40 at F0.1 S180, where the tool stays.)
NLAP1 G81
G00 X30
G01 Z-15 F0.2
X52 Z-25
Z-40 F0.1 S180
G80
G50 S2000
G00 X62 Z2 T010101
G96 S150 M03
G85 NLAP1 D6 F0.3 U0.4 M85
G00 X70
Z5
T020202
G87 NLAP1
G00 X200 Z100
M02
