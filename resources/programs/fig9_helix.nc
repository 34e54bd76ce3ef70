%
(fig9_helix.nc: six G03 half-circle R-form arcs with Z descending, a helix as in the paper's)
(Fig. 9. Every joint is tangent-continuous: the path speed stays at Vmax = 30 mm/s.)
G21 G17 G90 G94
G00 X10 Y0 Z0
G03 X-10 Y0 Z-1 R10 F1800
G03 X10 Y0 Z-2 R10
G03 X-10 Y0 Z-3 R10
G03 X10 Y0 Z-4 R10
G03 X-10 Y0 Z-5 R10
G03 X10 Y0 Z-6 R10
M30
%
