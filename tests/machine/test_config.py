"""Machine configuration: strict reading, atomic writing with a backup, recovery."""

from __future__ import annotations

import re
import tomllib
from dataclasses import replace
from pathlib import Path

import pytest

from app.machine.config import (
    MachineConfig,
    backup_path,
    config_from_dict,
    config_to_toml,
    load_config,
    recover_config,
    save_config,
)
from app.machine.controller import MachineController
from app.machine.errors import ConfigError
from app.machine.model import Severity
from resources import shipped_machine


@pytest.mark.parametrize("name", ["xyz_mill", "paper_yzca"])
def test_shipped_configurations_round_trip(name: str) -> None:
    cfg = load_config(shipped_machine(name))
    text = config_to_toml(cfg)
    again = config_from_dict(tomllib.loads(text), "again")
    assert config_to_toml(again) == text
    assert again.machine.axes == cfg.machine.axes
    assert again.homing == cfg.homing and again.bus == cfg.bus


def test_save_is_atomic_and_keeps_the_previous_file(config_path: Path) -> None:
    cfg = load_config(config_path)
    old_text = config_path.read_text()
    new = replace(cfg, machine=cfg.machine.with_limits(v_max_mm_s=25.0))
    saved = save_config(new, config_path)
    assert saved.machine.limits.v_max_mm_s == 25.0
    assert load_config(config_path).machine.limits.v_max_mm_s == 25.0
    assert backup_path(config_path).read_text() == old_text
    assert not list(config_path.parent.glob(".*.tmp"))  # no temporary file left behind


@pytest.mark.parametrize("edit, words", [
    (lambda t: t.replace("v_max = 100.0", "v_max = -1.0", 1), ["v_max", "-1"]),
    (lambda t: t.replace('method = "switches"', 'method = "magic"'), ["method", "magic"]),
    (lambda t: t.replace('kind = "sim"', 'kind = "can"'), ["kind", "can"]),
    (lambda t: re.sub(r"lead_s = [0-9.]+", "lead_s = 5.0", t), ["lead_s", "5.0"]),
    # the probe: an axis index the machine has, a bit of 0x60FD, an axis for the simulated surface
    (lambda t: re.sub(r"(\[probe\][^\n]*\ndrive = )2", r"\g<1>3", t), ["probe.drive", "3", "axis count 3"]),
    (lambda t: t.replace("bit = 16", "bit = 32"), ["probe.bit", "32"]),
    (lambda t: t.replace('sim_axis = "Z"', 'sim_axis = "A"'), ["probe.sim_axis", "A is not an axis"]),
    (lambda t: t.replace("touching_level = 1", "touching_level = 2"), ["touching_level", "2"]),
    # M66's inputs: on a drive the machine has, each number once
    (lambda t: re.sub(r"(\[\[inputs\]\][^\n]*\nnumber = 0\ndrive = )0", r"\g<1>4", t),
     ["inputs", "drive", "axis count 3"]),
    (lambda t: t + "\n[[inputs]]\nnumber = 0\ndrive = 1\nbit = 20\n", ["inputs", "input 0 is defined twice"]),
    # a copied axis left with its name: the copy's line is named
    (lambda t: t.replace('name = "Y"', 'name = "X"', 1), ["axes[1].name", "must be unique"]),
])
def test_invalid_values_are_named(config_path: Path, edit, words) -> None:
    cfg = load_config(config_path)
    save_config(cfg, config_path)  # adds the [controller] section
    config_path.write_text(edit(config_path.read_text()))
    with pytest.raises(ConfigError) as exc:
        load_config(config_path)
    for w in words:
        assert w in str(exc.value)
    assert str(config_path) in str(exc.value)


def test_truncated_mid_write_is_recovered_from_the_backup(config_path: Path) -> None:
    cfg = load_config(config_path)
    save_config(replace(cfg, machine=cfg.machine.with_limits(v_max_mm_s=20.0)), config_path)
    good = config_path.read_text()
    save_config(replace(cfg, machine=cfg.machine.with_limits(v_max_mm_s=21.0)), config_path)
    # a crash of a non-atomic writer: the file cut in the middle of a table
    text = config_path.read_text()
    config_path.write_text(text[: len(text) // 2] + "\n[[axes]\nname = ")
    with pytest.raises(ConfigError) as exc:
        load_config(config_path)
    assert exc.value.backup == str(backup_path(config_path))
    assert "damaged" in str(exc.value)
    cfg2, message = recover_config(config_path)
    assert cfg2.machine.limits.v_max_mm_s == 20.0
    assert config_path.read_text() == good
    assert config_path.with_name(config_path.name + ".damaged").exists()
    assert "restored" in message


def test_no_backup_no_silent_defaults(tmp_path: Path) -> None:
    p = tmp_path / "m.toml"
    p.write_text("[machine]\nname = 'x'\n[[axes]]\nname = 'X'\n")  # min/max missing
    with pytest.raises(ConfigError) as exc:
        load_config(p)
    assert exc.value.backup is None
    assert "missing 'min'" in str(exc.value)
    with pytest.raises(ConfigError):
        MachineController(p, state_dir=tmp_path / "s", worker_mode="manual")


def test_controller_recovers_a_damaged_file_and_says_so(qapp, config_path: Path, state_dir: Path) -> None:
    cfg = load_config(config_path)
    save_config(cfg, config_path)
    config_path.write_text(config_path.read_text()[:300])
    ctl = MachineController(config_path, state_dir=state_dir, worker_mode="manual")
    try:
        assert ctl.config.machine.axis_names == ("X", "Y", "Z")
        warn = [a for a in ctl.alarms if a.code == "config_recovered"]
        assert warn and warn[0].severity is Severity.WARNING and "restored" in warn[0].cause
    finally:
        ctl.shutdown()


def test_update_config_is_atomic_and_applied(qapp, config_path: Path, state_dir: Path) -> None:
    ctl = MachineController(config_path, state_dir=state_dir, worker_mode="manual")
    try:
        seen: list[MachineConfig] = []
        ctl.configChanged.connect(seen.append)
        new = replace(ctl.config, machine=ctl.config.machine.with_limits(a_max_mm_s2=800.0))
        assert ctl.update_config(new)
        assert seen and seen[-1].machine.limits.a_max_mm_s2 == 800.0
        assert load_config(config_path).machine.limits.a_max_mm_s2 == 800.0
        assert backup_path(config_path).exists()
    finally:
        ctl.shutdown()


def test_saving_keeps_the_integrators_comments_order_and_formats(tmp_path: Path) -> None:
    """A change made on the panel rewrites only that value: every comment, the key order and
    the hexadecimal drive identities of the integrator's file stay as they were."""
    p = tmp_path / "machine.toml"
    original = shipped_machine("xyz_mill").read_text(encoding="utf-8")
    p.write_text(original, encoding="utf-8")
    cfg = load_config(p)
    save_config(replace(cfg, machine=cfg.machine.with_limits(v_max_mm_s=25.0)), p)
    text = p.read_text(encoding="utf-8")
    for line in original.splitlines():
        if line.startswith("v_max_mm_s"):
            assert "v_max_mm_s = 25.0" in text
        else:
            assert line in text, f"lost: {line!r}"
    kept = [ln for ln in text.splitlines() if ln in original.splitlines() and ln.strip()]
    assert kept == [ln for ln in original.splitlines() if ln.strip() and not ln.startswith("v_max_mm_s")]
    assert "vendor_id = 0x00000539" in text
    assert load_config(p).machine.limits.v_max_mm_s == 25.0
    assert load_config(p) == replace(cfg, machine=cfg.machine.with_limits(v_max_mm_s=25.0), path=str(p))


def test_unknown_keys_in_the_file_are_refused_with_file_and_line(tmp_path: Path) -> None:
    p = tmp_path / "machine.toml"
    text = shipped_machine("xyz_mill").read_text(encoding="utf-8").replace("[limits]", "[limitz]")
    p.write_text(text, encoding="utf-8")
    line = text.splitlines().index(next(t for t in text.splitlines() if t.startswith("[limitz]"))) + 1
    with pytest.raises(ConfigError) as exc:
        load_config(p)
    assert f"{p}:{line}: limitz: unknown section (did you mean 'limits'?)" in str(exc.value)


DRIVE_TABLES = """
[[bus.drives]]
position = 0
vendor_id = 0x0000029C
product_code = 0x03B11002
mapping = "write"
rx_pdo = 0x1601
rx = ["0x6040:0:16", "0x607A:0:32", "0x2010:1:32s"]
tx_pdo = 0x1A01
tx = ["0x6041:0:16", "0x6064:0:32", "0x0000:0:8"]
complete_access = "off"
dc = false
sync0_shift_ns = -250000
sync_mode = 2
watchdog_ms = 250.5
[[bus.drives.sdo]]
index = 0x6060
value = 8
size = 1
[[bus.drives.sdo]]
index = 0x2002
subindex = 3
value = -5
size = 4
[[bus.drives]]
position = 1
"""


@pytest.mark.parametrize(("junk", "key"), [("[[drives]]", "drives: unknown section"),
                                           ("a.b = 2", "a: unknown section")])
def test_an_unknown_array_or_dotted_key_is_named_with_its_line(tmp_path: Path, junk: str, key: str) -> None:
    text = Path(shipped_machine("xyz_mill")).read_text(encoding="utf-8")
    lines = text.splitlines()
    at = next(i for i, line in enumerate(lines) if line.startswith("[")) + 1   # before the first table
    lines.insert(at - 1, junk)
    p = tmp_path / "m.toml"
    p.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ConfigError) as exc:
        load_config(p)
    assert f"{p}:{at}: {key}" in str(exc.value)


def _with_drives(tables: str) -> str:
    head = shipped_machine("xyz_mill").read_text(encoding="utf-8").split("[bus]")[0]
    return f'{head}[bus]\nkind = "soem"\nadapter = "eth1"\n{tables}'


def test_drive_start_up_settings_are_read_and_kept_on_save(tmp_path: Path) -> None:
    from ethercat.drive_setup import MappingPolicy, StartupSdo

    p = tmp_path / "machine.toml"
    p.write_text(_with_drives(DRIVE_TABLES), encoding="utf-8")
    cfg = load_config(p)
    setup = cfg.bus.drives[0].setup()
    assert setup.policy is MappingPolicy.WRITE and setup.complete_access is False and not setup.dc
    assert setup.sync0_shift_ns == -250_000 and setup.sync_mode == 2 and setup.watchdog_ms == 250.5
    assert setup.mapping is not None and setup.mapping.rx_pdo == 0x1601
    assert [(e.index, e.subindex, e.bits, e.signed) for e in setup.mapping.rx] == [
        (0x6040, 0, 16, False), (0x607A, 0, 32, True), (0x2010, 1, 32, True)]
    assert setup.startup_sdos == (StartupSdo(0x6060, 0, 8, 1), StartupSdo(0x2002, 3, -5, 4))
    assert setup.startup_sdos[1].data == b"\xfb\xff\xff\xff"
    default = cfg.bus.drives[1].setup()
    assert default.mapping is None and default.policy is MappingPolicy.ADAPT
    assert default.complete_access is None and default.watchdog_ms is None
    again = load_config(save_config(cfg, tmp_path / "saved.toml").path)
    assert again.bus.drives == cfg.bus.drives


@pytest.mark.parametrize("edit, key, words", [
    ('rx = ["0x6040:0:16", "0x607A:0:32", "0x2010:1:32s"]', "rx",
     'rx = ["0x6040:0:16", "0x607A:0:31"]'),
    ('tx = ["0x6041:0:16", "0x6064:0:32", "0x0000:0:8"]', "tx", 'tx = ["0x6041:0:16"]'),
    ("size = 1", "sdo", "size = 3"),
    ("value = -5", "sdo", "value = 5000000000"),
    ('mapping = "write"', "mapping", 'mapping = "fixed"'),
    ("watchdog_ms = 250.5", "watchdog_ms", "watchdog_ms = 0.5"),
    ("watchdog_ms = 250.5", "watchdog_ms", "watchdog_ms = 7000"),
])
def test_bad_drive_settings_name_the_key_and_line(tmp_path: Path, edit: str, key: str, words: str) -> None:
    p = tmp_path / "machine.toml"
    text = _with_drives(DRIVE_TABLES.replace(edit, words, 1))
    p.write_text(text, encoding="utf-8")
    with pytest.raises(ConfigError) as exc:
        load_config(p)
    msg = str(exc.value)
    assert re.search(rf"{re.escape(str(p))}:\d+: bus\.drives\[0\]\.{key}", msg), msg


def test_g59_1_to_g59_3_are_read_written_and_refused_with_their_line(tmp_path) -> None:
    from app.machine.config import MachineConfig, config_to_toml, load_config

    text = config_to_toml(MachineConfig.default()).replace("[offsets]\n",
                                                           '[offsets]\n"G59.1" = [1.0, 2.0, 3.0]\n', 1)
    path = tmp_path / "machine.toml"
    path.write_text(text)
    cfg = load_config(path)
    assert cfg.machine.work_offsets["G59.1"] == (1.0, 2.0, 3.0)
    assert '"G59.1" = [1.0, 2.0, 3.0]' in config_to_toml(cfg)
    bad = text.replace('"G59.1" = [1.0, 2.0, 3.0]', '"G59.3" = [1.0, 2.0]')
    path.write_text(bad)
    with pytest.raises(ConfigError) as err:
        load_config(path)
    line = bad.splitlines().index('"G59.3" = [1.0, 2.0]') + 1
    assert f"machine.toml:{line}: offsets.G59.3: [offsets] G59.3 needs 3 numbers" in str(err.value)
    path.write_text(text.replace('"G59.1"', '"G59.4"'))
    with pytest.raises(ConfigError, match=r"offsets.G59.4: unknown key"):
        load_config(path)
