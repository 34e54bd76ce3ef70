"""Random and named G-code programs for the motion tests: from fixed seeds, and drawn by
hypothesis block by block (``programs``) so that a failing program shrinks."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from hypothesis import strategies as st

from cli.plan import build_machine
from planner.core.machine import AxisSpec, MachineSpec
from planner.gcode.interpreter import parse_program
from resources import PROGRAMS

# Plane -> (first, second, normal) axis columns of X Y Z, and the I/J/K letters of first/second.
PLANES = {"G17": (0, 1, 2), "G18": (2, 0, 1), "G19": (1, 2, 0)}
OFFSET_LETTER = {0: "I", 1: "J", 2: "K"}


def paper_machine(**kw) -> MachineSpec:
    """3-axis XYZ, per-axis limits = the paper's path limits (what cnc-plan uses by default)."""
    return build_machine(None, kw.get("vmax"), kw.get("amax"), kw.get("jmax"), kw.get("ts"))


def machine_with_axes(axes: list[AxisSpec], **limits) -> MachineSpec:
    base = paper_machine()
    m = replace(base, axes=tuple(axes), work_offsets={k: (0.0,) * len(axes) for k in base.work_offsets})
    return m.with_limits(**limits) if limits else m


def _fmt(x: float) -> str:
    return f"{x:.9f}"


def xyza_machine() -> MachineSpec:
    """X Y Z plus a rotary A axis (deg), limits as the paper's path limits."""
    axes = [AxisSpec(n, drive_position=i, v_max=30, a_max=1000, j_max=10000) for i, n in enumerate("XYZ")]
    axes.append(AxisSpec("A", rotary=True, drive_position=3, v_max=90, a_max=1800, j_max=36000,
                         min_pos=-1e6, max_pos=1e6))
    return machine_with_axes(axes)


def random_program(seed: int, n_blocks: int = 40, events: bool = True, planes: bool = True,
                   tiny: bool = True, rotary: bool = False) -> str:
    """Lines (long, short, tiny, collinear), circles/helices in G17/G18/G19 (I/J/K form, both
    directions, partial and full turns), rapids, feeds, dwells, G61/G64, pauses; with
    ``rotary`` an A axis (deg) moves along on some lines and arcs, or alone."""
    rng = np.random.default_rng(seed)
    pos = np.zeros(3)
    a_pos = 0.0

    def a_word() -> str:
        nonlocal a_pos
        if not rotary or rng.random() < 0.5:
            return ""
        a_pos += float(rng.normal(0, 30))
        return f" A{a_pos:.4f}"

    out = ["G21 G90 G94 G17 F1800", "G00 X0 Y0 Z0"]
    plane = "G17"
    for _ in range(n_blocks):
        r = rng.random()
        feed = f" F{rng.uniform(300, 3000):.0f}" if rng.random() < 0.3 else ""
        if r < 0.35:
            step = rng.normal(0, 8, 3)
            if tiny and rng.random() < 0.15:
                step *= 1e-3
            if rng.random() < 0.2:  # collinear continuation / small angle change
                step = np.array([5.0, 0.0, 0.0]) + rng.normal(0, 0.05, 3)
            pos = pos + step
            out.append(f"G01 X{_fmt(pos[0])} Y{_fmt(pos[1])} Z{_fmt(pos[2])}{a_word()}{feed or ' F1800'}")
        elif r < 0.42:
            pos = pos + rng.normal(0, 10, 3)
            out.append(f"G00 X{_fmt(pos[0])} Y{_fmt(pos[1])} Z{_fmt(pos[2])}")
        elif r < 0.9:
            if planes and rng.random() < 0.4:
                plane = str(rng.choice(["G17", "G18", "G19"]))
            f, s, n = PLANES[plane]
            radius = float(rng.choice([rng.uniform(0.3, 2.0), rng.uniform(2.0, 25.0)]))
            a0 = rng.uniform(-math.pi, math.pi)
            center = pos.copy()
            center[f] -= radius * math.cos(a0)
            center[s] -= radius * math.sin(a0)
            full = rng.random() < 0.15
            sweep = rng.uniform(0.2, 2 * math.pi - 0.2)
            ccw = rng.random() < 0.5
            a1 = a0 + (sweep if ccw else -sweep)
            end = pos.copy()
            if not full:
                end[f] = center[f] + radius * math.cos(a1)
                end[s] = center[s] + radius * math.sin(a1)
            if rng.random() < 0.4:
                end[n] += rng.uniform(-3, 3)
            words = " ".join(f"{'XYZ'[k]}{_fmt(end[k])}" for k in range(3))
            offs = " ".join(f"{OFFSET_LETTER[k]}{_fmt(center[k] - pos[k])}" for k in (f, s))
            out.append(f"{plane} {'G03' if ccw else 'G02'} {words}{a_word()} {offs}{feed}")
            pos = end
        elif rotary and rng.random() < 0.3:
            a_pos += float(rng.normal(0, 45))
            out.append(f"G01 A{a_pos:.4f}")
        elif events:
            out.append(str(rng.choice(["G04 P0.05", "M00", "M01", "G61", "G64", "S5000 M03", "M05"])))
    out.append("M30")
    return "\n".join(out) + "\n"


def short_move_raster(rows: int) -> str:
    """A raster of 0.5 mm lines (40 a second at F1200), rows of 10 mm turning at right angles."""
    lines = ["G21 G90 G0 X0 Y0 Z0", "G1 F1200"]
    for row in range(rows):
        xs = [0.5 * (i + 1) for i in range(20)]
        lines += [f"X{x if row % 2 == 0 else 10.0 - x:.1f}" for x in xs] + [f"Y{0.5 * (row + 1):.1f}"]
    return "\n".join(lines + ["M2"]) + "\n"


def parse(text: str, machine: MachineSpec | None = None, name: str = "<test>"):
    return parse_program(text, name, machine or paper_machine())


def sample_program(name: str, machine: MachineSpec | None = None):
    path = PROGRAMS / name
    return parse_program(path.read_text(), str(path), machine or paper_machine())


@st.composite
def programs(draw: st.DrawFn, max_blocks: int = 12, scale: float = 1.0, rotated: bool = False) -> str:
    """A G-code program drawn block by block by hypothesis (so a failing one shrinks to the
    few blocks that matter): lines (long, tiny, nearly collinear), rapids, arcs and helices in
    the three planes (I/J/K form, both directions, partial and full turns), curves (G05 and
    G05.2 NURBS, made into arcs), feeds, dwells, pauses, exact stop and blending. Every length
    is multiplied by ``scale``. ``rotated``: in a coordinate system turned about Z by a drawn
    angle (G10 L2 R), where G18/G19 arcs lie in turned planes."""
    pos = np.zeros(3)
    out = ["G21 G90 G94 G17 F1800", "G00 X0 Y0 Z0"]
    if rotated:
        out.insert(1, f"G10 L2 P1 R{draw(st.floats(-180.0, 180.0).filter(lambda r: abs(r) > 0.01)):.3f}")
    plane = "G17"
    length = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)
    for _ in range(draw(st.integers(1, max_blocks))):
        kind = draw(st.sampled_from(["line", "tiny", "collinear", "rapid", "arc", "arc", "curve", "event",
                                     "cycle"]))
        # F1e9: "as fast as the machine goes", held to its limits
        feed = draw(st.sampled_from(["", "", " F300", " F1200", " F3000", " F1000000000"]))
        if kind in ("line", "tiny", "collinear", "rapid"):
            step = np.array([draw(length), draw(length), draw(length)])
            if kind == "tiny":
                step *= 1e-3
            elif kind == "collinear":
                step = np.array([5.0, 0.0, 0.0]) + 0.01 * step
            step *= scale
            if not np.any(np.abs(step) > 1e-6 * scale):
                continue
            pos = pos + step
            code = "G00" if kind == "rapid" else "G01"
            out.append(f"{code} X{_fmt(pos[0])} Y{_fmt(pos[1])} Z{_fmt(pos[2])}"
                       + ("" if kind == "rapid" else feed or " F1800"))
        elif kind == "arc":
            plane = draw(st.sampled_from(["G17", "G18", "G19"]))
            f, s, n = PLANES[plane]
            # at least 4x LinuxCNC's zero-radius tolerance (0.00127 mm), whatever the scale
            radius = max(draw(st.floats(0.3, 25.0)) * scale, 0.005)
            a0 = draw(st.floats(-math.pi, math.pi))
            sweep = draw(st.floats(0.2, 2 * math.pi - 0.2))
            full = draw(st.booleans()) and draw(st.booleans())
            ccw = draw(st.booleans())
            center = pos.copy()
            center[f] -= radius * math.cos(a0)
            center[s] -= radius * math.sin(a0)
            end = pos.copy()
            if not full:
                a1 = a0 + (sweep if ccw else -sweep)
                end[f] = center[f] + radius * math.cos(a1)
                end[s] = center[s] + radius * math.sin(a1)
            end[n] += draw(st.sampled_from([0.0, 0.0, -2.0, 1.5])) * scale
            words = " ".join(f"{'XYZ'[k]}{_fmt(end[k])}" for k in range(3))
            offs = " ".join(f"{OFFSET_LETTER[k]}{_fmt(center[k] - pos[k])}" for k in (f, s))
            out.append(f"{plane} {'G03' if ccw else 'G02'} {words} {offs}{feed}")
            pos = end
        elif kind == "curve":
            here = pos[:2].copy()

            def near(here: np.ndarray = here) -> np.ndarray:
                return here + np.array([draw(length), draw(length)]) * scale

            if draw(st.booleans()):
                end, first, last = near(), near() - here, near() - here
                out.append(f"G17 G05 X{_fmt(end[0])} Y{_fmt(end[1])} I{_fmt(first[0])} J{_fmt(first[1])} "
                           f"P{_fmt(last[0])} Q{_fmt(last[1])}{feed}")
            else:
                order = draw(st.integers(3, 4))
                points = [near() for _ in range(draw(st.integers(order - 1, 5)))]
                out.append(f"G17 G05.2 L{order}{feed}")
                weight = st.sampled_from(["1", "2", "0.5"])
                out += [f"X{_fmt(p[0])} Y{_fmt(p[1])} P{draw(weight)}" for p in points]
                out.append("G05.3")
                end = points[-1]
            plane = "G17"
            pos = np.array([end[0], end[1], pos[2]])
        elif kind == "cycle":
            # a drilling, pecking or tapping cycle in G17 from here: R above, the bottom below;
            # the taps with their spindle on, at their own feed
            code = draw(st.sampled_from(["G81", "G82 P0.05", "G83 Q", "G73 Q", "G84", "G85", "G89 P0.05"]))
            depth = draw(st.floats(0.5, 10.0)) * scale
            r_up = draw(st.floats(0.2, 3.0)) * scale
            hole = pos[:2] + np.array([draw(length), draw(length)]) * scale
            if code.endswith("Q"):
                code += _fmt(depth / draw(st.integers(1, 6)))
            spindle = "S1000 M03\n" if code == "G84" else ""
            out.append(f"{spindle}G17 G98 {code} X{_fmt(hole[0])} Y{_fmt(hole[1])} Z{_fmt(pos[2] - depth)} "
                       f"R{_fmt(pos[2] + r_up)}{feed or ' F600'}\nG80")
            plane = "G17"
            pos = np.array([hole[0], hole[1], pos[2] + r_up])
        else:
            out.append(draw(st.sampled_from(["G04 P0.05", "M00", "M01", "G61", "G64", "S5000 M03", "M05"])))
    out.append("M30")
    return "\n".join(out) + "\n"
