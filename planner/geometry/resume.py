"""Resuming a program part-way: split a move at path length u, build the remaining program,
the modal state (spindle, tool) as of a line, and a safe approach move to a start point.

Used by the machine controller after a fault (resume at the point where the drives stopped)
and for "run from line". Units: mm, deg, s; positions are machine coordinates.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace

import numpy as np

from planner.core.errors import PlannerError
from planner.core.movestore import MoveStore
from planner.core.program import (
    Arc,
    Event,
    EventKind,
    Move,
    MoveKind,
    OverrideLocks,
    Program,
    SpindleSpeed,
    TableRef,
    ToolNumber,
    arc_length_mm,
    arc_param_at_length,
)

__all__ = [
    "Approach",
    "ModalState",
    "approach_moves",
    "last_safe_height",
    "locate",
    "modal_state_at",
    "modal_state_before_move",
    "probe_move_at",
    "carry_overrides",
    "program_from_moves",
    "program_from_store",
    "reads_before",
    "remaining_program",
    "split_move",
]


def _path_length(a: np.ndarray, b: np.ndarray, rotary: tuple[bool, ...]) -> float:
    """LinuxCNC's feed rule: length over the linear axes if > 0, else over rotary degrees."""
    d = np.asarray(b, dtype=float) - np.asarray(a, dtype=float)
    lin = np.array([not r for r in rotary])
    length = float(np.linalg.norm(d[lin])) if lin.any() else 0.0
    if length > 0.0:
        return length
    return float(np.linalg.norm(d[~lin])) if (~lin).any() else 0.0


def split_move(move: Move, u_mm: float, at: tuple[np.ndarray, float] | None = None) -> Move:
    """The part of ``move`` from path length ``u_mm`` to its end (same end point exactly).

    Lines: a line from the point at u. Arcs/helices/spirals: the same circle with the start
    angle advanced, the sweep, rise and (spiral) start radius reduced, so the geometry of the
    tail is exactly the geometry of the original over [u, length]. ``at``: the point at u and
    an arc's angle fraction there, where the caller has them already.
    """
    length = move.length_mm
    u = min(max(float(u_mm), 0.0), length)
    start = at[0].copy() if at is not None else move.evaluate(np.array([u]))[0][0]
    if u >= length:
        start = move.end.copy()
    rest = max(length - u, 0.0)
    if move.blend is not None:
        # the same pair, entered further along
        return replace(move, start=start, length_mm=rest,
                       blend=replace(move.blend, s0_mm=move.blend.s0_mm + u))
    if move.arc is None:
        return replace(move, start=start, length_mm=rest)
    arc = move.arc
    if at is not None:
        t = at[1]
    else:
        t = float(arc_param_at_length(arc, np.array([u]), length)[0]) if length > 0 else 1.0
    new_arc = arc_part(arc, t, 1.0)
    new_len = arc_length_mm(new_arc) if rest > 0.0 else 0.0
    return replace(move, start=start, arc=new_arc, length_mm=new_len)


def arc_part(arc: Arc, t0: float, t1: float) -> Arc:
    """The same circle (or spiral, or helix) from angle fraction t0 to t1 of ``arc``."""
    dr = arc.radius_end_mm - arc.radius_start_mm
    sweep = arc.sweep_rad * (t1 - t0)
    return replace(
        arc,
        radius_start_mm=arc.radius_start_mm + dr * t0,
        radius_end_mm=arc.radius_start_mm + dr * t1,
        start_angle_rad=arc.start_angle_rad + arc.sweep_rad * t0,
        sweep_rad=sweep,
        rise_mm=arc.rise_mm * (t1 - t0),
        turns=max(1, math.ceil(abs(sweep) / (2.0 * math.pi) - 1e-12)),
    )


def head_move(move: Move, u_mm: float, at: tuple[np.ndarray, float] | None = None) -> Move:
    """The part of ``move`` from its start to path length ``u_mm`` (same start exactly):
    lines end at the point at u; arcs keep their circle with the sweep, rise and (spiral) end
    radius reduced. ``at``: the point at u and an arc's angle fraction there, where the caller
    has them already."""
    length = move.length_mm
    u = min(max(float(u_mm), 0.0), length)
    end = at[0].copy() if at is not None else move.evaluate(np.array([u]))[0][0]
    if move.arc is None:
        return replace(move, end=end, length_mm=u)
    arc = move.arc
    if at is not None:
        t = at[1]
    else:
        t = float(arc_param_at_length(arc, np.array([u]), length)[0]) if length > 0 else 0.0
    new_arc = arc_part(arc, 0.0, t)
    return replace(move, end=end, arc=new_arc, length_mm=arc_length_mm(new_arc))


def program_from_moves(template: Program, moves: list[Move], events: list[Event],
                       start_position: np.ndarray, name: str | None = None) -> Program:
    """A Program of ``moves`` as a store, numbered 0..n-1 (``program_from_store``)."""
    return program_from_store(template, MoveStore.from_moves(moves, np.asarray(start_position, dtype=float)),
                              events, start_position, name)


def program_from_store(template: Program, moves: MoveStore, events: list[Event],
                       start_position: np.ndarray, name: str | None = None) -> Program:
    """A Program of the moves of ``moves`` (a piece of another program's store is taken as it
    is, no move made of it), numbered 0..n-1 (events' ``after_move`` must already refer to the
    new indices). What events name (parameter sets, tools, probes) is the template's."""
    start = np.asarray(start_position, dtype=float).copy()
    return Program(name=name or template.name, axes=template.axes, rotary=template.rotary,
                   moves=moves, events=tuple(events), start_position=start,
                   line_count=template.line_count,
                   parameter_sets=template.parameter_sets, tool_sets=template.tool_sets,
                   probes=template.probes, inputs=template.inputs)


def remaining_program(program: Program, move_index: int, u_mm: float = 0.0,
                      line: int | None = None) -> Program:
    """The program from path length ``u_mm`` of move ``move_index`` to its end.

    Events after earlier moves are dropped (their effect is restored with ``modal_state_at``);
    events after the split move and later keep their place. ``line``: the run starts at that
    source line, so what reads the machine on it before the move (a probe's arming, M66) is
    kept, at the start.
    """
    n = len(program.moves)
    if not 0 <= move_index < n:
        raise PlannerError(f"move index {move_index} outside 0..{n - 1}")
    first = program.moves[move_index]
    tail = split_move(first, u_mm) if u_mm > 0.0 else first
    moves = [tail, *program.moves[move_index + 1:]]
    events = [replace(e, after_move=e.after_move - move_index) for e in program.events
              if e.after_move >= move_index]
    if line is not None and u_mm <= 0.0:
        reads = [replace(e, after_move=-1) for e in program.events
                 if e.after_move == move_index - 1 and e.line >= line
                 and e.kind in (EventKind.PROBE_START, EventKind.INPUT)]
        events = reads + events
    events = carry_overrides(program, move_index, events)
    # Drop a zero-length tail (resuming exactly at a move's end).
    if tail.length_mm <= 1e-12 and len(moves) > 1:
        moves = moves[1:]
        events = [replace(e, after_move=max(e.after_move - 1, -1)) for e in events]
    return program_from_moves(program, moves, events, tail.start)


def carry_overrides(program: Program, first_move: int, events: list[Event]) -> list[Event]:
    """``events`` (of the moves from ``first_move`` on) with the overrides in force for that
    move put first: a restart inside a tap or after M49 keeps the overrides off, though the
    event that turned them off comes before it."""
    locks = program.override_locks
    if locks is None or not 0 <= first_move < len(locks) or not locks[first_move]:
        return events
    bits = int(locks[first_move])
    line = program.moves[first_move].line
    return [Event(EventKind.OVERRIDES, line, -1, OverrideLocks(bits),
                  "overrides off as before the restart point"), *events]


def reads_before(program: Program, move_index: int, line: int) -> list[Event]:
    """The probes and M66 (PROBE, INPUT events) a run starting at move ``move_index``, from
    source line ``line``, would not make again: those before it. What follows them was read
    with their results (or with assumed ones)."""
    return [e for e in program.events if e.kind in (EventKind.PROBE, EventKind.INPUT)
            and (e.after_move < move_index - 1 or (e.after_move == move_index - 1 and e.line < line))]


def probe_move_at(program: Program, move_index: int) -> Event | None:
    """The PROBE event of move ``move_index`` when it is a probe move (G38.x), else None."""
    starts = {e.payload_as(TableRef).index for e in program.events
              if e.kind is EventKind.PROBE_START and e.after_move == move_index - 1}
    return next((e for e in program.events if e.kind is EventKind.PROBE and e.after_move == move_index
                 and e.payload_as(TableRef).index in starts), None)


@dataclass(frozen=True, slots=True)
class ModalState:
    """What a run from a line must restore (positions and offsets are already in the moves)."""

    spindle: SpindleSpeed = SpindleSpeed(0, 0.0)
    tool: int = 0
    feed_mm_s: float = 0.0  # feed of the first move at or after the line (0 if none)


def _spindle_and_tool(events: Iterable[Event], reached: Callable[[Event], bool]) -> tuple[SpindleSpeed, int]:
    """The spindle and the tool after the events before the first ``reached`` one."""
    spindle = SpindleSpeed(0, 0.0)
    tool = 0
    for e in events:
        if reached(e):
            break
        if e.kind is EventKind.SPINDLE:
            spindle = e.payload_as(SpindleSpeed)
        elif e.kind in (EventKind.TOOL_CHANGE, EventKind.TOOL_SET):   # in the spindle (T only selects)
            tool = e.payload_as(ToolNumber).number
    return spindle, tool


def modal_state_at(program: Program, line: int) -> ModalState:
    """Spindle, tool and feed in effect when execution reaches source line ``line``."""
    spindle, tool = _spindle_and_tool(program.events, lambda e: e.line >= line)
    feed = 0.0
    for m in program.moves:
        if m.line >= line and m.kind is not MoveKind.RAPID:
            feed = float(m.feed_mm_s)
            break
    return ModalState(spindle=spindle, tool=tool, feed_mm_s=feed)


def modal_state_before_move(program: Program, move_index: int) -> ModalState:
    """Spindle, tool and feed in effect when move ``move_index`` starts (events after earlier
    moves, including those written on the move's own line before it, have happened)."""
    spindle, tool = _spindle_and_tool(program.events, lambda e: e.after_move >= move_index)
    m = program.moves[move_index] if 0 <= move_index < len(program.moves) else None
    feed = float(m.feed_mm_s) if m is not None and m.kind is not MoveKind.RAPID else 0.0
    return ModalState(spindle=spindle, tool=tool, feed_mm_s=feed)


def locate(program: Program, line: int) -> int:
    """Index of the first move at or after source line ``line`` (PlannerError if none), found
    in the program's line column (no Move made for the moves before it: a restart near the end
    of a 10,000,000-line program)."""
    at = np.flatnonzero(program.move_lines >= line)
    if not len(at):
        raise PlannerError(f"no motion at or after line {line}")
    return int(program.moves[int(at[0])].index)


@dataclass(frozen=True, slots=True)
class Approach:
    """The way from where the machine stands to a restart point: ``moves`` (machine
    coordinates) and where the spindle is started: after move ``spindle_after`` (-1: before the
    first), the last one at the clearance height, so the tool never goes down without it."""

    moves: tuple[Move, ...]
    spindle_after: int


def last_safe_height(program: Program, move_index: int, axis: int) -> float | None:
    """The height (machine coordinate of ``axis``) of the last rapid move before move
    ``move_index`` that ended at or above where that move starts: the program's own retract
    plane there. None when the program made no such move."""
    if not 0 <= move_index < len(program.moves):
        return None
    z_target = float(program.moves[move_index].start[axis])
    for m in reversed(program.moves[:move_index]):
        if m.kind is MoveKind.RAPID and float(m.end[axis]) >= z_target:
            return float(m.end[axis])
    return None


def approach_moves(current: np.ndarray, target: np.ndarray, axes: tuple[str, ...],
                   rotary: tuple[bool, ...], *, clearance: float, feed_mm_s: float,
                   safe_height: float | None = None, retract_axis: str = "Z") -> Approach:
    """A restart approach that never moves sideways low: rapid up to ``clearance`` (a machine
    height; not down if the tool is higher already), rapid across at that height, [spindle],
    rapid down to ``safe_height`` (the program's own retract plane there, if given and above
    the target), then down to the target at ``feed_mm_s``. Without a retract axis among the
    axes: one straight rapid, the spindle before it."""
    cur = np.asarray(current, dtype=float).copy()
    tgt = np.asarray(target, dtype=float)
    if not (feed_mm_s > 0.0 and math.isfinite(feed_mm_s)):
        raise PlannerError(f"approach feed must be a positive number, got {feed_mm_s}")
    legs: list[tuple[np.ndarray, np.ndarray, bool]] = []   # (from, to, rapid)
    spindle_after = -1
    if retract_axis in axes:
        k = axes.index(retract_axis)
        high = max(cur[k], tgt[k], clearance)
        up, across = cur.copy(), tgt.copy()
        up[k] = across[k] = high
        legs += [(cur, up, True), (up, across, True)]
        spindle_after = 1
        low = across
        if safe_height is not None and tgt[k] < safe_height < high:
            low = tgt.copy()
            low[k] = safe_height
            legs.append((across, low, True))
        legs.append((low, tgt.copy(), False))
    else:
        legs.append((cur, tgt.copy(), True))
    moves: list[Move] = []
    last_high_leg, spindle_after = spindle_after, -1
    pos = cur
    for i, (_, b, rapid) in enumerate(legs):
        a, length = pos, _path_length(pos, b, rotary)
        if length <= 1e-12:
            continue
        pos = b
        moves.append(Move(index=len(moves), line=0, kind=MoveKind.RAPID if rapid else MoveKind.LINE,
                          start=a.copy(), end=b.copy(), feed_mm_s=math.inf if rapid else float(feed_mm_s),
                          length_mm=length, arc=None, exact_stop=True))
        if i <= last_high_leg:
            spindle_after = len(moves) - 1
    return Approach(tuple(moves), spindle_after)
