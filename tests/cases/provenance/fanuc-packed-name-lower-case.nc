O2012(Turn/Face)N1
(Reconstructed from the printed copy)
G21 G99
G00 X20. Z2.
M30
