%
(fig7_circle.nc: five G02 R-form arcs followed by a G01, in the G17 plane, as in the)
(paper's Fig. 7. The joint speeds follow Table 3 in paper mode; the G02 to G01 joint stops.)
G21 G17 G90 G94
G00 X0 Y0 Z0
G02 X20 Y0 R10 F1800
G02 X30 Y-10 R10
G02 X20 Y-20 R10
G02 X0 Y-20 R10
G02 X-10 Y-10 R10
G01 X0 Y0
M30
%
