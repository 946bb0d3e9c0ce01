(The common variables of machine-variables.nc, with their values in the machine settings:)
(`[machine] variables = { "#501" = 10.0, "#502" = 2.0 }`: X50 and Z-30, no warning.)
%
O0001
G21 G99
T0101
G97 S1000 M03
G00 X[#501+40.] Z2.
#100=#502+1.
G01 Z-[#100*10.] F0.2
G00 X100. Z100.
M30
%
