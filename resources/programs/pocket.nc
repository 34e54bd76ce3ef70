%
(pocket.nc: a circular pocket 20 mm across and 1 mm deep, helical entry, G03 with I/J)
G21 G17 G90 G94 G54
M03 S8000
G00 Z5
G00 X2 Y0
G01 Z0 F300
(helical entry, two full turns down to Z-1)
G03 X2 Y0 Z-0.5 I-2 J0 F900
G03 X2 Y0 Z-1.0 I-2 J0
G03 X2 Y0 I-2 J0
(widen the pocket in rings)
G01 X5 Y0
G03 X5 Y0 I-5 J0
G01 X8 Y0
G03 X8 Y0 I-8 J0
G01 X10 Y0
G03 X10 Y0 I-10 J0
G00 Z5
G00 X0 Y0
M05
M30
%
