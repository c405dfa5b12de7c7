"""Who asked for a command: the door it came through, the principal, the session.

The door decides the policy's treatment (docs/safety.md): operators (REST, the console) are not held
by operator locks or the simulators-only switch, may kill motors in flight and may interrupt a takeoff;
agents (MCP) are. A call forwarded by another cluster node keeps the Caller of the door it came
through; ``via="cluster"`` is for commands a node originates itself and is judged as an agent's.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal, TypedDict, get_args

from gateway.errors import InvalidArgument
from gateway.fleet.policy.safety_rules import Via

Door = Literal["mcp", "rest", "console", "cluster"]
DOORS: tuple[Door, ...] = get_args(Door)
OPERATOR_DOORS = frozenset({"rest", "console"})


class CallerBody(TypedDict):
    """A `Caller` as JSON (a call forwarded to another cluster node carries it)."""

    via: Door
    principal: str
    session: str | None


@dataclass(frozen=True)
class Caller:
    via: Door
    principal: str
    session: str | None = None

    def __post_init__(self) -> None:
        if self.via not in DOORS:
            raise InvalidArgument(f"via must be one of {', '.join(DOORS)}; got {self.via!r}")

    @property
    def is_operator(self) -> bool:
        return self.via in OPERATOR_DOORS

    @property
    def policy_via(self) -> Via:
        """How the safety policy judges this caller: as an operator ("rest") or as an agent ("mcp")."""
        return "rest" if self.is_operator else "mcp"

    def to_dict(self) -> CallerBody:
        return CallerBody(via=self.via, principal=self.principal, session=self.session)

    @classmethod
    def from_dict(cls, data: Mapping[str, object]) -> Caller:
        """The caller of a forwarded call, from its JSON (`to_dict`, perhaps with more keys)."""
        try:
            via, principal, session = data["via"], str(data["principal"]), data.get("session")
        except KeyError as exc:
            raise InvalidArgument(f"a caller needs '{exc.args[0]}' (via, principal, session)") from None
        door = next((d for d in DOORS if d == via), None)
        if door is None:
            raise InvalidArgument(f"via must be one of {', '.join(DOORS)}; got {via!r}")
        return cls(via=door, principal=principal, session=None if session is None else str(session))
