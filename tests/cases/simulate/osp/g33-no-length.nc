(A G33 pass whose end Z is its start Z: it plunges and backs out, and cuts no thread.)
G97 S400 M03
G00 X24 Z5
G33 X23.2 Z5 F1.5
G00 X100 Z100
M02
