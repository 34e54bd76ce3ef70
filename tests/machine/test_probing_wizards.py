"""The probing wizards: each shipped routine (resources/subroutines/probe_*.ngc) against a
simulated part at a known place, from 20 random start positions (the interpreter and the
simulated contacts of ``probing_sim``), and on the simulated machine (the worker, the drives,
the probe latched at 1 ms): the offset written within 0.01 mm of the truth, the angle within
0.01 degree; a missing part, a part not as expected and an obstacle on a positioning move stop
the routine before it writes."""

from __future__ import annotations

import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from app.machine.config import MachineConfig, ProbeSettings
from app.machine.controller import MachineController
from app.machine.devices.probing import probing_routine
from app.machine.model import WIZARD, WIZARDS, MachineState, ProbeWizard, ProbingRequest
from ethercat.sim_part import Feature, SimPart
from planner.core.errors import ProgramError
from planner.core.tools import Tool, ToolTable
from tests.machine.conftest import make_controller
from tests.machine.probing_sim import Outcome, ProbeAlarm, run

PROBE = Tool(99, 99, (("Z", 50.0),), 2.0, "3-D probe")
R = PROBE.diameter_mm / 2.0
TOP = -60.0                                  # the block's top (the stylus' tip), machine Z
BLOCK = SimPart(x_mm=20.0, y_mm=10.0, half_x_mm=40.0, half_y_mm=30.0, top_mm=TOP, depth_mm=40.0)
G55 = 5241                                   # #5241-#5249 X Y Z ..., #5250 the rotation
STARTS = 20


def _with(**kw: object) -> SimPart:
    return SimPart(**{**{f: getattr(BLOCK, f) for f in BLOCK.__dataclass_fields__}, **kw})  # type: ignore[arg-type]


def _run(req: ProbingRequest, start_tip: tuple[float, float, float], part: SimPart | None) -> Outcome:
    cfg = MachineConfig.default()
    text = probing_routine(req, ProbeSettings(drive=2), PROBE.number, "G54")
    x, y, z = start_tip
    return run(text, cfg.machine, ToolTable({PROBE.number: PROBE}), PROBE.number,
               (x, y, z + PROBE.length_mm), part)


def _starts(seed: int) -> np.random.Generator:
    return np.random.default_rng(seed)


# ------------------------------------------------------------------ each wizard, 20 starts
def test_z_surface_from_20_starts() -> None:
    rng = _starts(1)
    for _ in range(STARTS):
        start = (20.0 + rng.uniform(-30, 30), 10.0 + rng.uniform(-20, 20), TOP + rng.uniform(2, 8))
        out = _run(ProbingRequest(ProbeWizard.Z_SURFACE, system="G55"), start, BLOCK)
        assert out.system(G55)[G55 + 2] == pytest.approx(TOP, abs=0.01), start
        assert out.reported["Z"] == pytest.approx(TOP, abs=0.01)


@pytest.mark.parametrize(("axis", "direction", "face"), [("X", 1, -20.0), ("X", -1, 60.0), ("Y", 1, -20.0),
                                                          ("Y", -1, 40.0)])
def test_each_edge_from_20_starts(axis: str, direction: int, face: float) -> None:
    rng = _starts(2)
    for _ in range(STARTS):
        gap = rng.uniform(1, 8)
        if axis == "X":
            start = (face - direction * (R + gap), 10.0 + rng.uniform(-25, 25), TOP - rng.uniform(3, 8))
        else:
            start = (20.0 + rng.uniform(-35, 35), face - direction * (R + gap), TOP - rng.uniform(3, 8))
        req = ProbingRequest(ProbeWizard.EDGE, system="G55", axis=axis, x_dir=direction, y_dir=direction)
        out = _run(req, start, BLOCK)
        k = 0 if axis == "X" else 1
        assert out.system(G55)[G55 + k] == pytest.approx(face, abs=0.01), start
        assert out.reported[axis] == pytest.approx(face, abs=0.01)


@pytest.mark.parametrize(("xs", "ys"), [(1, 1), (-1, 1), (1, -1), (-1, -1)])
def test_outside_corners_from_20_starts(xs: int, ys: int) -> None:
    corner = (20.0 - xs * 40.0, 10.0 - ys * 30.0)        # the part is at +xs, +ys from the probe
    rng = _starts(3)
    for _ in range(STARTS):
        start = (corner[0] - xs * (R + rng.uniform(1, 5)), corner[1] - ys * (R + rng.uniform(1, 5)),
                 TOP - rng.uniform(3, 8))
        req = ProbingRequest(ProbeWizard.OUTSIDE_CORNER, system="G55", x_dir=xs, y_dir=ys, along_mm=10.0)
        out = _run(req, start, BLOCK)
        got = out.system(G55)
        assert (got[G55], got[G55 + 1]) == pytest.approx(corner, abs=0.01), start


@pytest.mark.parametrize(("xs", "ys"), [(1, 1), (-1, -1)])
def test_inside_corners_from_20_starts(xs: int, ys: int) -> None:
    part = _with(feature=Feature.POCKET, feature_x_mm=25.0, feature_y_mm=12.0, pocket_half_x_mm=12.0,
                 pocket_half_y_mm=9.0)
    corner = (25.0 + xs * 12.0, 12.0 + ys * 9.0)          # the walls are at +xs, +ys from the probe
    rng = _starts(4)
    for _ in range(STARTS):
        start = (corner[0] - xs * (R + rng.uniform(1, 6)), corner[1] - ys * (R + rng.uniform(1, 6)),
                 TOP - rng.uniform(3, 8))
        out = _run(ProbingRequest(ProbeWizard.INSIDE_CORNER, system="G55", x_dir=xs, y_dir=ys), start, part)
        got = out.system(G55)
        assert (got[G55], got[G55 + 1]) == pytest.approx(corner, abs=0.01), start


def test_bore_centre_and_diameter_from_20_starts() -> None:
    part = _with(feature=Feature.BORE, feature_x_mm=23.0, feature_y_mm=12.0, feature_radius_mm=10.0)
    rng = _starts(5)
    for _ in range(STARTS):
        start = (23.0 + rng.uniform(-3, 3), 12.0 + rng.uniform(-3, 3), TOP - rng.uniform(3, 8))
        out = _run(ProbingRequest(ProbeWizard.BORE, system="G55", diameter_mm=20.0, tolerance_mm=0.5),
                   start, part)
        got = out.system(G55)
        assert (got[G55], got[G55 + 1]) == pytest.approx((23.0, 12.0), abs=0.01), start
        assert out.reported["D"] == pytest.approx(20.0, abs=0.01)


def test_boss_centre_and_diameter_from_20_starts() -> None:
    part = _with(feature=Feature.BOSS, feature_x_mm=23.0, feature_y_mm=12.0, feature_radius_mm=8.0,
                 boss_height_mm=10.0)
    rng = _starts(6)
    for _ in range(STARTS):
        above = rng.uniform(2, 6)
        start = (23.0 + rng.uniform(-2, 2), 12.0 + rng.uniform(-2, 2), TOP + 10.0 + above)
        req = ProbingRequest(ProbeWizard.BOSS, system="G55", diameter_mm=16.0, tolerance_mm=0.5,
                             depth_mm=above + 5.0)
        out = _run(req, start, part)
        got = out.system(G55)
        assert (got[G55], got[G55 + 1]) == pytest.approx((23.0, 12.0), abs=0.01), start
        assert out.reported["D"] == pytest.approx(16.0, abs=0.01)


def test_the_angle_of_a_face_from_20_starts() -> None:
    rng = _starts(7)
    for _ in range(STARTS):
        angle = rng.uniform(-5, 5)
        part = _with(angle_deg=angle)
        x0 = 20.0 + rng.uniform(-30, -5)
        # the front face (y = -20 turned about the block's centre) at x0, and in front of it
        a = math.radians(angle)
        face_y = 10.0 + (x0 - 20.0) * math.tan(a) - 30.0 / math.cos(a)
        start = (x0, face_y - R - rng.uniform(4.5, 7), TOP - rng.uniform(3, 8))
        req = ProbingRequest(ProbeWizard.ANGLE, system="G55", axis="Y", y_dir=1, along_mm=30.0,
                             search_mm=15.0)
        out = _run(req, start, part)
        assert out.reported["A"] == pytest.approx(angle, abs=0.01), start
        assert out.system(G55)[G55 + 9] == pytest.approx(angle, abs=0.01)


def test_the_routine_writes_into_the_system_by_its_number_and_selects_it_only_when_turned_otherwise() -> None:
    """Into G55 from G54: G10 with P2, G54 stays in use; a G55 turned otherwise than G54 (a
    distance along one is not along the other's axes): the routine runs in G55, then G54 again."""
    req = ProbingRequest(ProbeWizard.EDGE, system="G55", axis="X", x_dir=1)
    same = probing_routine(req, ProbeSettings(drive=2), PROBE.number, "G54", same_turn=True)
    assert same.splitlines()[0] == f"G43 H{PROBE.number}" and "G54" not in same and "G55" not in same
    assert same.splitlines()[-1].split()[7] == "[2]"                  # #6: G10's P of G55
    turned = probing_routine(req, ProbeSettings(drive=2), PROBE.number, "G54", same_turn=False)
    assert turned.splitlines()[0] == "G55" and turned.splitlines()[-1] == "G54"
    only = probing_routine(ProbingRequest(ProbeWizard.EDGE, system="", axis="X", x_dir=1),
                           ProbeSettings(drive=2), PROBE.number, "G54")
    assert only.splitlines()[-1].split()[7] == "[0]"                  # only reported


def test_each_wizard_is_declared_once() -> None:
    """``WIZARDS`` declares each wizard (title, name, inputs, aim, the routine's arguments) and
    its routine is a shipped subroutine; apart from that declaration only the panel's pictures
    name a wizard: a new one is a routine, a row and a picture."""
    root = Path(__file__).resolve().parents[2]
    assert [w.wizard for w in WIZARDS] == list(ProbeWizard) and set(WIZARD) == set(ProbeWizard)
    for spec in WIZARDS:
        assert (root / "resources" / "subroutines" / f"{spec.wizard.value}.ngc").is_file()
        assert len({spec.title, spec.name}) == 2 and spec.inputs <= {"diameter", "tolerance", "depth",
                                                                    "along", "x", "y", "z"}
    named = {}
    for path in sorted((root / "app").rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        if path.name == "model.py" and path.parent.name == "machine":
            continue
        if path.name == "probing_panel.py":          # the pictures, drawn by wizard
            text = text[:text.index("def wizard_icon")]
        members = set(re.findall(r"ProbeWizard\.([A-Z_]+)", text))
        if members:
            named[str(path.relative_to(root))] = members
    assert named == {}, named


def test_report_only_writes_nothing() -> None:
    out = _run(ProbingRequest(ProbeWizard.Z_SURFACE), (20.0, 10.0, TOP + 5.0), BLOCK)
    assert out.reported["Z"] == pytest.approx(TOP, abs=0.01)
    assert out.system(G55) == {} and not out.program.parameter_sets


# ------------------------------------------------------------------ what stops a wizard
def test_a_missing_part_is_an_alarm() -> None:
    with pytest.raises(ProbeAlarm, match="ended without contact"):
        _run(ProbingRequest(ProbeWizard.BORE, system="G55"), (23.0, 12.0, TOP - 5.0), None)


def test_a_bore_not_as_expected_is_refused_before_it_writes() -> None:
    part = _with(feature=Feature.BORE, feature_x_mm=23.0, feature_y_mm=12.0, feature_radius_mm=10.0)
    with pytest.raises(ProgramError, match="the bore measures 20.0.* mm across, not 30.0"):
        _run(ProbingRequest(ProbeWizard.BORE, system="G55", diameter_mm=30.0, tolerance_mm=1.0),
             (23.0, 12.0, TOP - 5.0), part)


def test_an_obstacle_on_a_positioning_move_stops_the_routine() -> None:
    """An outside corner started too close to the part's side: the move along Y runs into it."""
    with pytest.raises(ProgramError, match="probe touched during positioning"):
        _run(ProbingRequest(ProbeWizard.OUTSIDE_CORNER, system="G55", along_mm=10.0),
             (-20.0 - R - 3.0, -20.0 + 2.0, TOP - 5.0), BLOCK)


# ------------------------------------------------------------------ on the simulated machine
class _Path:
    """The drives' actual positions, machine coordinates, as the worker reports them."""

    def __init__(self, ctl: MachineController) -> None:
        self.chunks: list[np.ndarray] = []
        ctl.add_trace_sink(lambda _cycles, _reference, actual, _lines: self.chunks.append(np.array(actual)))

    def actual(self) -> np.ndarray:
        return np.concatenate(self.chunks)


def _machine(qapp, config_path: Path, state_dir: Path) -> MachineController:
    ctl = make_controller(config_path, state_dir)
    assert ctl.set_tool(PROBE) and ctl.set_tool_in_spindle(PROBE.number)
    return ctl


def _to(ctl: MachineController, tip: tuple[float, float, float]) -> None:
    x, y, z = tip
    for block in (f"G53 G0 Z{z + PROBE.length_mm:.4f}", f"G53 G0 X{x:.4f} Y{y:.4f}"):
        assert ctl.mdi(block)
        assert ctl.run_until(lambda: ctl.state is MachineState.IDLE and ctl.stream.job is None, 30)


def _probe(ctl: MachineController, req: ProbingRequest) -> set[str]:
    """Run the wizard to its end; the systems the machine was in while it ran."""
    assert ctl.run_probing(req)
    systems: set[str] = set()

    def ended() -> bool:
        systems.add(ctl.active_offset)
        return ctl.state is not MachineState.RUNNING and ctl.stream.job is None

    assert ctl.run_until(ended, 120)
    return systems


MACHINE_CASES = [
    (ProbingRequest(ProbeWizard.Z_SURFACE, system="G55"), BLOCK, (20.0, 10.0, TOP + 4.0), {2: TOP}),
    (ProbingRequest(ProbeWizard.EDGE, system="G55", axis="X", x_dir=1), BLOCK, (-25.0, 12.0, TOP - 4.0),
     {0: -20.0}),
    (ProbingRequest(ProbeWizard.OUTSIDE_CORNER, system="G55", x_dir=1, y_dir=1), BLOCK,
     (-24.0, -24.0, TOP - 4.0), {0: -20.0, 1: -20.0}),
    (ProbingRequest(ProbeWizard.INSIDE_CORNER, system="G55", x_dir=1, y_dir=1),
     _with(feature=Feature.POCKET, feature_x_mm=25.0, feature_y_mm=12.0, pocket_half_x_mm=12.0,
           pocket_half_y_mm=9.0), (33.0, 17.0, TOP - 4.0), {0: 37.0, 1: 21.0}),
    (ProbingRequest(ProbeWizard.BORE, system="G55", diameter_mm=20.0, tolerance_mm=0.5),
     _with(feature=Feature.BORE, feature_x_mm=23.0, feature_y_mm=12.0, feature_radius_mm=10.0),
     (21.0, 13.5, TOP - 5.0), {0: 23.0, 1: 12.0}),
    (ProbingRequest(ProbeWizard.BOSS, system="G55", diameter_mm=16.0, tolerance_mm=0.5, depth_mm=8.0),
     _with(feature=Feature.BOSS, feature_x_mm=23.0, feature_y_mm=12.0, feature_radius_mm=8.0,
           boss_height_mm=10.0), (24.0, 11.0, TOP + 13.0), {0: 23.0, 1: 12.0}),
    (ProbingRequest(ProbeWizard.ANGLE, system="G55", axis="Y", y_dir=1, along_mm=30.0, search_mm=15.0),
     _with(angle_deg=3.0), (0.0, -27.0, TOP - 4.0), {9: 3.0}),
]


@pytest.mark.parametrize(("req", "part", "start", "truth"), MACHINE_CASES,
                         ids=[c[0].wizard.value for c in MACHINE_CASES])
def test_each_wizard_on_the_simulated_machine(qapp, config_path: Path, state_dir: Path, req: ProbingRequest,
                                              part: SimPart, start: tuple[float, float, float],
                                              truth: dict[int, float]) -> None:
    """The probe latched by the worker at 1 ms, the motion stopped past the contact, the routine
    read again with each contact: G55 takes what the part says, within 0.01 mm (0.01 degree)."""
    ctl = _machine(qapp, config_path, state_dir)
    try:
        assert ctl.simulate_part(part)
        _to(ctl, start)
        path = _Path(ctl)
        before = ctl.work_offsets["G55"]
        preview = ctl.preview_probing(req)
        assert not isinstance(preview, type(ctl.measure_tool(0))), preview
        assert len(preview.moves) > 2 and preview.probes                 # drawn before it runs
        systems = _probe(ctl, req)
        assert not ctl.active_alarms, [a.cause for a in ctl.active_alarms]
        assert systems == {"G54"}          # the DRO names the system in use all along, not G55
        result = ctl.last_probing
        assert result is not None and result.written == "G55"
        for k, value in truth.items():
            got = ctl.work_rotation("G55") if k == 9 else ctl.work_offsets["G55"][k]
            assert got == pytest.approx(value, abs=0.01), (k, got, ctl.work_offsets["G55"])
        for k in range(3):
            if k not in truth:
                assert ctl.work_offsets["G55"][k] == before[k]
        assert ctl.active_offset == "G54"                  # back in the system that was in use
        # the stylus' ball never went into the part by more than the stops' overtravel
        tip = path.actual() - np.array([0.0, 0.0, PROBE.length_mm - R])
        deepest = min(part.distance(*p) for p in tip[::5]) - R
        assert -0.3 < deepest < 0.0, deepest
    finally:
        ctl.shutdown()


@pytest.mark.parametrize("rotation_deg", [0.0, 10.0])
def test_a_result_says_where_the_corner_is_on_the_machine_whatever_the_system_was(
        qapp, config_path: Path, state_dir: Path, rotation_deg: float) -> None:
    """An outside corner found into a G55 that stood elsewhere (turned as the block is): the
    result reads the corner's machine position, not coordinates of the system as it was before
    the wizard wrote it."""
    c, s = math.cos(math.radians(rotation_deg)), math.sin(math.radians(rotation_deg))
    part = replace(BLOCK, angle_deg=rotation_deg)
    corner = (BLOCK.x_mm - 40.0 * c + 30.0 * s, BLOCK.y_mm - 40.0 * s - 30.0 * c)   # its -X -Y corner
    start = (corner[0] - 4.0 * c + 4.0 * s, corner[1] - 4.0 * s - 4.0 * c)        # off it diagonally
    ctl = _machine(qapp, config_path, state_dir)
    try:
        assert ctl.simulate_part(part)
        assert ctl.set_work_offset("G55", {"X": 100.0, "Y": 50.0})
        assert ctl.set_work_rotation("G55", rotation_deg)
        _to(ctl, (*start, TOP - 4.0))
        _probe(ctl, ProbingRequest(ProbeWizard.OUTSIDE_CORNER, system="G55", x_dir=1, y_dir=1))
        assert not ctl.active_alarms, [a.cause for a in ctl.active_alarms]
        result = ctl.last_probing
        assert result is not None and result.written == "G55"
        assert (result.values["X"], result.values["Y"]) == pytest.approx(corner, abs=0.01)
        assert (ctl.work_offsets["G55"][0], ctl.work_offsets["G55"][1]) == pytest.approx(corner, abs=0.01)
    finally:
        ctl.shutdown()


def test_a_wrong_bore_says_so_under_the_wizard_s_name_not_its_subroutine_s_lines(
        qapp, config_path: Path, state_dir: Path) -> None:
    """The bore measures 24 mm where 20 were asked for: the alarm says what the wizard found,
    as "probing a bore: ...", without the subroutine file and line the operator never saw."""
    part = replace(BLOCK, feature=Feature.BORE, feature_x_mm=25.0, feature_y_mm=12.0, feature_radius_mm=12.0)
    ctl = _machine(qapp, config_path, state_dir)
    try:
        assert ctl.simulate_part(part)
        _to(ctl, (23.0, 12.0, TOP - 5.0))
        before = dict(ctl.work_offsets)
        _probe(ctl, ProbingRequest(ProbeWizard.BORE, system="G55", diameter_mm=20.0, tolerance_mm=0.5))
        assert ctl.state is MachineState.ALARM
        (alarm,) = [a for a in ctl.active_alarms if "the bore measures" in a.cause]
        assert re.fullmatch(r"probing a bore: the bore measures 24\.00\d+ mm across, not 20\.0+ mm within "
                            r"0\.50+ mm: nothing written", alarm.cause), alarm.cause
        assert ".ngc" not in alarm.cause and "line" not in alarm.cause and "ABORT" not in alarm.cause
        assert ctl.work_offsets == before
    finally:
        ctl.shutdown()


def test_a_missing_part_on_the_machine_is_an_alarm_and_writes_nothing(qapp, config_path: Path,
                                                                      state_dir: Path) -> None:
    ctl = _machine(qapp, config_path, state_dir)
    try:
        assert ctl.simulate_part(None)
        _to(ctl, (23.0, 12.0, TOP - 5.0))
        before = dict(ctl.work_offsets)
        _probe(ctl, ProbingRequest(ProbeWizard.BORE, system="G55", diameter_mm=20.0))
        assert ctl.state is MachineState.ALARM
        assert any("ended without contact" in a.cause for a in ctl.active_alarms)
        assert ctl.work_offsets == before and ctl.last_probing is None
    finally:
        ctl.shutdown()


def test_an_obstacle_on_the_machine_stops_the_move_with_the_alarm(qapp, config_path: Path,
                                                                  state_dir: Path) -> None:
    ctl = _machine(qapp, config_path, state_dir)
    try:
        assert ctl.simulate_part(BLOCK)
        _to(ctl, (-20.0 - R - 3.0, -18.0, TOP - 5.0))
        path = _Path(ctl)
        before = dict(ctl.work_offsets)
        _probe(ctl, ProbingRequest(ProbeWizard.OUTSIDE_CORNER, system="G55", along_mm=10.0))
        assert ctl.state is MachineState.ALARM
        (alarm,) = [a for a in ctl.active_alarms if "probe touched during positioning" in a.cause]
        # under the wizard's name, not the positioning subroutine's file and line
        assert alarm.cause == "probing an outside corner: probe touched during positioning"
        assert ctl.work_offsets == before
        # it stopped at the contact: the ball touched the part's side and stopped, never further
        # than the stop's overtravel (the search would have gone 10 mm on)
        tip = path.actual() - np.array([0.0, 0.0, PROBE.length_mm - R])
        deepest = min(BLOCK.distance(*p) for p in tip) - R
        assert -0.3 < deepest < 0.0, deepest
    finally:
        ctl.shutdown()


def test_a_wizard_is_refused_without_the_probe_in_the_spindle(ctl: MachineController) -> None:
    r = ctl.run_probing(ProbingRequest(ProbeWizard.Z_SURFACE, system="G55"))
    assert not r and "no tool is in the spindle, not the probe T99" in r.reason
    assert ctl.set_tool(Tool(99, 99, (("Z", 40.0),), 0.0, "no tip")) and ctl.set_tool_in_spindle(99)
    r = ctl.run_probing(ProbingRequest(ProbeWizard.Z_SURFACE, system="G55"))
    assert not r and "has no tip diameter" in r.reason


def test_a_cutter_in_the_spindle_makes_no_probing_move_in_a_wizard_or_in_mdi(ctl: MachineController) -> None:
    """The end mill T1 in the spindle: the wizard and a G38.2 typed in MDI are refused, naming
    the probe, and no axis moves; the probe itself is let through."""
    assert ctl.set_tool(PROBE) and ctl.set_tool(Tool(1, 1, (("Z", 40.0),), 6.0, "6 mm flat end mill"))
    assert ctl.set_tool_in_spindle(1)
    before = tuple(ctl.machine_position)
    r = ctl.run_probing(ProbingRequest(ProbeWizard.Z_SURFACE, system="G55"))
    assert not r and "T1 is in the spindle, not the probe T99" in r.reason
    r = ctl.mdi("G38.2 Z-10 F300")
    assert not r and "T1 is in the spindle, not the probe T99" in r.reason and "M61 Q99" in r.reason
    ctl.advance(1.0)
    assert tuple(ctl.machine_position) == before and ctl.state is MachineState.IDLE
    assert ctl.set_tool_in_spindle(99)
    assert ctl.mdi("G91 G38.3 Z-1 F300")                 # the probe may
    ctl.advance(2.0)
    assert ctl.machine_position[2] == pytest.approx(before[2] - 1.0, abs=1e-3)


def test_without_a_probe_named_no_tool_probes(qapp, config_path: Path, state_dir: Path) -> None:
    config_path.write_text(config_path.read_text().replace("\ntool = 99 ", "\n# tool = 99 ", 1))
    ctl = make_controller(config_path, state_dir)
    try:
        assert ctl.config.probe.tool is None
        assert ctl.set_tool(PROBE) and ctl.set_tool_in_spindle(99)
        r = ctl.run_probing(ProbingRequest(ProbeWizard.Z_SURFACE, system="G55"))
        assert not r and "no probe is named: set [probe] tool" in r.reason
        r = ctl.mdi("G38.3 Z-1 F300")
        assert not r and "no probe is named" in r.reason
    finally:
        ctl.shutdown()


def test_a_preview_says_why_without_a_refusal_and_probe_tool_is_enforced(qapp, config_path: Path,
                                                                         state_dir: Path) -> None:
    """The panel asks for the preview at every change: why it cannot run comes back without
    the refusal the status line shows. With ``[probe] tool`` only that tool probes."""
    ctl = make_controller(config_path, state_dir)       # the shipped mill names T99 the probe
    refused: list[tuple[str, str]] = []
    ctl.commandRefused.connect(lambda action, why: refused.append((action, why)))
    try:
        assert ctl.set_tool(PROBE) and ctl.set_tool(Tool(1, 1, (("Z", 40.0),), 6.0, "mill"))
        assert ctl.set_tool_in_spindle(1)
        req = ProbingRequest(ProbeWizard.Z_SURFACE, system="G55")
        preview = ctl.preview_probing(req)
        assert not preview and "T1 is in the spindle, not the probe T99" in preview.reason
        assert refused == []
        r = ctl.run_probing(req)                          # the command itself is refused, told
        assert not r and refused and "not the probe T99" in refused[-1][1]
        assert ctl.set_tool_in_spindle(99)
        assert ctl.preview_probing(req).probes
    finally:
        ctl.shutdown()


def test_a_slow_probe_feed_not_below_the_fast_one_is_refused(ctl: MachineController) -> None:
    """The edge is read at the slow probe: a slow feed above the fast one (the edge then read
    0.0039 mm off on the simulated machine) is refused, and nothing moves."""
    assert ctl.set_tool(PROBE) and ctl.set_tool_in_spindle(PROBE.number)
    before = tuple(ctl.machine_position)
    for slow in (400.0, 300.0):
        r = ctl.run_probing(ProbingRequest(ProbeWizard.Z_SURFACE, system="G55", fast_feed_mm_min=300.0,
                                           slow_feed_mm_min=slow))
        assert not r and f"the slow probe feed F{slow:g} must be below the fast one F300 mm/min" in r.reason
    ctl.advance(0.5)
    assert tuple(ctl.machine_position) == before
    assert ctl.preview_probing(ProbingRequest(ProbeWizard.Z_SURFACE, system="G55", fast_feed_mm_min=300.0,
                                              slow_feed_mm_min=30.0)).probes


def test_a_result_names_the_angle_and_the_diameter_never_an_axis_letter() -> None:
    from app.machine.model import ProbingResult

    res = ProbingResult(ProbeWizard.ANGLE, {"X": 1.0, "A": 12.3456, "D": 20.0}, "G55")
    assert res.said() == "X 1.0000 angle 12.3456° diameter 20.0000"
    assert res.text() == "probed (machine): X 1.0000 angle 12.3456° diameter 20.0000, written to G55"
