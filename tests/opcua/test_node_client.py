"""The server through a client that is not asyncua: node-opcua (``tests/opcua/node_client``,
installed by ``make test`` with npm). The security refusals, the alarm conditions on the Server
object with ConditionRefresh, and a walk of the machine (values, timestamps, the stack light's
SignalMode, the diagnostics, the ApplicationUri) as another stack reads them."""

from __future__ import annotations

import json
import shutil
import subprocess
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.opcua.conftest import Served, make_served
from tests.opcua.test_security import PASSWORD, client_certificate

NODE_DIR = Path(__file__).resolve().parent / "node_client"


def _skip_without_node() -> None:
    if shutil.which("node") is None:
        pytest.skip("node is not installed (as root: apt-get install nodejs npm), so node-opcua cannot run")
    if not (NODE_DIR / "node_modules" / "node-opcua-client").is_dir():
        pytest.skip(f"node-opcua is not installed: npm ci --prefix {NODE_DIR} (make test does it)")


def _pem(der: Path) -> Path:
    from cryptography import x509
    from cryptography.hazmat.primitives.serialization import Encoding

    pem = der.with_suffix(".pem")
    pem.write_bytes(x509.load_der_x509_certificate(der.read_bytes()).public_bytes(Encoding.PEM))
    return pem


def _lines(text: str) -> list[dict[str, Any]]:
    return [json.loads(line[3:]) for line in text.splitlines() if line.startswith("@@ ")]


def _start(opts: dict[str, Any], tmp: Path) -> subprocess.Popen[str]:
    return subprocess.Popen(["node", str(NODE_DIR / "client.js"), json.dumps({"pki": str(tmp), **opts})],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)


def _run(opts: dict[str, Any], tmp: Path, timeout_s: float = 60.0) -> list[dict[str, Any]]:
    proc = _start(opts, tmp)
    try:
        out, _ = proc.communicate(timeout=timeout_s)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(10)
    return _lines(out)


@pytest.fixture
def insecure(qapp: Any, tmp_path: Path) -> Iterator[Served]:
    _skip_without_node()
    s = make_served(qapp, tmp_path / "state")
    yield s
    s.ctl.shutdown()


def test_the_secure_endpoint_serves_a_trusted_node_opcua_client_and_refuses_the_rest(
        qapp: Any, tmp_path: Path) -> None:
    _skip_without_node()
    from opcua_server.security import UserFile, folder

    state = tmp_path / "state"
    base = folder(state)
    UserFile(base / "users").add("mes", PASSWORD)
    key, cert = client_certificate(tmp_path / "client")
    shutil.copy(cert, base / "trusted" / "client.der")
    other_key, other_cert = client_certificate(tmp_path / "other")
    served = make_served(qapp, state, secure=True)
    try:
        user = {"url": served.url, "action": "read", "user": "mes", "password": PASSWORD}
        trusted = _run({**user, "security": "sign_encrypt", "cert_pem": str(_pem(cert)), "key": str(key)},
                       tmp_path / "n1")
        assert trusted == [{"ok": True, "serial": trusted[0].get("serial")}]
        assert str(trusted[0]["serial"]).endswith(served.ctl.config.machine.name)
        over_none = _run({**user, "security": "none"}, tmp_path / "n2")
        # node-opcua finds no None endpoint and stops before CreateSession (asyncua's client,
        # made to go on, is refused by the server: test_security.py)
        assert len(over_none) == 1 and over_none[0]["ok"] is False
        assert "securityMode = None" in over_none[0]["error"]
        untrusted = _run({**user, "security": "sign_encrypt", "cert_pem": str(_pem(other_cert)),
                          "key": str(other_key)}, tmp_path / "n3")
        assert len(untrusted) == 1 and untrusted[0]["ok"] is False
        assert [p.read_bytes() for p in (base / "rejected").glob("*.der")] == [other_cert.read_bytes()]
        server = served.ctl.remote.server
        assert server is not None and server.guard is not None
        assert server.guard.counts.security_rejected == 1
        assert server.guard.counts.created_sessions == 1             # the trusted client's alone
    finally:
        served.ctl.shutdown()


def _listen(served: Served, tmp: Path, refresh: bool) -> subprocess.Popen[str]:
    proc = _start({"url": served.url, "action": "events", "refresh": refresh, "seconds": 3}, tmp)
    assert proc.stdout is not None
    for line in proc.stdout:                     # wait until it is subscribed
        if line.startswith("@@ "):
            assert "subscribed" in json.loads(line[3:]), line
            break
    return proc


def _events(proc: subprocess.Popen[str]) -> list[dict[str, Any]]:
    """Everything the listener says after it subscribed, to its end. Read through the same
    text stream as the subscription line: what that read took in ahead of it (the refresh's
    result comes right after) is in the stream's buffer, which ``communicate`` (reading the
    pipe itself) would skip."""
    assert proc.stdout is not None
    killer = threading.Timer(60.0, proc.kill)
    killer.start()
    try:
        out = proc.stdout.read()
        proc.wait()
    finally:
        killer.cancel()
    return _lines(out)


def test_node_opcua_subscribed_on_the_server_object_receives_the_estop_condition(
        insecure: Served, tmp_path: Path) -> None:
    ctl = insecure.ctl
    proc = _listen(insecure, tmp_path, refresh=False)
    try:
        ctl.estop()
        insecure.step(0.5)
        insecure.settle()
    finally:
        told = _events(proc)
    alarm = [a for a in ctl.active_alarms if a.code == "estop"][-1]
    found = [t["event"] for t in told if "event" in t and alarm.cause in str(t["event"]["Message"])]
    assert len(found) == 1, told
    e = found[0]
    assert [name for name, value in e.items() if value is None] == []
    assert e["ConditionId"] == f"ns={e['ConditionId'].split(';')[0][3:]};s=Alarms.{alarm.id}"
    assert e["Retain"] is True and e["EnabledState.Id"] is True and e["ActiveState.Id"] is True
    assert e["AckedState.Id"] is False and e["Severity"] == e["LastSeverity"] == 1000
    assert e["ConditionClassId"] == "ns=0;i=17218"                # SafetyConditionClassType
    assert e["dataTypes"]["BranchId"] == "NodeId"


def test_node_opcua_connecting_late_learns_the_active_alarm_by_condition_refresh(
        insecure: Served, tmp_path: Path) -> None:
    ctl = insecure.ctl
    ctl.estop()
    insecure.step(0.5)
    insecure.settle()
    alarm = [a for a in ctl.active_alarms if a.code == "estop"][-1]
    proc = _listen(insecure, tmp_path, refresh=True)
    try:
        insecure.step(0.5)
    finally:
        told = _events(proc)
    assert {"refresh": "Good"} in told, [t for t in told if "event" not in t]   # the client's own words
    found = [t["event"] for t in told if "event" in t and alarm.cause in str(t["event"]["Message"])]
    assert len(found) == 1 and found[0]["Retain"] is True and found[0]["ActiveState.Id"] is True, told


def test_node_opcua_walks_the_machine_and_finds_every_value_stamped(insecure: Served, tmp_path: Path) -> None:
    (walked,) = _run({"url": insecure.url, "action": "walk"}, tmp_path)
    assert walked.get("variables", 0) > 60, walked
    assert walked["noValue"] == [] and walked["noTimestamp"] == []
    assert walked["signalModes"] == [0, 0, 0]             # Continuous, on each of the three lamps
    assert walked["diagnostics"]["currentSessionCount"] == 1
    assert walked["diagnostics"]["cumulatedSessionCount"] >= 1
    assert len(walked["applicationUris"]) == 1 and "freeopcua" not in walked["applicationUris"][0]
