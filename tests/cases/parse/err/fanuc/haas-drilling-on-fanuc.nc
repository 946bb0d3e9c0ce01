(A Haas drilling block read on a Fanuc control: G81 is no Fanuc lathe code, and the hint)
(names the Haas setting, not only Okuma's LAP contour.)
%
O0001
G00 X0. Z5.
G81 Z-10. R2. F0.1
G80
M30
%
