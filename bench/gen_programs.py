"""Generate the paper's three experiment programs (Table in METHOD.md section 1), our own:

* sphere roughing: about 1,500 lines, about 500 of them G02/G03 (concentric full circles at
  Z levels down a hemisphere, G01 step-overs between them), about 3 million set-points;
* sphere finishing: about 35,000 lines of short G01 chords along parallels of a
  hemisphere (a CAM-style contour finish), about 5.4 million set-points;
* sphere finishing with helical arcs: about 35,000 lines of G03 helical arcs spiralling up
  a hemisphere (a CAM-style spiral finish with arc fitting) at F900, about 87 minutes of
  motion, 5.2 million set-points;
* circular pocket: about 1,200 lines, rings of G03 half circles (I/J) with G01 step-overs
  and helical entries, about 1.2 million set-points.

At F1800 (30 mm/s, the paper's Vmax), the helical finish at F900.
``python -m bench.gen_programs OUTDIR`` writes sphere_roughing.nc, sphere_finishing.nc,
sphere_helical.nc, circular_pocket.nc.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

__all__ = ["circular_pocket", "sphere_finishing", "sphere_helical", "sphere_roughing", "write_all"]

HEADER = ["%", "G21 G17 G90 G94 G54", "M03 S12000", "G00 Z5"]
FOOTER = ["G00 Z5", "M05", "M30", "%"]


def _f(x: float) -> str:
    s = f"{x:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def sphere_finishing(radius: float = 60.0, chord_mm: float = 3.5, stepover_mm: float = 0.19) -> str:
    """Contour finish of a hemisphere: parallels as G01 chords, a G01 step between them."""
    out = list(HEADER)
    levels = int((math.pi / 2 * radius) / stepover_mm)
    first = True
    for i in range(levels):
        phi = (i + 0.5) / levels * (math.pi / 2)  # latitude from the equator up
        r = radius * math.cos(phi)
        z = radius * math.sin(phi) - radius
        n = max(8, int(round(2 * math.pi * r / chord_mm)))
        if first:
            out += [f"G00 X{_f(r)} Y0", f"G01 Z{_f(z)} F600"]
            first = False
        else:
            out.append(f"G01 X{_f(r)} Y0 Z{_f(z)}")
        for k in range(1, n + 1):
            a = 2 * math.pi * k / n
            line = f"X{_f(r * math.cos(a))} Y{_f(r * math.sin(a))}"
            out.append(("G01 " + line + " F1800") if k == 1 else line)
    return "\n".join(out + FOOTER) + "\n"


def sphere_helical(radius: float = 60.0, turns: int = 318, arcs_per_turn: int = 110,
                   feed_mm_min: float = 900.0) -> str:
    """Spiral finish of a hemisphere from the equator up: G03 helical arcs (R form), each a
    fraction of a turn at the radius of its middle, dropping in Z as the spiral climbs the
    latitude; consecutive arcs meet at a slight kink where the radius changes."""
    out = list(HEADER)
    n = turns * arcs_per_turn
    out += [f"G00 X{_f(radius)} Y0", "G01 Z0 F600"]

    def point(k: int) -> tuple[float, float, float, float]:
        phi = k / n * (math.pi / 2) * 0.98           # latitude, short of the pole
        a = 2 * math.pi * k / arcs_per_turn
        r = radius * math.cos(phi)
        return r * math.cos(a), r * math.sin(a), radius * math.sin(phi), r

    for k in range(1, n + 1):
        x, y, z, _ = point(k)
        r_mid = point(k)[3] * 0.5 + point(k - 1)[3] * 0.5
        words = f"G03 X{_f(x)} Y{_f(y)} Z{_f(z)} R{_f(r_mid)}"
        out.append(words + (f" F{feed_mm_min:g}" if k == 1 else ""))
    return "\n".join(out + FOOTER) + "\n"


def sphere_roughing(radius: float = 28.0, levels: int = 166, rings: int = 3,
                    ring_mm: float = 3.0) -> str:
    """Roughing around a hemisphere: per Z level three G03 full circles (I/J) from the outside
    in, down to 0.5 mm above the sphere, G01 step-overs between them."""
    out = list(HEADER)
    for i in range(levels):
        z = -radius * (i + 1) / levels
        sphere_r = math.sqrt(max(radius * radius - (radius + z) ** 2, 0.0))
        r = sphere_r + 0.5 + ring_mm * (rings - 1)
        out += [f"G00 X{_f(r)} Y0", f"G00 Z{_f(z + 1.0)}", f"G01 Z{_f(z)} F600"]
        for k in range(rings):
            if k:
                r -= ring_mm
                out.append(f"G01 X{_f(r)} Y0 F1800")
            out.append(f"G03 X{_f(r)} Y0 I{_f(-r)} J0" + ("" if k else " F1800"))
        out.append("G00 Z5")
    return "\n".join(out + FOOTER) + "\n"


def circular_pocket(radius: float = 17.0, depth: float = 17.0, dz: float = 0.5,
                    stepover: float = 1.0) -> str:
    """Circular pocket: per Z level a helical entry, then G03 full-circle rings (I/J) with
    G01 step-overs between them."""
    out = list(HEADER)
    out += ["G00 X1 Y0", "G01 Z0 F600"]
    z = 0.0
    while z > -depth + 1e-9:
        z -= dz
        out.append(f"G03 X1 Y0 Z{_f(z)} I-1 J0 F900")  # helical entry, one turn
        r = 1.0
        while r + stepover <= radius:
            r += stepover
            out.append(f"G01 X{_f(r)} Y0 F1800")
            out.append(f"G03 X{_f(r)} Y0 I{_f(-r)} J0")
        out.append("G00 Z5")
        out.append("G00 X1 Y0")
        out.append(f"G01 Z{_f(z)} F600")
    return "\n".join(out + FOOTER) + "\n"


PROGRAMS = {
    "sphere_roughing": sphere_roughing,
    "sphere_finishing": sphere_finishing,
    "sphere_helical": sphere_helical,
    "circular_pocket": circular_pocket,
}


def write_all(outdir: str | Path) -> dict[str, Path]:
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    paths = {}
    for name, gen in PROGRAMS.items():
        p = outdir / f"{name}.nc"
        p.write_text(gen(), encoding="utf-8")
        paths[name] = p
    return paths


if __name__ == "__main__":
    for name, path in write_all(sys.argv[1] if len(sys.argv) > 1 else "out/programs").items():
        print(name, path, sum(1 for _ in path.open()))
