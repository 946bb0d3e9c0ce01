%
O1004 (FACE AND TURN)
N10 G21 G99
(turnpass 0.1.0 compensated, model test lathe, sha256 3e3e)
N20 G00 X51.982 Z1.994
N30 M30
%
