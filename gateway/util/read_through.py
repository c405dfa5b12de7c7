"""An attribute an object reads of one of its parts, under the same name (a vehicle's ``sysid`` is its
link's ``sysid``): declared in one line instead of a property each."""

from __future__ import annotations

from typing import Generic, Self, TypeVar, overload

T = TypeVar("T")


class ReadThrough(Generic[T]):
    """``sysid = ReadThrough[int | None]("link")``: reading ``obj.sysid`` reads ``obj.link.sysid``
    (read-only: a write raises AttributeError, like a property without a setter; with ``writable`` a
    write sets the part's attribute)."""

    def __init__(self, part: str, *, writable: bool = False) -> None:
        self.part = part
        self.writable = writable
        self.name = ""

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    @overload
    def __get__(self, obj: None, owner: type) -> Self: ...

    @overload
    def __get__(self, obj: object, owner: type) -> T: ...

    def __get__(self, obj: object | None, owner: type) -> T | Self:
        if obj is None:
            return self
        result: T = getattr(getattr(obj, self.part), self.name)
        return result

    def __set__(self, obj: object, value: T) -> None:
        if not self.writable:
            raise AttributeError(f"{self.name} is read from {self.part}: set it there")
        setattr(getattr(obj, self.part), self.name, value)
