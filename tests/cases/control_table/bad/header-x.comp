nominal forward reverse
0.0 0.002 -0.002
10.0 0.001 -0.003
