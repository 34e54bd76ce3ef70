"""The controller's sentences in the panel's language.

The controller (``app.machine``) and the worker speak English: their messages are built with
values in them ("following error on axis X: +1.2000 exceeds window 1 ..."). The panel shows
them translated by matching each against the templates below: a template is the English
sentence with ``{0}``, ``{1}`` ... where the values go; its translation (in the ``.ts``, like
every other string) takes the same values. Values that are themselves known sentences (a state,
a reason) are translated too. A sentence no template matches is shown as it is.

Beside the templates written here (those with a comment on how they are used), the controller's
refusals, alarms and messages and the interpreter's (a program's errors) come from
``app.message_text``, gathered from their sources by ``tools.i18n_catalog``.
"""

from __future__ import annotations

import re
from functools import lru_cache

from app.i18n import N_, tr
from app.message_text import CONTROLLER_TEMPLATES, GCODE_TEMPLATES

__all__ = ["TEMPLATES", "localize"]

TEMPLATES: tuple[str, ...] = (
    # a program's errors, as the planner and the controller wrap the interpreter's messages
    N_("{0}:{1}:{2}: error: {3}"),
    N_("{0} error(s) in the program; first: {1}"),
    N_("line {0}, axis {1}: {2}"),
    N_("approach move: soft limit: {0}"),
    N_("soft limit: {0}"),
    N_("{0}: with the result, line {1} reads: {2}"),
    N_("{0}: with the result, line {1}: {2}"),
    N_("line {0}: {1}"),
    # the interpreter's words that go into its sentences
    N_("clockwise"), N_("counterclockwise"), N_("enable"), N_("disable"),
    N_("set an analog output"), N_("set a digital output"), N_("change the plane"),
    N_("change the path control mode"), N_("change the canned cycle retract mode"),
    N_("store the G28/G30 position"), N_("change the axis offsets (G52, G92)"),
    N_("change the coordinate system"), N_("change tools"), N_("change the tool length offset"),
    N_("use {0}"),
    # program stops and what they ask
    N_("program paused (M00, line {0}): press cycle start"),
    N_("optional stop (M01, line {0}): press cycle start"),
    N_("tool change (M06, line {0}): insert tool {1} and press cycle start"),
    N_("{0}; {1} is then measured on the tool setter"),
    N_("single block: end of line {0}"),
    N_("feed hold"),
    N_("stopping"),
    N_("stopped by the operator"),
    N_("program end"),
    # refusals
    N_("machine is {0}"),
    N_("nothing to hold: machine is {0}"),
    N_("axes not homed: {0} (home them or set machine zero first)"),
    N_("axes not homed"),
    N_("no program loaded"),
    N_("acknowledge the active alarms first"),
    N_("the program {0} is still being checked (wait until it is loaded)"),
    N_("{0}: {1} is being checked again; it starts when ready"),
    N_("the machine moved since it was loaded"),
    N_("the work offsets changed since it was loaded"),
    N_("the machine configuration changed since it was loaded"),
    N_("the tool table changed since it was loaded"),
    N_("another tool is in the spindle since it was loaded"),
    N_("feed override must be 0-{0} %, got {1}"),
    N_("spindle override must be 50-150 %, got {0}"),
    N_("feed override {0} % capped at {1} % here: the machine's speed, acceleration or jerk limit"),
    N_("spindle override {0} % capped at {1} %: the spindle's maximum is {2} rpm"),
    N_("the tool table cannot change while the machine is {0}: a program reads the offsets when it is "
       "checked"),
    N_("T{0} is not in the tool table"),
    N_("T{0} is in the spindle: set another tool first"),
    N_("line {0} needs T{1} in the spindle (T{2} is in it): put it in and set it on the Tools page, or run "
       "from the M6 line {3}"),
    # the machine states as the refusals name them
    N_("idle"), N_("running"), N_("hold"), N_("alarm"), N_("e-stop"), N_("homing"), N_("disconnected"),
    # alarms
    N_("following error on axis {0}: {1} exceeds window {2} for more than {3} cycles: quick stop of all "
       "axes"),
    N_("drive fault on axis {0} (slave {1}): error code {2}: quick stop of all axes"),
    N_("working counter {0} instead of {1} for more than {2} cycles: quick stop of all axes{3}"),
    N_("E-stop: quick stop of all axes ({0})"),
    N_("E-stop pressed"),
    N_("E-stop pressed: {0}"),
    N_("E-stop pressed {0}"),
    N_("quick stop of all axes: {0}"),
    N_("homing of axis {0} failed ({1})"),
    N_("{0} lost: not answering process data; trying to recover it when it comes back"),
    N_("set-point buffer underrun after {0} set-points: holding the last position"),
    N_("axis {0} did not reach OPERATION ENABLED within {1} s (drive state {2})"),
    N_("the control did not shut down cleanly (power loss or killed; position last saved {0}): {1}"),
    N_("axes are not homed any more: home them before running a program"),
    N_("the drives have absolute encoders: homed flags kept"),
    # the machine around the drives
    N_("E-stop chain open (the machine's safety circuit): quick stop of all axes; the drives cannot be "
       "enabled until it is closed again"),
    N_("axis {0} on its positive limit switch: quick stop of all axes; override limits to jog it off the "
       "switch (toward -)"),
    N_("axis {0} on its negative limit switch: quick stop of all axes; override limits to jog it off the "
       "switch (toward +)"),
    N_("the drives cannot be re-enabled: axis {0} is on its positive limit switch: override limits to jog "
       "it off the switch"),
    N_("the drives cannot be re-enabled: axis {0} is on its negative limit switch: override limits to jog "
       "it off the switch"),
    N_("axis {0} is on its positive limit switch: it may only jog away from it ({1})"),
    N_("axis {0} is on its negative limit switch: it may only jog away from it ({1})"),
    N_("homing of axis {0} failed at step '{1}': {2}; quick stop of all axes"),
    N_("off switch"), N_("search"), N_("back off"), N_("latch"), N_("index"), N_("square"),
    N_("the switch did not change within the search travel"), N_("a limit switch tripped"),
    N_("timeout"), N_("no index pulse within the search travel"),
    N_("its drive has no touch probe (0x60B8, 0x60B9, 0x60BA) in its process data for the index"),
    N_("homing {0}"),
    # gantries
    N_("gantry {0}: its drives {1} and {2} are {3} out of square (window {4}) for more than {5} cycles: "
       "quick stop of all axes"),
    N_("squaring the gantry would move this side further than its homing travel"),
    N_("a gantry's side homes only together with its other side"),
    # the handwheel
    N_("handwheel on axis {0}: its counter jumped by {1} counts in one cycle (a terminal restarted or a wire "
       "is loose): the jump moved nothing, the axis stopped; select the axis again to go on"),
    N_("handwheel on axis {0}: its encoder terminal stopped answering: the axis stopped; select the axis "
       "again once it answers"),
    # the homing steps as Machine zero shows them ("homing Z searching the switch")
    N_("{0} moving off the switch"), N_("{0} searching the switch"), N_("{0} backing off the switch"),
    N_("{0} latching the switch edge"), N_("{0} searching the index pulse"), N_("{0} at the switch"),
    N_("{0} squaring the gantry"),
    # lists, causes and places: each part said in the panel's language
    N_("{0}, {1}"), N_("{0}: {1}"), N_("{0} ({1})"),
    # where a signal is wired (the Signals tab)
    N_("{0} (slave {1}) channel {2}"), N_("drive {0} (slave {1}) {2} bit {3}"), N_("{0}, normally closed"),
    N_("{0} lost ({1} reads false)"),
    N_("{0} lost ({1} reads false): the motion stops"),
    # probing, inputs and the tool setter
    N_("{0} (line {1}): contact at {2} (machine)"),
    N_("{0} (line {1}): contact lost at {2} (machine)"),
    N_("{0} (line {1}): no contact"),
    N_("{0} (line {1}): the probe move ended without contact"),
    N_("{0} (line {1}): the probe already touches where the move starts"),
    N_("{0} (line {1}): with the result, {2}"),
    # ... in the tool setter's routine, named by its step
    N_("{0} ({1}): contact at {2} (machine)"),
    N_("{0} ({1}): no contact"),
    N_("{0} ({1}): the probe move ended without contact"),
    N_("{0} ({1}): the probe already touches where the move starts"),
    N_("{0} ({1}): with the result, {2}"),
    N_("the move up to the clearance height"),
    N_("the move over the tool setter"),
    N_("the fast probe down to the setter"),
    N_("the move up from the first contact"),
    N_("the slow probe down to the setter"),
    N_("the move back up"),
    N_("measuring tool T{0}"),
    N_("a probe move ended without the probe armed: the program stops here"),
    N_("line {0} comes after the probe at line {1}: what follows depends on what it read; run from line "
       "{1} (or before) to read it again"),
    N_("M66 (line {0}): input P{1} timed out after {2} s: #5399 = -1"),
    N_("T{0} measured on the tool setter: length {1} mm"),
    N_("T{0} is not in the spindle: put it in and set it (In the spindle) first"),
    # restarts, offsets and tools
    N_("the program stopped at line {0}: resume there or start it again from the beginning (choose one)"),
    N_("no program stopped part-way"),
    N_("run from line {0}"),
    N_("reset"),
    N_("power loss or killed"),
    N_("E-stop: {0}"),
    # a path beyond the travel (``planner.geometry.softlimits.LimitViolation``)
    N_("axis {0} reaches {1} ({2}), beyond its soft limit {3} {4}"),
    N_("end point"), N_("arc extreme"), N_("path"), N_("max"), N_("min"),
    N_("interrupted at line {0}: the control stopped (power loss or killed)"),
    N_("the tool length offset in force changed since it was loaded"),
    # the longer first: the shorter would take its words as a value
    N_("{0} {1} zero would be at machine {2} with the tool length offset in force, outside the travel "
       "{3} .. {4} {5}"),
    N_("{0} {1} zero would be at machine {2}, outside the travel {3} .. {4} {5}"),
    N_("touch off {0}: not a number"),
    N_("{0}: not a number"),
    N_("T{0} length {1} mm is longer than the Z travel ({2} mm): check the value and the surface it was "
       "touched off on"),
    N_("feed move with the spindle stopped: the M6 at line {0} stopped it and no M3/M4 started it again"),
    N_("M06: the spindle stops for the tool change"),
    # the probing wizards: what runs and what it found (the values as "X12.0000 Y3.5000")
    N_("probing {0}: {1}"),
    N_("the bore measures {0} mm across, not {1} mm within {2} mm: nothing written"),
    N_("the boss measures {0} mm across, not {1} mm within {2} mm: nothing written"),
    N_("probe touched during positioning"),
    N_("probing {0}"), N_("probed (machine): {0}, written to {1}"),
    N_("probed (machine): {0} (only reported)"),
    # (the wizards' names: app.machine.model.WIZARDS, gathered from there)
    # the part counter
    N_("{0} part(s) made: the target of {1} is reached"),
    N_("the target of {0} part(s) is reached: reset the part counter (or raise the target) to run again"),
    # the editor's error marks: where in the line
    N_("column {0}: {1}"),
)


@lru_cache(maxsize=1)
def _compiled() -> tuple[tuple[re.Pattern[str], str, int], ...]:
    """(pattern, template, how many of its characters are not values) for every template."""
    out = []
    gathered = [t for t in (*CONTROLLER_TEMPLATES, *GCODE_TEMPLATES) if t not in TEMPLATES]
    # an alarm's source stands for itself where a sentence names it ("E-stop: operator")
    for template in (*TEMPLATES, *SOURCE_TEXT.values(), *dict.fromkeys(gathered)):
        parts = re.split(r"(\{\d+\})", template)
        literal = [p.replace("{{", "{").replace("}}", "}") for p in parts[::2]]
        pattern = "".join("(.*?)" if k % 2 else re.escape(literal[k // 2]) for k, _ in enumerate(parts))
        out.append((re.compile(pattern + r"\Z", re.DOTALL), template, sum(map(len, literal))))
    return tuple(out)


_Reading = tuple[int, int, tuple["_Reading", ...]]   # (accounted for, template index or -1, values)


@lru_cache(maxsize=4096)
def _read(text: str, depth: int = 0) -> _Reading:
    """How ``text`` is made of templates: (characters they account for, the outer template,
    the readings of its values). Of the templates that match, the one that accounts for the
    most of the text with its values' own readings wins, the earlier on a tie: "bad.ngc:3:1:
    error: G82 needs a P word ..." is the location's template around the interpreter's, not the
    interpreter's with the location taken for the code's name."""
    best: _Reading = (0, -1, ())
    if not text or depth > 3:
        return best
    for index, (pattern, _, literal) in enumerate(_compiled()):
        m = pattern.match(text)
        if m is None:
            continue
        values = tuple(_read(v, depth + 1) for v in m.groups())
        score = literal + sum(v[0] for v in values)
        if score > best[0]:
            best = (score, index, values)
    return best


def _say(text: str, reading: _Reading) -> str:
    _, index, values = reading
    if index < 0:
        return text
    pattern, template, _ = _compiled()[index]
    translated = tr(template)
    m = pattern.match(text)
    assert m is not None
    said = [_say(v, r) for v, r in zip(m.groups(), values, strict=True)]
    if translated == template and said == list(m.groups()):
        return text                      # English, or no translation: the original sentence
    # a template that reads the same in both languages ("{0}, {1}") still says its values in
    # the panel's language
    return translated.format(*said)


def localize(text: str) -> str:
    """``text`` from the controller in the panel's language (as it is when no template fits);
    several lines (a program's errors) line by line."""
    if not text:
        return text
    if "\n" in text:
        return "\n".join(localize(line) for line in text.split("\n"))
    return _say(text, _read(text))


#: where an alarm comes from, shown in the operator's language
SOURCE_TEXT = {"worker": N_("worker"), "bus": N_("bus"), "planner": N_("planner"),
               "controller": N_("controller"), "operator": N_("operator"), "config": N_("configuration"),
               "probe": N_("probe"), "tools": N_("tools"), "persistence": N_("state folder"),
               "opcua": N_("OPC UA"), "spindle": N_("spindle"), "program": N_("program"),
               "outputs": N_("outputs"), "homing": N_("homing"), "input": N_("input"),
               "E-stop chain": N_("E-stop chain"), "door": N_("door"), "coolant": N_("coolant"),
               "air_ok": N_("air"), "lube_ok": N_("lubrication")}


def source_text(source: str) -> str:
    """An alarm's source in the panel's language ("drive X" keeps its axis)."""
    if source.startswith("drive "):
        return tr("drive {0}").format(source[len("drive "):])
    return tr(SOURCE_TEXT[source]) if source in SOURCE_TEXT else source
