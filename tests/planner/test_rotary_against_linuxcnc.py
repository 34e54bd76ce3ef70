"""Rotary words read as LinuxCNC reads them: random programs moving X Y Z A C (G0, G1 in G94
and G93, G90 and G91) read by LinuxCNC's own ``rs274`` and by this interpreter on an XYZAC
machine: every straight move's end equal, the rotary coordinates included."""

from __future__ import annotations

import re
import tempfile
from dataclasses import replace
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.core.machine import AxisSpec, MachineSpec
from planner.gcode.interpreter import parse_program
from tools.linuxcnc_oracle import RS274, _rs274, run_linuxcnc

pytestmark = pytest.mark.skipif(
    RS274 is None, reason="LinuxCNC's rs274 is not installed (make test installs Debian's linuxcnc-uspace "
                          "as root; or: apt-get install --no-install-recommends linuxcnc-uspace)")

MACHINE = replace(MachineSpec.default(), axes=(
    AxisSpec("X"), AxisSpec("Y", drive_position=1), AxisSpec("Z", drive_position=2),
    AxisSpec("A", rotary=True, drive_position=3, min_pos=-1e5, max_pos=1e5),
    AxisSpec("C", rotary=True, drive_position=4, min_pos=-1e5, max_pos=1e5)), work_offsets={})
_STRAIGHT = re.compile(r"\s*\d+ N\.+ (STRAIGHT_TRAVERSE|STRAIGHT_FEED)\(([^)]*)\)")


@st.composite
def programs(draw: st.DrawFn) -> str:
    val = st.integers(-3600, 3600).map(lambda k: k / 10.0)
    out = ["G21 G17 G90 G94 G40 G49 G54 F600"]
    for _ in range(draw(st.integers(1, 10))):
        words = [f"{a}{draw(val):.1f}" for a in "XYZAC" if draw(st.booleans())] or [f"C{draw(val):.1f}"]
        mode = draw(st.sampled_from(["G0", "G1", "G93 G1", "G91 G0", "G91 G1"]))
        feed = f" F{draw(st.integers(1, 100))}" if "G93" in mode else ""
        out.append(f"{mode} {' '.join(words)}{feed}")
        out.append("G90 G94 F600")          # G94 clears the feed, as in LinuxCNC
    out.append("M2")
    return "\n".join(out) + "\n"


def _theirs(out_text: str) -> list[tuple[float, ...]]:
    """rs274's straight moves' ends (X Y Z A C), moves to where the tool stands left out."""
    ends: list[tuple[float, ...]] = []
    here = (0.0,) * 5
    for line in out_text.splitlines():
        m = _STRAIGHT.match(line)
        if m is None:
            continue
        v = [float(a) for a in m.group(2).split(",")]
        end = (v[0], v[1], v[2], v[3], v[5])
        if max(abs(a - b) for a, b in zip(end, here)) >= 0.003:
            ends.append(end)
        here = end
    return ends


@settings(max_examples=40, deadline=None)
@given(programs())
def test_straight_moves_end_where_rs274_ends_them_rotary_included(text: str) -> None:
    theirs = run_linuxcnc(text)
    assert not theirs.error, theirs.error
    ours = [tuple(float(x) for x in m.end) for m in parse_program(text, machine=MACHINE).moves]
    with tempfile.TemporaryDirectory() as tmp:           # the raw output: rotary words included
        prog = Path(tmp) / "p.ngc"
        prog.write_text(text)
        raw = _rs274(prog, None, tmp)
    want = _theirs(raw)
    assert len(ours) == len(want), (text, ours, want)
    for a, b in zip(ours, want):
        assert max(abs(x - y) for x, y in zip(a, b)) <= 0.003, (text, a, b)
