(turnpass: dialect=fanuc)
N10 G92 S3000
N20 G00 X10. Z2.
N30 M30
