"""Every kind of file a user gives, mutated at random: a tool table, a script of operator
actions, a machine configuration and a program are read or refused with the reader's own error
naming the file, never another exception. The hardening round's reproducers are the first
examples of each."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from app.machine.errors import ConfigError, MachineError
from planner.core.errors import PlannerError

TOOLS = b"T1 P1 Z0 D6 ;6 mm flat end mill\nT2 P2 Z-12.5 D3 ;3 mm ball\nT99 P99 Z50 D2 ;probe\n"
SCRIPT = b'{"after_s": 0.5, "op": "feed_hold"}\n{"at_line": 3, "op": "stop"}\n{"after_s": 2, "op": "reset"}\n'
PROGRAM = b"G21 G90\nG0 X10 Y10\nG1 X40 F3000\nG2 X50 Y20 I10 J0\no1 repeat [2]\nG1 Y30\no1 endrepeat\nM30\n"
#: what the mutations put in: NUL and control bytes, line separators that are no line ends,
#: numbers beyond a float, deep brackets
PIECES = [b"\0", b"\x0c", "\u0085".encode(), "\u2028".encode(), b"\xff\xfe", b"9" * 400, b"[" * 600,
          b"\r", b"\n", b"{", b"}", b'"', b"-1e999", b"nan", b"#", b";", b"(", b"T", b"P", b"Z"]


def _mutated(base: bytes):
    piece = st.sampled_from(PIECES) | st.binary(max_size=8)
    edit = st.tuples(st.integers(0, len(base)), st.integers(0, 8), piece)

    def apply(edits: list[tuple[int, int, bytes]]) -> bytes:
        data = base
        for at, cut, piece in edits:
            at = min(at, len(data))
            data = data[:at] + piece + data[at + cut:]
        return data

    return st.lists(edit, min_size=1, max_size=6).map(apply)


def _write(tmp: Path, name: str, data: bytes) -> Path:
    path = tmp / name
    path.write_bytes(data)
    return path


@settings(max_examples=150, deadline=None)
@given(_mutated(TOOLS))
@example(b"T1 P1 Z1 ;a\x0cT5 P5\nT2 P2 Z" + b"9" * 400 + b"\n")
@example(b"\0" * 64)
def test_a_mutated_tool_table_is_read_or_refused_naming_it(tmp_path_factory: pytest.TempPathFactory,
                                                           data: bytes) -> None:
    from planner.core.tools import read_tbl

    path = _write(tmp_path_factory.mktemp("tbl"), "tools.tbl", data)
    try:
        read_tbl(path)
    except PlannerError as exc:
        assert str(path) in str(exc) and str(exc).isprintable(), str(exc)


@settings(max_examples=150, deadline=None)
@given(_mutated(SCRIPT))
@example(b'{"at_line": ' + b"9" * 400 + b', "op": "stop"}\n')
@example(b'{"after_s": NaN, "op": "feed_hold"}\n')
def test_a_mutated_script_is_read_or_refused_naming_it(tmp_path_factory: pytest.TempPathFactory,
                                                       data: bytes) -> None:
    from app.machine.program.scenario import read_script

    path = _write(tmp_path_factory.mktemp("script"), "ops.jsonl", data)
    try:
        read_script(path)
    except MachineError as exc:
        assert str(path) in str(exc), str(exc)


@settings(max_examples=60, deadline=None)
@given(_mutated(b"[machine]\nname = \"m\"\n[limits]\nv_max_mm_s = 30.0\n"))
@example(b"a = " + b"[" * 500 + b"]" * 500 + b"\n")
def test_a_mutated_configuration_is_read_or_refused_naming_it(tmp_path_factory: pytest.TempPathFactory,
                                                              data: bytes) -> None:
    from app.machine.config import load_config

    path = _write(tmp_path_factory.mktemp("cfg"), "machine.toml", data)
    try:
        load_config(path)
    except ConfigError as exc:
        assert str(path) in str(exc), str(exc)


@settings(max_examples=150, deadline=None)
@given(_mutated(PROGRAM))
@example(b"G21\nM98 P[10**308*10]\nM2\n")
@example(b"G21\no1 repeat [10**308*10]\no1 endrepeat\nM2\n")
@example(b"G21\nG92\nM2\n")
def test_a_mutated_program_is_read_or_refused_at_a_line(tmp_path_factory: pytest.TempPathFactory,
                                                        data: bytes) -> None:
    from planner.core.errors import ProgramError
    from planner.gcode.interpreter import parse_file

    path = _write(tmp_path_factory.mktemp("prog"), "p.ngc", data)
    try:
        parse_file(path)
    except ProgramError as exc:
        assert exc.errors and all(e.message.isprintable() for e in exc.errors), exc.errors
    except PlannerError as exc:                     # the file itself (binary data, too long)
        assert str(path) in str(exc), str(exc)
