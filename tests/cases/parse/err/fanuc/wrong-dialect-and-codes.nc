(turnpass: dialect=fanuc)
G91 G01 U1.
G92 S3000
X=5.
V1=2
XA=60
CALL OSUB
G81
G85 X1.
M30
