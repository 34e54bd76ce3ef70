"""Random programs mixing tools (G43, G43.1, G10 L1/L10), offsets (G10 L2 with rotation, G54/G55,
G92, G52, G53, G28/G30), cycles, subroutines, loops, conditions, parameters and expressions,
modal memory (M70/M72), curves (G05, G05.1, G05.2/G05.3), cutter compensation (G41.1/G42.1
and G41/G42 from the table), threads (G76, G33), arcs in
every plane with turns and absolute centres, inverse time, polar words, inch blocks, probes
(G38.2/G38.3) and input reads (M66 L0), read by
LinuxCNC's own interpreter (``rs274`` of Debian's linuxcnc-uspace 2.9.0~pre1) and by this one:
every motion call equal
(end points, arc centres and turns, in program coordinates), or both refuse the program."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.errors import ProgramError
from planner.core.machine import MachineSpec
from planner.core.tools import parse_tbl
from planner.gcode.interpreter import parse_program
from tools.against_linuxcnc import call_ends, close, without_short_moves
from tools.linuxcnc_oracle import RS274, motion_calls, project_motion, run_linuxcnc

pytestmark = pytest.mark.skipif(
    RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs Debian's linuxcnc-uspace "
                          "as root; or: apt-get install --no-install-recommends linuxcnc-uspace)")

TOOLS = parse_tbl("T1 P1 Z10 D6\nT2 P2 Z25.5 D3\nT3 P3 Z-4 D10\n")
SUB = "o100 sub\nG91 G1 X#1 Y#2\nG90\no100 endsub\n"
# digital input 0 for M66 (the stand-alone rs274 reads 0 from it, as the check assumes of L0)
MACHINE = replace(MachineSpec.default(), input_bits={0: (0, 16, "")})


def _n(v: float) -> str:
    return f"{v:.3f}"


@st.composite
def programs(draw) -> str:
    """A program of feature blocks; the generator keeps the program position (x, y, z) it left,
    so arcs and incremental words stay valid."""
    val = st.integers(-400, 400).map(lambda k: k / 10.0)
    x, y, z = 0.0, 0.0, 10.0
    out = [SUB, "G21 G17 G90 G94 G40 G49 G54 F600", f"G0 X0 Y0 Z{_n(z)}"]

    def goto() -> None:
        nonlocal x, y, z
        x, y, z = draw(val), draw(val), draw(st.integers(5, 30).map(float))
        out.append(f"G0 X{_n(x)} Y{_n(y)} Z{_n(z)}")

    kinds = draw(st.lists(st.sampled_from(
        ["line", "rapid", "arc", "inc", "tool", "offset", "g92", "cycle", "sub", "repeat", "comp",
         "inverse", "polar", "inch", "helix", "plane_arc", "g53", "g28", "g52", "params", "ifwhile",
         "modal", "g43_1", "comp_tool", "g10_tool", "absarc", "probe", "input", "plane_cycle",
         "polar_cycle", "m98", "curve", "diameter", "overrides", "thread"]),
        min_size=1, max_size=10))
    for kind in kinds:
        # no move to where the tool is: LinuxCNC writes one (a Program has none), and after G92
        # its program coordinates differ from the last call's, so the oracle cannot drop it
        if kind in ("line", "rapid"):
            nx, ny, nz = draw(val), draw(val), draw(st.integers(-5, 20).map(float))
            if (nx, ny, nz) == (x, y, z):
                continue
            x, y, z = nx, ny, nz
            out.append(f"{'G1' if kind == 'line' else 'G0'} X{_n(x)} Y{_n(y)} Z{_n(z)}")
        elif kind == "arc":
            ex, ey = draw(val), draw(val)
            half = math.hypot(ex - x, ey - y) / 2.0
            if half < 0.5:
                continue
            r = half * draw(st.floats(1.05, 3.0)) * draw(st.sampled_from([1.0, -1.0]))
            out.append(f"{draw(st.sampled_from(['G2', 'G3']))} X{_n(ex)} Y{_n(ey)} R{r:.4f}")
            x, y = ex, ey
        elif kind == "inc":
            dx, dy = draw(val), draw(val)
            if dx == dy == 0.0:
                continue
            out.append(f"G91 G1 X{_n(dx)} Y{_n(dy)}\nG90")
            x, y = x + dx, y + dy
        elif kind == "tool":
            t = draw(st.integers(1, 3))
            out.append(f"T{t} M6\n{draw(st.sampled_from(['G43', f'G43 H{t}', 'G49']))}")
            goto()
        elif kind == "offset":
            rot = draw(st.sampled_from([0, 0, 30, -45, 90]))
            out.append(f"G10 L2 P2 X{_n(draw(val))} Y{_n(draw(val))} Z{_n(draw(val))} R{rot}")
            system = draw(st.sampled_from(["G55", "G54"]))
            out.append(system)
            goto()
        elif kind == "g92":
            if draw(st.booleans()):
                x, y = draw(val), draw(val)
                out.append(f"G92 X{_n(x)} Y{_n(y)}")
            else:
                out.append("G92.1")
                goto()
        elif kind == "cycle":
            out.append(f"G0 Z{_n(max(z, 5.0))}")
            z = max(z, 5.0)
            code = draw(st.sampled_from(["G81", "G82 P0.2", "G83 Q1.5", "G73 Q1", "G85", "G89 P0.1"]))
            retract = draw(st.sampled_from(["G98", "G99"]))
            x, y = draw(val), draw(val)
            out.append(f"{retract} {code} X{_n(x)} Y{_n(y)} Z-3 R2 F300")
            x2, y2 = draw(val), draw(val)
            out.append(f"X{_n(x2)} Y{_n(y2)}\nG80\nF600")
            x, y = x2, y2
            z = z if retract == "G98" else 2.0
        elif kind == "curve":
            # G05, G05.1, G05.2/G05.3: rs274 prints each as one NURBS_FEED of its control points
            ex, ey = draw(val), draw(val)
            form = draw(st.sampled_from(["G5", "G5.1", "G5.2"]))
            if form == "G5":
                out.append(f"G5 X{_n(ex)} Y{_n(ey)} I{_n(draw(val))} J{_n(draw(val))} P{_n(draw(val))} "
                           f"Q{_n(draw(val))}")
            elif form == "G5.1":
                out.append(f"G5.1 X{_n(ex)} Y{_n(ey)} I{_n(draw(val))} J{_n(draw(val))}")
            else:
                order = draw(st.integers(3, 5))
                points = [(draw(val), draw(val)) for _ in range(draw(st.integers(order - 1, 6)))]
                weights = [draw(st.sampled_from([0.5, 1, 2])) for _ in points]
                body = "\n".join(f"X{_n(px)} Y{_n(py)} P{w}" for (px, py), w in zip(points, weights))
                out.append(f"G5.2 L{order}\n{body}\nG5.3")
                ex, ey = points[-1]
            # rs274 does not print where a curve ends, so a move after it to where the tool
            # already is cannot be told from a real one: the next move goes up
            z += 1.0
            out.append(f"G1 Z{_n(z)}")
            x, y = ex, ey
        elif kind == "polar_cycle":
            # in G91 @ or ^ step at each L repeat about the program zero (bolt circles)
            if math.hypot(x, y) < 1.0:
                continue
            step = draw(st.sampled_from(["^", "@"])) + str(draw(st.integers(-90, 90) if draw(st.booleans())
                                                             else st.integers(1, 5)))
            out.append(f"G0 Z{_n(max(z, 5.0))}\nG91 G98 G81 {step} R-1 Z-3 L{draw(st.integers(1, 4))} F300\n"
                       "G90 G80 F600")
            goto()
        elif kind == "plane_cycle":
            # G18: holes along Y, G19: along X; in a rotated system that axis is a turned one
            code = draw(st.sampled_from(["G81", "G83 Q1.5", "G73 Q1", "G85"]))
            retract = draw(st.sampled_from(["G98", "G99"]))
            a, b = draw(val), draw(val)
            if draw(st.booleans()):
                out.append(f"G0 Y5\nG18 {retract} {code} X{_n(a)} Z{_n(b)} Y-3 R2 F300\nG17 G80 F600")
            else:
                out.append(f"G0 X5\nG19 {retract} {code} Y{_n(a)} Z{_n(b)} X-3 R2 F300\nG17 G80 F600")
            goto()
        elif kind == "sub":
            a, b = draw(val), draw(val)
            if a == b == 0.0:
                continue
            out.append(f"o100 call [{_n(a)}] [{_n(b)}]")
            x, y = x + a, y + b
        elif kind == "m98":
            # a Fanuc-style subprogram (O300 after the M2) run L times: 1 mm along X and Y each
            runs = draw(st.integers(0, 3))
            out.append(f"M98 P300 L{runs}")
            x, y = x + runs, y + runs
        elif kind == "repeat":
            k = draw(st.integers(1, 4))
            label = 200 + 2 * len(out)      # a label of its own (LinuxCNC refuses a reused one)
            out.append(f"o{label} repeat [{k}]\nG91 G1 X1 Y-0.5\nG90\no{label} endrepeat")
            x, y = x + k, y - 0.5 * k
        elif kind == "comp":
            w, h = draw(st.integers(20, 60).map(float)), draw(st.integers(20, 60).map(float))
            d = draw(st.sampled_from([2.0, 4.0, 6.0]))
            code = draw(st.sampled_from(["G41.1", "G42.1"]))
            out.append(f"G0 X{_n(x - 10)} Y{_n(y - 10)}")
            out.append(f"{code} D{d:g} G1 X{_n(x)} Y{_n(y)}")
            out.append(f"X{_n(x + w)}\nG3 X{_n(x + w)} Y{_n(y + h)} R{h / 2:.3f}\nG1 X{_n(x)}\nY{_n(y)}")
            out.append(f"G40 G1 X{_n(x - 10)} Y{_n(y - 10)}")
            x, y = x - 10, y - 10
        elif kind == "inverse":
            nx, ny = draw(val), draw(val)
            if (nx, ny) == (x, y):
                continue
            x, y = nx, ny
            out.append(f"G93 G1 X{_n(x)} Y{_n(y)} F{draw(st.integers(1, 50))}\nG94 F600")
        elif kind == "polar":
            r, ang = draw(st.integers(1, 40).map(float)), draw(st.integers(-180, 180))
            nx, ny = r * math.cos(math.radians(ang)), r * math.sin(math.radians(ang))
            if math.hypot(nx - x, ny - y) < 0.01:
                continue
            out.append(f"G1 @{r:g} ^{ang}")
            x, y = nx, ny
        elif kind == "inch":
            xi, yi = draw(st.integers(-15, 15)) / 10.0, draw(st.integers(-15, 15)) / 10.0
            if math.hypot(xi * 25.4 - x, yi * 25.4 - y) < 0.01:
                continue
            out.append(f"G20 G1 X{xi:g} Y{yi:g}\nG21")
            x, y = xi * 25.4, yi * 25.4
        elif kind == "helix":
            # a full circle (or P turns) about a centre off the current point, going down
            i, j = draw(val), draw(val)
            if math.hypot(i, j) < 1.0:
                continue
            turns = draw(st.integers(1, 3))
            dz = draw(st.integers(-10, 10).map(float))
            out.append(f"{draw(st.sampled_from(['G2', 'G3']))} X{_n(x)} Y{_n(y)} Z{_n(z + dz)} I{_n(i)} "
                       f"J{_n(j)} P{turns}")
            z += dz
        elif kind == "plane_arc":
            # a half circle in G18 or G19 from the current point, back to G17; in a rotated
            # system (G55 here) its plane holds Z and the turned X or Y. Centre by I/J/K, by R
            # (a little under a half: exactly 2 R is at the edge of LinuxCNC's tolerance), by
            # absolute centre (G90.1), or a helix along the plane's normal
            d = draw(st.integers(5, 100).map(lambda k: k / 10.0))
            form = draw(st.sampled_from(["ijk", "r", "absolute", "helix"]))
            g = draw(st.sampled_from(["G2", "G3"]))
            rise = draw(st.integers(-50, 50).map(lambda k: k / 10.0)) if form == "helix" else 0.0
            if draw(st.booleans()):
                centre = {"ijk": f"I{_n(d)} K0", "helix": f"I{_n(d)} K0", "r": f"R{d + 1.0:.3f}",
                          "absolute": f"I{_n(x + d)} K{_n(z)}"}[form]
                out.append(f"{'G90.1 ' if form == 'absolute' else ''}G18 {g} X{_n(x + 2 * d)} Z{_n(z)} "
                           f"{centre}{f' Y{_n(y + rise)}' if rise else ''}\nG17 G91.1")
                x += 2 * d
                y += rise
            else:
                centre = {"ijk": f"J{_n(d)} K0", "helix": f"J{_n(d)} K0", "r": f"R{d + 1.0:.3f}",
                          "absolute": f"J{_n(y + d)} K{_n(z)}"}[form]
                out.append(f"{'G90.1 ' if form == 'absolute' else ''}G19 {g} Y{_n(y + 2 * d)} Z{_n(z)} "
                           f"{centre}{f' X{_n(x + rise)}' if rise else ''}\nG17 G91.1")
                y += 2 * d
                x += rise
        elif kind == "probe":
            # the stand-alone rs274 has no probe: it reports no contact and backs off 0.254 mm,
            # where a run takes the machine's result; an absolute move after it meets both
            if draw(st.booleans()):
                out.append(f"G38.2 Z{_n(z - draw(st.integers(1, 20)))}")
            else:
                out.append(f"G38.3 X{_n(x + draw(st.integers(1, 50)) / 10.0)} Y{_n(draw(val))}")
            goto()
        elif kind == "input":
            x = x + 1.0
            out.append(f"M66 P0 L0\nG1 X[{_n(x)} + #5399]")
        elif kind == "g53":
            out.append(f"G53 G0 Z{_n(draw(st.integers(0, 50).map(float)))}")
            goto()
        elif kind == "g28":
            out.append(f"G28.1\n{draw(st.sampled_from(['G28', 'G28 Z30', 'G30', 'G30 X5']))}")
            goto()
        elif kind == "g52":
            out.append(f"G52 X{_n(draw(val))} Y{_n(draw(val))}")
            goto()
            out.append("G52 X0 Y0")
            goto()
        elif kind == "params":
            a, b = draw(val), draw(val)
            out.append(f"#<dx> = {_n(a)}\n#7 = [{_n(b)} * 2 + SQRT[16] - 4]\n"
                       f"G1 X[{_n(x)} + #<dx>] Y[#7 / 2 + {_n(y)}]")
            x, y = x + a, y + b
            if a == b == 0.0:
                out.append("G1 Z[#<_z> + 1]")       # LinuxCNC's predefined position parameter
                z += 1.0
        elif kind == "ifwhile":
            k = draw(st.integers(1, 3))
            label = 1000 + 2 * len(out)
            out.append(f"#<n> = 0\no{label} while [#<n> LT {k}]\n"
                       f"o{label + 1} if [#<n> EQ 1]\nG91 G1 X2\no{label + 1} else\nG91 G1 Y2\n"
                       f"o{label + 1} endif\nG90\n#<n> = [#<n> + 1]\no{label} endwhile")
            x, y = x + 2 * (k >= 2), y + 2 * (k - (k >= 2))
        elif kind == "modal":
            out.append("M70\nG91 G20\nG1 X0.1\nM72")
            x += 2.54
        elif kind == "g43_1":
            out.append(f"G43.1 Z{_n(draw(val))}")
            goto()
            out.append("G49")
            goto()
        elif kind == "comp_tool":
            t = draw(st.integers(1, 3))
            out.append(f"T{t} M6\nG43 H{t}")
            goto()
            w = draw(st.integers(30, 60).map(float))
            code = draw(st.sampled_from(["G41", "G42"]))
            out.append(f"G0 X{_n(x - 15)} Y{_n(y - 15)}\n{code} D{t} G1 X{_n(x)} Y{_n(y)}\n"
                       f"X{_n(x + w)}\nY{_n(y + w)}\nG2 X{_n(x)} Y{_n(y + w)} R{w / 2 + 5:.3f}\nG1 Y{_n(y)}\n"
                       f"G40 G1 X{_n(x - 15)} Y{_n(y - 15)}\nG49")
            goto()
        elif kind == "g10_tool":
            t = draw(st.integers(1, 3))
            out.append(f"G10 L1 P{t} Z{_n(draw(val))} R{draw(st.integers(1, 5))}\nT{t} M6\nG43")
            goto()
            out.append(f"G10 L10 P{t} Z{_n(draw(val))}\nG43")
            goto()
            out.append("G49")
            goto()
        elif kind == "thread":
            # G76 from where the tool stands (offsets, rotation and G92 as they are), then a G33
            nz = draw(st.integers(-30, 10).map(float))
            if nz == z:
                continue
            words = [f"P{draw(st.sampled_from(['1', '1.5', '2']))}", f"Z{_n(nz)}",
                     f"I{draw(st.sampled_from(['-1', '0.8']))}", "J0.2", "K0.9"]
            words += draw(st.lists(st.sampled_from(["R1.5", "Q29.5", "H1", "E1 L3", "E0.5 L1"]),
                                   max_size=2, unique=True))
            out.append(f"M3 S400\nG76 {' '.join(draw(st.permutations(words)))}\nG33 Z{_n(z)} K1\nM5")
        elif kind == "diameter":
            # G7: X words are diameters, in every code that reads one, until G8
            d, dx = draw(val), draw(val)
            if math.hypot(d / 2 - x, 0) < 0.01 or dx == 0:
                continue
            out.append(f"G7 G1 X{_n(d)}\nG91 X{_n(dx)}\nG90 G92 X{_n(d)}\nG1 Y{_n(y + 1)}\nG92.1\nG8")
            x, y = d / 2 + dx / 2, y + 1
        elif kind == "overrides":
            # M48-M53 around a move: the moves read as LinuxCNC reads them (the overrides
            # themselves are checked in test_override_codes)
            nx = draw(val)
            if nx == x:
                continue
            code = draw(st.sampled_from(["M49", "M50 P0", "M51 P0", "M50", "M52 P0", "M53 P1"]))
            out.append(f"{code}\nG1 X{_n(nx)}\nM48")
            x = nx
        elif kind == "absarc":
            ex, ey = draw(val), draw(val)
            cx, cy = (x + ex) / 2.0, (y + ey) / 2.0
            if math.hypot(ex - x, ey - y) < 1.0:
                continue
            out.append(f"G90.1 {draw(st.sampled_from(['G2', 'G3']))} X{_n(ex)} Y{_n(ey)} I{cx:.4f} J{cy:.4f}"
                       "\nG91.1")
            x, y = ex, ey
    out.append("M2\nO300 (a Fanuc-style subprogram)\nG91 G1 X1 Y1\nG90\nM99")
    return "\n".join(out) + "\n"


def _without_short_moves(motion: list[tuple], program) -> list[tuple]:
    """The oracle's rule on this side too (``tools.against_linuxcnc.without_short_moves``):
    polar words end off the 0.1 mm grid, so a following grid move can be that short."""
    return without_short_moves(motion, call_ends(program))


_close = close


@settings(max_examples=80, deadline=None)
@given(programs())
def test_random_programs_read_as_linuxcnc_reads_them(text: str) -> None:
    theirs = run_linuxcnc(text, TOOLS)
    try:
        program = parse_program(text, name="p.ngc", tools=TOOLS, machine=MACHINE)
        ours = _without_short_moves(project_motion(program), program)
    except ProgramError as exc:
        assert theirs.error, f"only this interpreter refuses: {exc}\n{text}"
        return
    assert not theirs.error, f"only LinuxCNC refuses: {theirs.error} at {theirs.error_block!r}\n{text}"
    mismatch = [(k, a, b) for k, (a, b) in enumerate(zip(ours, theirs.motion)) if not _close(a, b)]
    assert len(ours) == len(theirs.motion), (len(ours), len(theirs.motion), text)
    assert not mismatch, (mismatch[:3], text)


@st.composite
def rotated_plane_arcs(draw) -> str:
    """A program in a rotated coordinate system (G10 L2 R with an origin, mm or inch, a G92
    shift sometimes), then arcs in G18 and G19 of every form: centre by I/J/K, by R, absolute
    (G90.1), helices along the turned normal, whole turns (P), incremental end points (G91);
    lines and G17 arcs between them."""
    val = st.integers(-300, 300).map(lambda k: k / 10.0)
    unit = draw(st.sampled_from(["G21", "G20"]))
    rot = draw(st.integers(-180000, 180000).filter(lambda r: r != 0)) / 1000.0
    out = [f"{unit} G17 G90 G94 G40 G49 F50",
           f"G10 L2 P2 X{_n(draw(val))} Y{_n(draw(val))} Z{_n(draw(val))} R{rot}", "G55 G0 X0 Y0 Z0"]
    x, y, z = 0.0, 0.0, 0.0
    if draw(st.booleans()):
        x, y = draw(val), draw(val)
        out.append(f"G92 X{_n(x)} Y{_n(y)}")
    for _ in range(draw(st.integers(1, 6))):
        kind = draw(st.sampled_from(["arc", "arc", "arc", "line", "xy_arc"]))
        if kind == "line":
            x, y, z = draw(val), draw(val), draw(val)
            out.append(f"G1 X{_n(x)} Y{_n(y)} Z{_n(z)}")
            continue
        d = draw(st.integers(5, 80).map(lambda k: k / 10.0))
        g = draw(st.sampled_from(["G2", "G3"]))
        if kind == "xy_arc":
            out.append(f"G17 {g} X{_n(x + 2 * d)} Y{_n(y)} I{_n(d)} J0")
            x += 2 * d
            continue
        form = draw(st.sampled_from(["ijk", "r", "absolute", "helix", "turns", "incremental"]))
        rise = draw(st.integers(-50, 50).map(lambda k: k / 10.0)) if form == "helix" else 0.0
        g18 = draw(st.booleans())
        swing, normal = ("X", "Y") if g18 else ("Y", "X")
        here = x if g18 else y
        centre = {"r": f"R{d + 1.0:.3f}",
                  "absolute": f"{'I' if g18 else 'J'}{_n(here + d)} K{_n(z)}"}.get(
            form, f"{'I' if g18 else 'J'}{_n(d)} K0")
        end = f"{swing}{_n(here + 2 * d)} Z{_n(z)}"
        if form == "incremental":
            end = f"G91 {swing}{_n(2 * d)} Z0"
        normal_word = f" {normal}{_n((y if g18 else x) + rise)}" if rise else ""
        turns = f" P{draw(st.integers(2, 3))}" if form == "turns" else ""
        out.append(f"{'G90.1 ' if form == 'absolute' else ''}{'G18' if g18 else 'G19'} {g} {end} "
                   f"{centre}{normal_word}{turns}\nG90 G91.1 G17")
        if g18:
            x, y = x + 2 * d, y + rise
        else:
            y, x = y + 2 * d, x + rise
    out.append("M2")
    return "\n".join(out) + "\n"


@settings(max_examples=60, deadline=None)
@given(rotated_plane_arcs())
def test_arcs_in_a_rotated_system_read_as_linuxcnc_reads_them(text: str) -> None:
    """G18/G19 arcs while the XY plane is rotated lie in planes turned about Z (LinuxCNC's
    canon turns them): the same calls in program coordinates, and the same machine positions."""
    theirs = run_linuxcnc(text)
    assert not theirs.error, f"{theirs.error} at {theirs.error_block!r}\n{text}"
    program = parse_program(text, name="p.ngc")
    ours = motion_calls(program)
    assert len(ours) == len(theirs.motion), (len(ours), len(theirs.motion), text)
    for (call, end), lcnc, lcnc_end in zip(ours, theirs.motion, theirs.machine, strict=True):
        assert _close(call, lcnc), (call, lcnc, text)
        assert max(abs(a - b) for a, b in zip(end[:3], lcnc_end)) <= 0.003, (end, lcnc_end, text)


def test_the_oracle_sees_what_it_should() -> None:
    """The harness itself: a known program gives LinuxCNC's known calls, an error is caught."""
    res = run_linuxcnc("G21 F600\nG1 X10\nG2 X20 R5\nM2\n")
    assert [c for c, _ in res.motion] == ["straight_feed", "arc_feed"] and not res.error
    assert res.motion[1][1][:4] == pytest.approx((20.0, 0.0, 15.0, 0.0))
    bad = run_linuxcnc("G21\nG1 X10\nM2\n")
    assert "zero feed rate" in bad.error and bad.error_block == "G1 X10"


def test_the_oracle_reads_long_block_numbers() -> None:
    """rs274 pads a block's N number to five places: a longer one runs into the call's name
    ("N100100STRAIGHT_FEED"), and the call is still read, not taken for an error."""
    res = run_linuxcnc("G21 F600\nN5 G1 X1\nN100100 G1 X2\nN1234567 G1 Y3\nM2\n")
    assert not res.error
    assert [end for _, end in res.motion] == [(1.0, 0.0, 0.0), (2.0, 0.0, 0.0), (2.0, 3.0, 0.0)]


def test_the_library_check_finds_subroutines_where_it_is_told(tmp_path) -> None:
    """A shop keeps its subroutine files in a folder of their own (LinuxCNC's SUBROUTINE_PATH):
    ``--subroutines DIR`` gives it to both interpreters, after the program's own folder."""
    from tools.against_linuxcnc import judge, main

    (tmp_path / "programs").mkdir()
    (tmp_path / "subs").mkdir()
    program = tmp_path / "programs" / "part.ngc"
    program.write_text("G21 F300\no<hole> call [5] [7]\nM2\n")
    (tmp_path / "subs" / "hole.ngc").write_text(
        "o<hole> sub\nG0 X#1 Y#2\nG1 Z-1\nG0 Z1\no<hole> endsub\nM2\n")
    assert judge(program).kind == "both refuse"
    verdict = judge(program, [tmp_path / "subs"])
    assert (verdict.kind, verdict.detail) == ("same", "3 calls")
    assert main([str(program), "--subroutines", str(tmp_path / "subs")]) == 0
    assert main([str(program), "--subroutines", str(tmp_path / "nowhere")]) == 2


def test_the_library_check_draws_curves_as_linuxcnc_does(tmp_path) -> None:
    """rs274 prints a curve as NURBS_FEED(n, ...) only: the library check also holds each curve's
    points against those LinuxCNC's preview module draws, and says when it could not."""
    from tools.against_linuxcnc import judge
    from tools.linuxcnc_oracle import preview_available

    curve = tmp_path / "curve.ngc"
    curve.write_text("G21 G17 F600\nG0 X1 Y2\nG5 X20 Y10 I8 J12 P-6 Q9\nG5.2 L4\nX25 Y5 P1\nX30 Y-5 P2\n"
                     "X35 Y5 P1\nX40 Y0 P1\nG5.3\nM2\n")
    tool = tmp_path / "tool.ngc"             # a tool word: the preview module cannot draw it here
    tool.write_text("G21 G17 F600\nT1 M6\nG5.1 X20 Y10 I8 J12\nM2\n")
    if not preview_available():
        pytest.skip("LinuxCNC's preview module (gcode) is not installed")
    verdict = judge(curve)
    assert (verdict.kind, verdict.detail) == ("same", "3 calls, 2 curves as LinuxCNC's preview draws them")
    verdict = judge(tool)
    assert verdict.kind == "same" and "by their control points' count" in verdict.detail


def test_the_library_check_classes_each_program(tmp_path) -> None:
    """``python -m tools.against_linuxcnc FOLDER``, which an integrator runs on a shop's programs:
    each program in its class, and the share rs274 reads that this reads alike."""
    from tools.against_linuxcnc import judge, main, programs_in, summary

    programs = {
        "same.ngc": "G21 F100\nG1 X10\nG2 X20 R5\nM2\n",
        # M19 (an oriented spindle stop) this machine's spindle cannot do; rs274 writes it
        "orient.ngc": "G21 F100 M3 S100\nM19 R90\nG1 X1\nM2\n",
        # no M2: rs274 calls it an error at the end, this reads it
        "open_end.nc": "G21\nG1 X1 F100\n",
        "no_feed.tap": "G21\nG1 X1\nM2\n",
        # G84 in G18: LinuxCNC's own tests show it feeding along X; this feeds along Y
        "tap_g18.ngc": "G21 G18 G98 F10\nM3 S1000\nG0 X0 Y50 Z0\nG84 X25 Z25 Y-25 R25\nM2\n",
        "notes.txt": "G21 F100\nG1 X10\nM2\n",          # not a program's name: left alone
    }
    for name, text in programs.items():
        (tmp_path / name).write_text(text)
    found = programs_in([tmp_path])
    assert sorted(p.name for p in found) == sorted(n for n in programs if not n.endswith(".txt"))
    kinds = {p.name: judge(p).kind for p in found}
    assert kinds == {
        "same.ngc": "same", "orient.ngc": "only rs274 reads it", "open_end.nc": "only this reads it",
        "no_feed.tap": "both refuse", "tap_g18.ngc": "differ",
    }
    totals = summary([judge(p) for p in found])
    assert (totals["programs"], totals["rs274 reads"], totals["read alike of those"]) == (5, 3, 33.3)
    assert main([str(tmp_path)]) == 0
