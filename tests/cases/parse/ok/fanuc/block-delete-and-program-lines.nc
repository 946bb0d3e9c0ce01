%O1200(TOKARKA)
O2012(Turn/Face)N1
/N10 G00 X10.
/2G00 X12.
G00X3.1Z.1/M08
G00 X1. Z2.;
T0505 ;bedame de 3mm
N99999 G01 Z-1.
N100000 G01 Z-2.
M30
%
trailing text after the closing percent is ignored by the control
