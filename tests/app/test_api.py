"""The controller's public face (``MachineApi``) is what the panel uses, and both the real
controller and the pages' test double have all of it with the same signatures, so a page
test on the double says something about the panel on the real machine."""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import pytest
from PySide6.QtCore import Signal

from app.machine.api import MachineApi
from app.machine.controller import MachineController
from tests.app.fake_controller import FakeController

APP = Path(__file__).resolve().parents[2] / "app"


def _protocol_members() -> tuple[set[str], dict[str, inspect.Signature], set[str]]:
    signals = {k for k, v in MachineApi.__annotations__.items() if "SignalInstance" in str(v)}
    methods, props = {}, set()
    for name, value in vars(MachineApi).items():
        if name.startswith("_"):
            continue
        if isinstance(value, property):
            props.add(name)
        elif inspect.isfunction(value):
            methods[name] = inspect.signature(value)
    return signals, methods, props


SIGNALS, METHODS, PROPERTIES = _protocol_members()


def test_the_protocol_is_not_empty() -> None:
    assert len(SIGNALS) >= 20 and len(METHODS) >= 30 and len(PROPERTIES) >= 25


def _params(sig: inspect.Signature) -> list[tuple[str, inspect._ParameterKind]]:
    return [(p.name, p.kind) for p in sig.parameters.values() if p.name != "self"]


@pytest.mark.parametrize("impl", [MachineController, FakeController], ids=["controller", "double"])
def test_implementations_have_every_member_with_its_signature(qapp, impl: type) -> None:
    missing, different = [], []
    for name in SIGNALS:
        if not isinstance(getattr(impl, name, None), Signal):
            missing.append(f"signal {name}")
    instance = impl() if impl is FakeController else None
    for name in PROPERTIES:
        is_property = isinstance(getattr(impl, name, None), property)
        if not (is_property or (instance is not None and hasattr(instance, name))):
            missing.append(f"property {name}")
    for name, sig in METHODS.items():
        fn = getattr(impl, name, None)
        if not callable(fn):
            missing.append(f"method {name}")
            continue
        got, want = _params(inspect.signature(fn)), _params(sig)
        # the same parameters in the same order; an implementation may add optional ones after them
        extra = list(inspect.signature(fn).parameters.values())[len(want) + 1:]
        required_extra = [p for p in extra if p.default is p.empty and p.kind not in (p.VAR_POSITIONAL,
                                                                                      p.VAR_KEYWORD)]
        if got[: len(want)] != want or required_extra:
            different.append(f"{name}{inspect.signature(fn)} instead of {name}{sig}")
    assert not missing, missing
    assert not different, different


def _names_used_on_the_controller(path: Path) -> set[str]:
    """Attributes read from the controller in a module: ``controller.X``, ``c.X`` where
    ``c = ...controller``, and ``getattr(c, "X", ...)``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))

    def is_controller(node: ast.expr) -> bool:
        """ctx.controller, self.ctx.controller, context.controller"""
        if not (isinstance(node, ast.Attribute) and node.attr == "controller"):
            return False
        owner = node.value
        if isinstance(owner, ast.Name):
            return owner.id in ("ctx", "context", "_ctx")
        return isinstance(owner, ast.Attribute) and owner.attr in ("ctx", "context", "_ctx")

    aliases = {"controller"}
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and is_controller(node.value):
            aliases |= {t.id for t in node.targets if isinstance(t, ast.Name)}

    def is_base(node: ast.expr) -> bool:
        return (isinstance(node, ast.Name) and node.id in aliases) or is_controller(node)

    used = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and is_base(node.value):
            used.add(node.attr)
        elif isinstance(node, ast.Call) and getattr(node.func, "id", "") == "getattr" \
                and len(node.args) >= 2:
            key = node.args[1]
            if is_base(node.args[0]) and isinstance(key, ast.Constant) and isinstance(key.value, str):
                used.add(key.value)
    return used


def test_pages_and_widgets_use_only_the_protocol() -> None:
    allowed = SIGNALS | set(METHODS) | PROPERTIES | {"connect", "emit"}
    offenders = {}
    modules = [*(APP / "pages").glob("*.py"), *(APP / "widgets").glob("*.py"), APP / "main_window.py"]
    for path in sorted(modules):
        extra = _names_used_on_the_controller(path) - allowed
        if extra:
            offenders[str(path.relative_to(APP))] = sorted(extra)
    assert not offenders, offenders
