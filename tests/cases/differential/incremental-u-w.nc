(U and W: incremental X, as a diameter, and Z, alone and mixed with absolute words.)
%
O1002
G21 G99
G97 S500 M03
G00 X60. Z5.
U-20. W-3.
G01 W-10. F0.15
U6. Z-20.
X46. W-5.
G02 U10. W-5. R5.
G01 W-10.
G03 X66. W-10. R10.
G00 U20. W30.
X100. Z50.
M30
%
