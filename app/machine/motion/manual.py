"""Manual motion: continuous and incremental jog, MDI. Every motion is planned and checked like a
program (soft limits on the whole path); a continuous jog is planned to the soft limit, so a
lost release stops there.
"""

from __future__ import annotations

from collections.abc import Callable

from app.machine.errors import MachineError
from app.machine.model import Activity, CommandResult, SpindleState
from app.machine.motion.jobs import Job, JobTerms
from app.machine.motion.making import JobMaker
from app.machine.motion.refusals import machine_abilities, violation_issues
from app.machine.motion.streamer import Streamer
from app.machine.ports import (
    CoordinatesView,
    JogInterlocks,
    OutputSwitch,
    PositionsView,
    RunModes,
    Settings,
    SpindleDrive,
    ToolView,
)
from app.machine.state.gate import Action, guarded
from app.machine.state.states import StateMachine
from planner.core.errors import PlannerError, ProgramError
from planner.core.movestore import MoveStore
from planner.core.program import (
    CoolantSwitch,
    EventKind,
    Move,
    MoveKind,
    OutputLevel,
    Program,
    SpindleSpeed,
    TableRef,
    ToolNumber,
)
from planner.gcode.lexer import LexError, compact
from planner.pipeline import Reread, SoftLimitError, load

__all__ = ["JOG_INCREMENTS", "ManualMotion"]

JOG_INCREMENTS: tuple[float, ...] = (0.001, 0.01, 0.1, 1.0)  # mm or degrees


class ManualMotion:
    """Jog and MDI (``controller.manual``)."""

    def __init__(self, settings: Settings, states: StateMachine, positions: PositionsView,
                 coordinates: CoordinatesView, tools: ToolView, spindle: SpindleDrive,
                 outputs: OutputSwitch, modes: RunModes, motion: Streamer, jobs: JobMaker,
                 interlocks: JogInterlocks) -> None:
        self._settings = settings
        self._interlocks = interlocks
        self._states = states
        self._positions = positions
        self._coordinates = coordinates
        self._tools = tools
        self._spindle = spindle
        self._outputs = outputs
        self._modes = modes
        self._motion = motion
        self._jobs = jobs

    @property
    def gate(self) -> StateMachine:
        return self._states

    def show_message(self, text: str) -> None:
        """A message for the operator (the status line and the alarm log)."""
        self._motion.show_message(text)

    def _single_axis_program(self, i: int, target: float, feed_mm_s: float, name: str) -> Program:
        cfg = self._settings.config
        cur = self._positions.machine_pos()
        end = cur.copy()
        end[i] = target
        rotary = cfg.machine.rotary
        length = abs(target - cur[i])
        move = Move(
            index=0,
            line=0,
            kind=MoveKind.LINE,
            start=cur.copy(),
            end=end,
            feed_mm_s=feed_mm_s,
            length_mm=length,
            arc=None,
            exact_stop=True,
        )
        return Program(
            name=name,
            axes=cfg.axes,
            rotary=rotary,
            moves=MoveStore.from_moves((move,), cur),
            events=(),
            start_position=cur.copy(),
            line_count=0,
        )

    @guarded(Action.JOG)
    def jog_start(self, axis: str | int, direction: int, speed_fraction: float = 1.0) -> CommandResult:
        """Continuous jog of one axis toward + (1) or - (-1) at ``speed_fraction`` of the jog
        speed. The motion is planned to end at the soft limit, so a lost release stops exactly
        there; ``jog_stop`` is a jerk-limited stop.
        """
        states, cfg = self._states, self._settings.config
        try:
            i = states.axis(axis)
        except MachineError as exc:
            return states.refuse(Action.JOG, str(exc))
        if direction not in (1, -1):
            return states.refuse(Action.JOG, f"direction must be +1 or -1, got {direction}")
        ax = cfg.machine.axes[i]
        cur = float(self._positions.machine_pos()[i])
        # a wrapped rotary axis turns without end: the jog runs until released (100 turns at most)
        if ax.wrapped:
            limit = cur + direction * 36_000.0
        elif self._between_switches(i):
            limit = cur + direction * (ax.max_pos - ax.min_pos)     # to the limit switch from anywhere
        else:
            limit = ax.max_pos if direction > 0 else ax.min_pos
        if (limit - cur) * direction <= 1e-9:
            return states.refuse(Action.JOG, f"axis {ax.name} is at its soft limit {limit:g}")
        why = self._toward_limit(i, direction)
        if why:
            return states.refuse(Action.JOG, why)
        frac = min(max(float(speed_fraction), 0.01), 1.0)
        feed = self._jog_feed(cfg.controller.jog_speed_mm_s * frac, ax.v_motion)
        prog = self._single_axis_program(i, limit, feed, f"jog {ax.name}{'+' if direction > 0 else '-'}")
        self._motion.start_job(self._jobs.make_job(Activity.JOG, prog, prog.name, overrides=False))
        return states.ok(Action.JOG)

    def _between_switches(self, i: int) -> bool:
        """An unhomed axis with both limit switches jogs between them, not between its soft
        limits: those are machine coordinates, which mean nothing until it is homed (LinuxCNC
        jogs an unhomed joint the same way). Without both switches the soft limits stay, taken
        from the position the control last knew."""
        return not self._positions.homed[i] and self._interlocks.has_limit_switches(i)

    def _toward_limit(self, i: int, direction: int) -> str:
        """Why a jog of axis ``i`` toward ``direction`` is refused by a limit switch ("" when not):
        an axis on its switch moves only away from it."""
        side = self._interlocks.limit_side(i)
        if side and side == direction:
            name = self._settings.config.axes[i]
            return (f"axis {name} is on its {'positive' if side > 0 else 'negative'} limit switch: it may "
                    f"only jog away from it ({name}{'-' if side > 0 else '+'})")
        return ""

    def _jog_feed(self, feed: float, v_max: float) -> float:
        """The jog's speed: the one asked, within the axis' and, with the door open, the setup
        speed."""
        cap = self._interlocks.jog_speed_cap()
        return min(feed, v_max, cap if cap is not None and cap > 0.0 else feed)

    def jog_stop(self, axis: str | int | None = None) -> CommandResult:
        """Release: jerk-limited stop of the jog (harmless when nothing jogs)."""
        self._motion.stop_job("jog released", only=Activity.JOG)
        return self._states.ok("jog_stop")

    @guarded(Action.JOG)
    def jog_increment(self, axis: str | int, step: float, direction: int = 1) -> CommandResult:
        """Move one axis by ``direction * step`` (0.001 / 0.01 / 0.1 / 1 mm or degrees), refused
        when the target is beyond the soft limit (an unhomed axis between limit switches: by
        them).
        """
        states, cfg = self._states, self._settings.config
        try:
            i = states.axis(axis)
        except MachineError as exc:
            return states.refuse(Action.JOG, str(exc))
        step = abs(float(step))
        if not any(abs(step - s) < 1e-12 for s in JOG_INCREMENTS):
            return states.refuse(Action.JOG, f"increment must be one of {JOG_INCREMENTS}, got {step:g}")
        ax = cfg.machine.axes[i]
        why = self._toward_limit(i, 1 if direction > 0 else -1)
        if why:
            return states.refuse(Action.JOG, why)
        target = float(self._positions.machine_pos()[i]) + (1 if direction > 0 else -1) * step
        within = ax.min_pos - 1e-9 <= target <= ax.max_pos + 1e-9
        if not ax.wrapped and not self._between_switches(i) and not within:
            return states.refuse(
                Action.JOG,
                f"axis {ax.name} would reach {target:.4f}, beyond its soft limit "
                f"[{ax.min_pos:g}, {ax.max_pos:g}]",
            )
        feed = self._jog_feed(cfg.controller.jog_speed_mm_s, ax.v_motion)
        prog = self._single_axis_program(i, target, feed,
                                         f"jog {ax.name} {step:g}")
        self._motion.start_job(self._jobs.make_job(Activity.JOG, prog, prog.name, overrides=False))
        return states.ok(Action.JOG)

    def _read(self, text: str, name: str, action: str, quiet: bool = False
              ) -> tuple[Program, Reread] | CommandResult:
        """``text`` read from where the machine is, as a program is checked: parsed (the reader
        kept, to read it again with what a probe or M66 reads), within the soft limits, its
        probing possible on this machine. The refusal otherwise (``quiet``: not told to the
        panel, for a preview that is only looked at)."""
        spindle = self._spindle.spindle
        refuse = self._states.refuse if not quiet else (lambda a, why: CommandResult(False, str(a), why))
        try:
            # the one load, as a program's (its order: read, refuse, limits), without blending
            # and for blocks that need not move
            loaded = load(text, name, self._coordinates.machine(), lambda p: p,
                          start_position=self._positions.machine_pos(), tools=self._tools.table,
                          tool_in_spindle=self._tools.in_spindle,
                          spindle=(spindle.direction, spindle.rpm),
                          parameters=dict(self._coordinates.parameters),
                          block_delete=self._modes.block_delete, tool_offset=self._coordinates.start_offset(),
                          abilities=machine_abilities(self._settings.config), blend=False,
                          require_motion=False)
        except SoftLimitError as exc:
            return refuse(action, f"soft limit: {violation_issues([exc.violations[0]])[0].message}")
        except ProgramError as exc:
            return refuse(action, "; ".join(e.message for e in exc.errors))
        except PlannerError as exc:
            return refuse(action, str(exc))
        return loaded.program, loaded.reread

    def _start(self, prog: Program, read: Reread, name: str, action: str,
               when_done: Callable[[Job], None] | None = None, reason: str = "",
               steps: dict[int, str] | None = None) -> CommandResult:
        """Run ``prog`` (read by ``_read``) as an MDI job; ``when_done(job)`` once it has all run."""
        terms = JobTerms(reason=reason, steps=tuple(sorted((steps or {}).items())), when_done=when_done,
                         reread=read)
        try:
            job = self._jobs.make_job(Activity.MDI, prog, name, terms=terms)
        except PlannerError as exc:
            return self._states.refuse(action, f"planner: {exc}")
        self._motion.start_job(job)
        return self._states.ok(action)

    def check_routine(self, text: str, name: str, action: str) -> Program | CommandResult:
        """A few blocks the controller wrote, read and checked as ``run_routine`` would run
        them (the path to draw before the operator confirms), or why not (not told to the
        panel: a preview is asked for at every change of its inputs)."""
        read = self._read(text, name, action, quiet=True)
        return read if isinstance(read, CommandResult) else read[0]

    def run_routine(self, text: str, name: str, action: str,
                    when_done: Callable[[Job], None] | None = None, reason: str = "",
                    steps: dict[int, str] | None = None) -> CommandResult:
        """A few blocks the controller wrote (tool measurement): read, checked and run as MDI
        is; ``when_done(job)`` once they have all run. ``reason``: what the state says meanwhile
        ("measuring tool T1"); ``steps``: what each line does, named in its errors instead of
        the line of a routine the operator never saw."""
        why = self._states.claim(action)
        if why:
            return self._states.refuse(action, why)
        read = self._read(text, name, action)
        if isinstance(read, CommandResult):
            return read
        return self._start(*read, name, action, when_done, reason, steps)

    @guarded(Action.MDI)
    def mdi(self, block: str) -> CommandResult:
        """Execute one G-code block with the active work offset and the same checks as a program
        (parse, soft limits on the whole path, homed rule).
        """
        states, action = self._states, Action.MDI
        text = block.strip()
        if not text:
            return states.refuse(action, "empty block")
        if "\n" in text:
            return states.refuse(action, "MDI takes one block (one line)")
        active = self._coordinates.active_offset
        if active != "G54":
            text = f"{active} {text}"
        checked = self._read(text, "MDI", action)
        if isinstance(checked, CommandResult):
            return checked
        prog, read = checked
        cfg = self._settings.config
        why = (_mdi_refusal(prog, cfg.controller.spindle_max_rpm) or _mdi_stands_alone(prog, block))
        if not why and any(ev.kind in (EventKind.PROBE_START, EventKind.PROBE) for ev in prog.events):
            why = cfg.probe.probe_refusal(self._tools.in_spindle)
        if why:
            return states.refuse(action, why)
        if not prog.moves:
            for ev in prog.events:
                if ev.kind is EventKind.SPINDLE:
                    speed = ev.payload_as(SpindleSpeed)
                    self._spindle.apply_spindle(SpindleState(direction=speed.direction, rpm=speed.rpm))
                elif ev.kind is EventKind.TOOL_SET:
                    res = self._tools.set_tool_in_spindle(ev.payload_as(ToolNumber).number)
                    if not res:
                        return states.refuse(action, res.reason)
                elif ev.kind is EventKind.OUTPUT:      # M64 P1 ... typed in MDI
                    output = ev.payload_as(OutputLevel)
                    why = self._outputs.set_output(output.number, output.on)
                    if why:
                        return states.refuse(action, why)
                elif ev.kind is EventKind.COOLANT:     # M7, M8, M9 typed in MDI
                    why = self._outputs.set_coolant(ev.payload_as(CoolantSwitch).switch)
                    if why:
                        return states.refuse(action, why)
                elif ev.kind is EventKind.MESSAGE:     # (MSG,...) typed in MDI
                    self._motion.show_message(ev.message)
                elif ev.kind is EventKind.TOOL_DATA:   # G10 L1/L10/L11 typed in MDI
                    self._tools.set_by_program(prog.tool_sets[ev.payload_as(TableRef).index])
                elif ev.kind is EventKind.OFFSETS:     # G10, G92, G52, G28.1 ... typed in MDI
                    self._coordinates.apply_parameters(prog.parameter_sets[ev.payload_as(TableRef).index])
                elif ev.kind is EventKind.END:  # M2/M30: the end of a program: spindle off, reset
                    self._spindle.apply_spindle(SpindleState(direction=0, rpm=self._spindle.spindle.rpm))
                    states.reset()
            return states.ok(action)
        return self._start(prog, read, "MDI", action)


# What an MDI block may not do, and why: every block either does what it says or is refused.
_NOT_IN_MDI = {
    EventKind.TOOL_CHANGE: "M6 runs in a program; in MDI put the tool in by hand and say which it is "
                           "with M61 Q<n> (or on the Tools page)",
    EventKind.PAUSE: "M0 pauses a running program; an MDI block has nothing to pause",
    EventKind.OPTIONAL_PAUSE: "M1 pauses a running program; an MDI block has nothing to pause",
    EventKind.TOOL: "T selects the tool for a program's M6; in MDI say which tool is in the spindle with "
                    "M61 Q<n>",
    # an MDI block is read on its own: #5399 would end with it (the Diagnostics page shows the inputs)
    EventKind.INPUT: "M66 reads an input for the program that follows it; an MDI block keeps no "
                     "value for the next one (the Diagnostics page shows the inputs)",
}


def _mdi_stands_alone(prog: Program, block: str) -> str:
    """An MDI block is read on its own: its modes, F, S and parameters end with it. A block
    that would only set them would return OK and change nothing, and cutter compensation would
    end without its exit move: both are refused with the way to say it in one block."""
    if any(tok in ("G41", "G42", "G41.1", "G42.1") for _, text in prog.modal for tok in text.split()):
        return ("cutter radius compensation (G41/G42) works across the moves of a program; an MDI "
                "block stands alone, so it would end without its exit move: run it in a program")
    if not prog.moves and any(e.kind is EventKind.OVERRIDES for e in prog.events):
        return ("M48-M51 switch the overrides for the moves that follow them; an MDI block stands alone: "
                "put the code in the block with the move (tapping cycles turn them off by themselves)")
    if prog.moves or prog.events:
        return ""
    try:
        code = compact(block)
    except LexError:
        code = block.strip()
    if not code:
        return ""                                # a comment: it says nothing, and does nothing
    return ("this block moves nothing and changes nothing that lasts: an MDI block stands alone (its "
            "modes, F, S and parameters end with it); put them in the block with the move, e.g. "
            "G91 G1 X10 F500")


def _mdi_refusal(prog: Program, spindle_max_rpm: float) -> str:
    kinds = {ev.kind for ev in prog.events}
    for ev in prog.events:
        rpm = ev.payload_as(SpindleSpeed).rpm if ev.kind is EventKind.SPINDLE else 0.0
        if rpm > spindle_max_rpm:
            return (f"S{rpm:g} is over the spindle's maximum of {spindle_max_rpm:g} rpm "
                    "([controller] spindle_max_rpm)")
    for kind, why in _NOT_IN_MDI.items():        # in this order: "M6 T5" is about M6
        if kind in kinds:
            return why
    if EventKind.DWELL in kinds and not prog.moves:
        return "G4 dwells between the moves of a program; a block without motion has nothing to wait for"
    return ""
