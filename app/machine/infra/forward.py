"""The facade's members declared, not written: each command is its part's method, each
read-only property its part's attribute.

``forward(part, Part.method)`` makes a class attribute that, read on an instance, is the bound
method of the part (its own name, signature and docstring: ``inspect`` and the type checker
see the part's method); read on the class, it is the part's function. ``name: reads[T] =
reads(part, "attr")`` is a ``property`` reading the part's attribute. ``part`` picks the part
from the facade.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Concatenate, Generic, ParamSpec, TypeVar, overload

__all__ = ["forward", "reads"]

P = ParamSpec("P")
R = TypeVar("R")
T = TypeVar("T")
O = TypeVar("O")


class forward(Generic[O, P, R]):  # noqa: N801 - used like a decorator
    """A command of the facade that is its part's method."""

    def __init__(self, part: Callable[[Any], O], fn: Callable[Concatenate[O, P], R]) -> None:
        self._part = part
        self._fn = fn
        self.__doc__ = fn.__doc__
        self.__wrapped__ = fn

    @overload
    def __get__(self, obj: None, owner: type | None = None) -> Callable[Concatenate[O, P], R]: ...

    @overload
    def __get__(self, obj: object, owner: type | None = None) -> Callable[P, R]: ...

    def __get__(self, obj: object | None, owner: type | None = None) -> Any:
        if obj is None:
            return self._fn
        return self._fn.__get__(self._part(obj))


class reads(property, Generic[T]):  # noqa: N801 - used like a decorator
    """A read-only property of the facade that is its part's attribute."""

    def __init__(self, part: Callable[[Any], Any], attr: str, doc: str | None = None) -> None:
        super().__init__(lambda obj: getattr(part(obj), attr), doc=doc)

    @overload
    def __get__(self, obj: None, owner: type | None = None) -> reads[T]: ...

    @overload
    def __get__(self, obj: object, owner: type | None = None) -> T: ...

    def __get__(self, obj: object | None, owner: type | None = None) -> Any:
        return super().__get__(obj, owner)
