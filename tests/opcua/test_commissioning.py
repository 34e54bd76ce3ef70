"""What the integrator and a headless run see: ``[opcua]`` checked key by key, ``cnc-run
--opcua-port`` serving a running program to a client in another process, ``cnc-opcua``
telling the endpoint, certificate and users and browsing the model, and the panel saying
where it serves."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from app.machine.errors import ConfigError
from tests.opcua.conftest import free_port, make_served

ROOT = Path(__file__).resolve().parents[2]
MT = "http://opcfoundation.org/UA/MachineTool/"


@pytest.mark.parametrize(("line", "key", "why"), [
    ('host = "bad host!"', "opcua.host", "not an IP address or a host name"),
    ("port = 0", "opcua.port", "within [1, 65535]"),
    ("security = []", "opcua.security", "needs at least one of"),
    ('security = ["Basic128Rsa15"]', "opcua.security[0]", "must be one of"),
    ("rate_hz = 1000.0", "opcua.rate_hz", "within [0.1, 50]"),
    ("enable = true", "opcua.enable", "enabled"),
])
def test_a_bad_opcua_setting_is_refused_naming_its_key_and_line(tmp_path: Path, line: str, key: str,
                                                                 why: str) -> None:
    from app.machine.config import MachineConfig, config_to_toml, load_config

    lines = config_to_toml(MachineConfig.default()).splitlines()
    start = lines.index("[opcua]")
    name = line.split(" ")[0]
    written = [i for i in range(start, len(lines)) if lines[i].startswith(f"{name} =")]
    if written:
        lines[written[0]] = line
    else:
        lines.insert(start + 1, line)
    text = "\n".join(lines) + "\n"
    path = tmp_path / "machine.toml"
    path.write_text(text)
    with pytest.raises(ConfigError) as err:
        load_config(path)
    message = str(err.value)
    assert key in message and why in message
    assert f":{text.splitlines().index(line) + 1}" in message


_READER = """
import asyncio, sys, time
from asyncua import Client
from opcua_server.browse import find_machine
async def main():
    seen = []
    end = time.monotonic() + 60
    while time.monotonic() < end:
        try:
            async with Client(sys.argv[1], timeout=5) as c:
                mt = await c.get_namespace_index("http://opcfoundation.org/UA/MachineTool/")
                m = await find_machine(c)
                state = await m.get_child([f"{mt}:Production", f"{mt}:ActiveProgram", f"{mt}:State",
                                           "0:CurrentState"])
                name = await m.get_child([f"{mt}:Production", f"{mt}:ActiveProgram", f"{mt}:Name"])
                while time.monotonic() < end:
                    text = (await state.read_value()).Text
                    if not seen or seen[-1] != text:
                        seen.append(text)
                        print(text, await name.read_value(), flush=True)
                    if text == "Ended":
                        return
                    await asyncio.sleep(0.05)
        except (OSError, asyncio.TimeoutError):
            await asyncio.sleep(0.2)
asyncio.run(main())
"""


def test_cnc_run_serves_the_running_program_to_a_client_in_another_process(tmp_path: Path) -> None:
    program = tmp_path / "square.ngc"
    program.write_text("G21 G90\nG4 P1.5\nG0 X10 Y10\nG1 X40 F3000\nG1 Y40\nG1 X10\nM30\n")
    port = free_port()
    run = subprocess.Popen([sys.executable, "-m", "app.run_cli", str(program), "--sim", "--json",
                            "--opcua-insecure", "--opcua-port", str(port)], cwd=ROOT,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    reader = subprocess.Popen([sys.executable, "-c", _READER, f"opc.tcp://127.0.0.1:{port}/"], cwd=ROOT,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        out, err = run.communicate(timeout=120)
        seen, reader_err = reader.communicate(timeout=60)
    finally:
        for proc in (run, reader):
            if proc.poll() is None:
                proc.kill()
                proc.wait(10)
    assert run.returncode == 0, err
    assert f"OPC UA server at opc.tcp://127.0.0.1:{port}/" in err and "security None" in err
    states = [line.split(" ")[0] for line in seen.splitlines()]
    assert "Running" in states and states[-1] == "Ended", (seen, reader_err)
    assert "square.ngc" in seen


def test_cnc_run_refuses_a_port_outside_the_tcp_range(qapp: Any, capsys: pytest.CaptureFixture[str],
                                                      tmp_path: Path) -> None:
    from app.run_cli import main

    program = tmp_path / "p.ngc"
    program.write_text("G0 X1\nM30\n")
    assert main([str(program), "--sim", "--opcua-port", "70000"]) == 2
    assert "--opcua-port 70000: a TCP port is 1 to 65535" in capsys.readouterr().err


def test_cnc_opcua_tells_the_endpoint_certificate_and_users_and_browses_the_model(
        qapp: Any, tmp_path: Path, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    from app.opcua_cli import main

    state = tmp_path / "state"
    monkeypatch.setenv("CNC_OPCUA_PASSWORD", "correct horse")
    assert main(["--state-dir", str(state), "--add-user", "mes"]) == 0
    out = capsys.readouterr().out
    assert "user mes added" in out and "users:         mes" in out
    assert "Basic256Sha256_SignAndEncrypt; users only" in out
    thumb = out.split("SHA-1 ")[1].split(")")[0]
    assert len(thumb) == 40
    served = make_served(qapp, state, secure=True)
    try:
        assert main(["--state-dir", str(state), "--browse", "--url", served.url, "--user", "mes"]) == 0
        tree = capsys.readouterr().out
        assert f"SHA-1 {thumb}" in tree                       # the certificate the server serves with
        assert served.ctl.config.machine.name in tree
        for node in ("ChannelState = 2", "IsRotating = False", "CurrentState = 'Initializing'", "Stacklight"):
            assert node in tree, tree
    finally:
        served.ctl.shutdown()
    assert main(["--state-dir", str(state), "--browse", "--url", served.url, "--user", "mes"]) == 1
    assert "no answer from" in capsys.readouterr().err
