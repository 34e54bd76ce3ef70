"""The snapshot read as OPC 40501 values: every combination of state, activity, resume point
and alarms gives one stack-light colour at most, and the channel's state says what moves."""

from __future__ import annotations

from dataclasses import replace

from hypothesis import given
from hypothesis import strategies as st

from app.machine.model import (
    Activity,
    Alarm,
    AlarmState,
    BusStatus,
    ControllerSnapshot,
    HoldKind,
    MachineState,
    Prompt,
    RunSummary,
    Severity,
    SpindleState,
)
from opcua_server.mapping import (
    ChannelState,
    MachineOperationMode,
    MessageTracker,
    ProgramState,
    ProgramTracker,
    stacklight,
    view_of,
)


def snap(state: MachineState = MachineState.IDLE, activity: Activity = Activity.NONE, **changes: object
         ) -> ControllerSnapshot:
    base = ControllerSnapshot(
        state=state, activity=activity, axes=("X", "Y", "Z"), machine_pos=(0.0, 0.0, 0.0),
        work_pos=(0.0, 0.0, 0.0), homed=(True, True, True), active_offset="G54", line=0, progress=0.0,
        remaining_s=0.0, path_speed_mm_s=0.0, feed_override_pct=100.0, rapid_override_pct=100.0,
        single_block=False, optional_stop=False, block_delete=False, spindle=SpindleState(), alarms=(),
        bus=BusStatus())
    return replace(base, **changes)  # type: ignore[arg-type]


def _alarm(i: int, severity: Severity, active: bool = True) -> Alarm:
    return Alarm(id=i, time_s=0.0, source="drive X", cause=f"cause {i}", severity=severity,
                 state=AlarmState.ACTIVE if active else AlarmState.ACKNOWLEDGED, code=f"code{i}")


@given(state=st.sampled_from(MachineState), activity=st.sampled_from(Activity),
       resume=st.integers(0, 3), alarmed=st.booleans(), program=st.booleans())
def test_one_colour_at_most_and_the_channel_says_what_moves(
        state: MachineState, activity: Activity, resume: int, alarmed: bool, program: bool) -> None:
    alarms = (_alarm(1, Severity.STOP),) if alarmed else ()
    s = snap(state, activity, resume_line=resume, alarms=alarms, program_name="p.ngc" if program else "")
    light = stacklight(s)
    assert [light.red, light.yellow, light.green].count(True) <= 1
    assert light.red == (state in (MachineState.ESTOP, MachineState.ALARM) or alarmed)
    assert light.green == (state in (MachineState.RUNNING, MachineState.HOMING) and not light.red)
    view = view_of(s, ProgramState.INITIALIZING)
    assert (view.channel_state is ChannelState.ACTIVE) == (state in (MachineState.RUNNING,
                                                                     MachineState.HOMING))
    if state is MachineState.HOLD:
        assert view.channel_state is ChannelState.INTERRUPTED
    if state is MachineState.HOMING:
        assert view.operation_mode is MachineOperationMode.SETUP


def test_the_program_state_machine_over_a_run_a_stop_and_a_new_program() -> None:
    t = ProgramTracker()
    loaded = snap(program_name="a.ngc", program_path="/p/a.ngc", program_lines=10, estimated_cycle_s=5.0)
    assert t.state(loaded) is ProgramState.INITIALIZING
    running = replace(loaded, state=MachineState.RUNNING, activity=Activity.PROGRAM)
    assert t.state(running) is ProgramState.RUNNING
    held = replace(running, state=MachineState.HOLD, hold_kind=HoldKind.FEED_HOLD)
    assert t.state(held) is ProgramState.INTERRUPTED
    stopped = replace(loaded, resume_line=4)
    assert t.state(stopped) is ProgramState.INTERRUPTED
    aborted = replace(loaded, last_run=RunSummary(name="a.ngc", completed=False, cycle_time_s=1.0,
                                                  estimated_s=5.0, last_line=4))
    assert t.state(aborted) is ProgramState.ABORTED
    t.state(running)
    ended = replace(loaded, last_run=RunSummary(name="a.ngc", completed=True, cycle_time_s=5.0,
                                                estimated_s=5.0, last_line=10))
    assert t.state(ended) is ProgramState.ENDED
    other = replace(ended, program_name="b.ngc", program_path="/p/b.ngc")
    assert t.state(other) is ProgramState.INITIALIZING


def test_each_alarm_is_told_once_raised_and_once_acknowledged_and_a_prompt_once() -> None:
    m = MessageTracker()
    old = _alarm(1, Severity.WARNING, active=False)
    assert m.events(snap(alarms=(old,))) == []            # history before the server started
    new = _alarm(2, Severity.QUICK_STOP)
    raised = m.events(snap(alarms=(old, new)))
    assert [(e.identifier, e.severity, e.acknowledged, e.needs_acknowledgement) for e in raised] == \
        [("alarm-2", 800, False, True)]
    assert m.events(snap(alarms=(old, new))) == []
    acked = m.events(snap(alarms=(old, replace(new, state=AlarmState.ACKNOWLEDGED))))
    assert [(e.identifier, e.acknowledged) for e in acked] == [("alarm-2", True)]
    prompt = Prompt(kind=HoldKind.TOOL_CHANGE, line=7, tool=2, text="insert tool")
    told = m.events(snap(prompt=prompt))
    assert [e.message for e in told] == ["line 7: insert tool (tool T2)"]
    assert m.events(snap(prompt=prompt)) == []


def test_an_alarm_s_condition_is_active_until_cleared_and_retained_until_acknowledged() -> None:
    m = MessageTracker()
    m.events(snap())
    stop, warning = _alarm(5, Severity.STOP), _alarm(6, Severity.WARNING)
    raised = m.events(snap(alarms=(stop, warning)))
    assert [(e.identifier, e.active, e.acked_state, e.retain) for e in raised] == \
        [("alarm-5", True, False, True), ("alarm-6", True, True, True)]
    cleared = m.events(snap(alarms=(replace(stop, state=AlarmState.ACKNOWLEDGED),
                                    replace(warning, state=AlarmState.ACKNOWLEDGED))))
    assert [(e.identifier, e.active, e.acked_state, e.retain) for e in cleared] == \
        [("alarm-5", False, True, False), ("alarm-6", False, True, False)]
    # a record (raised acknowledged) is told as raised, then cleared
    record = _alarm(7, Severity.INFO, active=False)
    told = m.events(snap(alarms=(record,)))
    assert [(e.identifier, e.active, e.retain) for e in told] == \
        [("alarm-7", True, True), ("alarm-7", False, False)]


def test_each_alarm_has_the_condition_class_of_what_it_is_about() -> None:
    from opcua_server.mapping import ConditionClass, condition_class

    assert condition_class(replace(_alarm(1, Severity.ESTOP), source="operator")) is ConditionClass.SAFETY
    assert condition_class(replace(_alarm(2, Severity.QUICK_STOP), source="drive X")) is ConditionClass.SYSTEM
    assert condition_class(replace(_alarm(3, Severity.WARNING), source="opcua")) is ConditionClass.SYSTEM
    assert condition_class(replace(_alarm(4, Severity.STOP), source="planner")) is ConditionClass.PROCESS
