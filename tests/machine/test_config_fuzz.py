"""Configuration files with typos: the shipped machines' files, mutated at random (a line
dropped, doubled or cut, a value replaced by another type or an out-of-range number, a key
misspelt, junk inserted). Whatever the file says, reading it either gives a configuration or
raises ConfigError naming the file and the line (and the key) of what is wrong; nothing else
escapes."""

from __future__ import annotations

import re
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from app.machine.config import load_config
from app.machine.errors import ConfigError
from resources import shipped_machine

TEXTS = {name: Path(shipped_machine(name)).read_text(encoding="utf-8") for name in ("xyz_mill", "paper_yzca")}
_VALUE_LINE = re.compile(r"^(\s*[A-Za-z_][A-Za-z0-9_]*\s*=\s*)(.+?)(\s*(#.*)?)$")

values = st.sampled_from(["0", "-1", "1e308", "-1e308", "nan", "inf", "-inf", "1e-300", "2147483648",
                          '""', '"x"', "true", "[]", "[1, 2]", "{}", "{a = 1}", "0x10", "1_000",
                          "2024-01-01", "'''a'''", "-0.0", "3.5", "99999999999999999999"])
junk = st.sampled_from(["[", "]]", "= 3", "[[axes]]", "[axes]", "x = ", "\x00", "é = 1", "a.b = 2",
                        "[controller]", "[[drives]]", "= = ="])


@st.composite
def mutated(draw) -> tuple[str, str]:
    name = draw(st.sampled_from(sorted(TEXTS)))
    lines = TEXTS[name].splitlines()
    # mostly values and keys (what an integrator mistypes), sometimes the file's structure
    kinds = st.sampled_from(["value"] * 6 + ["key"] * 2 + ["drop", "double", "cut", "junk"])
    for what in draw(st.lists(kinds, min_size=1, max_size=3)):
        settable = [k for k, line in enumerate(lines) if _VALUE_LINE.match(line)]
        if what in ("value", "key") and settable:
            i = draw(st.sampled_from(settable))
            m = _VALUE_LINE.match(lines[i])
            assert m is not None
            if what == "value":
                lines[i] = m.group(1) + draw(values)
            else:
                key = m.group(1).split("=")[0].strip()
                lines[i] = lines[i].replace(key, key[:-1] + draw(st.sampled_from("xq_")), 1)
            continue
        if not lines:
            break
        i = draw(st.integers(0, len(lines) - 1))
        if what == "drop":
            del lines[i]
        elif what == "double":
            lines.insert(i, lines[i])
        elif what == "cut":
            lines[i] = lines[i][:draw(st.integers(0, len(lines[i])))]
        elif what == "junk":
            lines.insert(i, draw(junk))
    return name, "\n".join(lines) + "\n"


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=mutated())
def test_a_mutated_configuration_is_read_or_refused_with_file_and_key(tmp_path_factory, case) -> None:
    name, text = case
    path = tmp_path_factory.mktemp("cfg") / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    try:
        cfg = load_config(path)
    except ConfigError as exc:
        message = str(exc)
        where = re.escape(str(path))
        # the TOML reader's own line and column, the line of a byte no text has, or the line
        # and key of what is wrong
        located = (rf"{where}: damaged file, not valid TOML: .+\(at line \d+"
                   rf"|{where}:\d+: (binary data \(a NUL byte\)|not UTF-8 text)"
                   rf"|{where}:\d+: [A-Za-z_][\w\[\]\.-]*: \S")
        assert re.match(located, message), message
        return
    assert cfg.machine.axis_names                       # a configuration a machine can run
