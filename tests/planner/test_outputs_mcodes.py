"""Digital outputs M62-M65 and user M-codes M100-M199: what the machine configuration defines
is done at its point of the path; anything else is refused naming the code and where to define it."""

from __future__ import annotations

import tomllib
from dataclasses import replace

import pytest

from app.machine.config import config_from_dict
from app.machine.errors import ConfigError
from planner.core.errors import ProgramError
from planner.core.machine import MachineSpec
from planner.core.program import OutputLevel
from planner.gcode.interpreter import parse_program
from resources import shipped_machine

MACHINE = replace(MachineSpec.default(), output_bits={1: (0, 4, "vacuum"), 2: (1, 2, "air blast")},
                  mcodes={101: ("pause", "check the clamp", -1, True), 102: ("output", "air on", 2, True),
                          103: ("ignore", "", -1, True)})


def events(text: str) -> list[tuple[str, int, object, str]]:
    p = parse_program(text, machine=MACHINE)
    return [(e.kind.name, e.after_move, e.payload, e.message) for e in p.events]


def test_outputs_switch_where_the_path_is() -> None:
    got = events("G21 F100\nG1 X1\nM64 P1\nG1 X2\nM65 P1\nM62 P2\nM63 P2\n")
    assert got == [("OUTPUT", 0, OutputLevel(1, True), "M64: output 1 on"),
                   ("OUTPUT", 1, OutputLevel(1, False), "M65: output 1 off"),
                   ("OUTPUT", 1, OutputLevel(2, True), "M62: output 2 on"),
                   ("OUTPUT", 1, OutputLevel(2, False), "M63: output 2 off")]


def test_user_m_codes_do_what_the_machine_says() -> None:
    got = events("G21 F100\nG1 X1\nM101\nM102\nM103\n")
    assert got == [("PAUSE", 0, None, "M101: check the clamp"),
                   ("OUTPUT", 0, OutputLevel(2, True), "M102: air on: output 2 on"),
                   ("MESSAGE", 0, None, "M103 (does nothing on this machine)")]


@pytest.mark.parametrize("text, col, words", [
    ("M110\n", 1, "M110 is a user M-code this machine does not define (add it to [[mcodes]]"),
    ("M64 P7\n", 5, "M64 needs P with a configured output number (P1, P2)"),
    ("M64\n", 1, "M64 needs P"),
    ("M66 P1 L0\n", 5, "M66 P1: no such digital input on this machine (none: add [[inputs]])"),
    ("M64 M65 P2\n", 5, "same modal group"),
    ("M101 M102\n", 6, "same modal group"),
])
def test_refusals(text: str, col: int, words: str) -> None:
    with pytest.raises(ProgramError) as exc:
        parse_program(text, machine=MACHINE)
    (err,) = exc.value.errors
    assert words in err.message and err.col == col, err


def test_without_a_configuration_no_output_exists() -> None:
    with pytest.raises(ProgramError, match=r"configured output number \(none: add \[\[outputs\]\]\)"):
        parse_program("M64 P0\n")


def _config(extra: str) -> str:
    return shipped_machine("xyz_mill").read_text(encoding="utf-8") + "\n" + extra


def test_configuration_tables_are_read_checked_and_written_back() -> None:
    from app.machine.config import config_to_toml

    text = _config('[[outputs]]\nnumber = 1\ndrive = 2\nbit = 3\nname = "vacuum"\n\n'
                   '[[mcodes]]\ncode = 120\naction = "output"\noutput = 1\non = false\n'
                   'message = "vacuum off"\n')
    cfg = config_from_dict(tomllib.loads(text), "m.toml", text)
    assert cfg.machine.output_bits == {1: (2, 3, "vacuum")}
    assert cfg.machine.mcodes == {120: ("output", "vacuum off", 1, False)}
    again = config_from_dict(tomllib.loads(config_to_toml(cfg)), "again")
    assert again.machine.output_bits == cfg.machine.output_bits and again.machine.mcodes == cfg.machine.mcodes


@pytest.mark.parametrize("extra, key", [
    ('[[mcodes]]\ncode = 120\naction = "output"\n', "mcodes[0].output"),
    ('[[outputs]]\nnumber = 1\ndrive = 0\nbit = 1\n', "outputs[0].bit"),              # the spindle's bits
    ('[[outputs]]\nnumber = 1\ndrive = 9\nbit = 4\n', "outputs[0].drive"),
    ('[[outputs]]\nnumber = 1\ndrive = 1\nbit = 4\n[[outputs]]\nnumber = 1\ndrive = 1\nbit = 5\n',
     "outputs[1].number"),
    ('[[mcodes]]\ncode = 99\naction = "pause"\n', "mcodes[0].code"),
])
def test_configuration_mistakes_name_the_key_and_line(extra: str, key: str) -> None:
    text = _config(extra)
    with pytest.raises(ConfigError) as exc:
        config_from_dict(tomllib.loads(text), "m.toml", text)
    assert f"{key}:" in str(exc.value) and "m.toml:" in str(exc.value)
