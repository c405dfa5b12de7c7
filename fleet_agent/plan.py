"""The plan a model writes: request-shaped steps, typed. ``plan_schema(ids)``, what the model decodes under,
makes drone fields an ``enum`` of the fleet's ids; ``parse_plan`` refuses others. Lengths carry units."""

from __future__ import annotations

import copy
from enum import StrEnum
from typing import Annotated, Any, Literal, TypeGuard

from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    ValidationInfo,
    field_validator,
    model_validator,
)

from fleet_agent import arithmetic
from fleet_agent.units import Unit, to_metres


class Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Length(Strict):
    """A distance or an altitude as the request gave it: a number, or arithmetic of the request's numbers
    that the host works out (`fleet_agent.arithmetic`: "halfway between 8 m and 20 m" is "(8+20)/2")."""

    value: Annotated[float, Field(ge=0)] | Annotated[str, Field(max_length=arithmetic.MAX_CHARS)]
    unit: Unit

    @field_validator("value")
    @classmethod
    def _worked_out(cls, value: float | str) -> float | str:
        if isinstance(value, str) and arithmetic.evaluate(value) < 0:
            raise ValueError(f"value {value!r} works out below 0; a length is 0 or more")
        return value

    @property
    def metres(self) -> float:
        value = arithmetic.evaluate(self.value) if isinstance(self.value, str) else self.value
        return to_metres(value, self.unit)


def _zero_is_none(value: Any) -> Any:
    """A move's or a pattern's 0 m is no height given: both models wrote 0 where the request gave none."""
    return None if isinstance(value, dict) and value.get("value") == 0 else value


FlownHeight = Annotated[Length | None, BeforeValidator(_zero_is_none)]


class Direction(StrEnum):
    north, south, east, west = "north", "south", "east", "west"
    northeast, northwest, southeast, southwest = "northeast", "northwest", "southeast", "southwest"
    up, down = "up", "down"


#: the most legs a move or a formation holds (a small model repeated a shuttle's leg to its token limit)
MAX_LEGS = 8
_PAIRS = "north-south east-west up-down northeast-southwest northwest-southeast".split()
OPPOSITE = {a: b for pair in _PAIRS for a, b in (pair.split("-"), pair.split("-")[::-1])}


class Leg(Strict):
    """A negative distance is the other way ("-20 m north" is 20 m south: a model copied a signed offset)."""

    distance: Length
    direction: Direction

    @model_validator(mode="before")
    @classmethod
    def _signed(cls, leg: Any) -> Any:
        length = leg.get("distance") if isinstance(leg, dict) else None
        if isinstance(length, dict) and isinstance(length.get("value"), int | float) and length["value"] < 0:
            flipped = OPPOSITE.get(leg.get("direction"), leg.get("direction"))
            return {**leg, "distance": {**length, "value": -length["value"]}, "direction": flipped}
        return leg


class Reference(Strict):
    """Where a move is measured from: the drone itself (here), its home, another drone, a place, a point."""

    kind: Literal["here", "home", "drone", "place", "point"]
    drone: str | None = None
    place: str | None = None
    lat_deg: float | None = Field(default=None, ge=-90, le=90)
    lon_deg: float | None = Field(default=None, ge=-180, le=180)


class DroneStep(Strict):
    """A step of one drone. Each step declares its ``action`` first and then its ``drone``: a schema-guided
    decoder writes the properties in the schema's order, and the examples start a step with its action."""

    @field_validator("drone", "than", check_fields=False)
    @classmethod
    def _known_drone(cls, value: str | None, info: ValidationInfo) -> str | None:
        return None if value is None else known_drone(value, info)


def _known_drones(value: list[str], info: ValidationInfo) -> list[str]:
    return [known_drone(v, info) for v in value]


#: drone ids of the fleet (given as validation context), as the fleet spells them
DroneIds = Annotated[list[str], AfterValidator(_known_drones)]


#: what a drone does once a climb, a move or a pattern is flown, required where the step is written (a
#: landing asked for at the end was dropped as a separate step; one not asked for was added after a takeoff)
Ending = Literal["stay", "land", "return_home"]


class Takeoff(DroneStep):
    """Up to ``altitude``, then ``after`` (``stay`` when read; required in the schema, `plan_schema`)."""

    action: Literal["takeoff"]
    drone: str
    altitude: Length
    after: Ending = "stay"


class Land(DroneStep):
    action: Literal["land"]
    drone: str


class ReturnHome(DroneStep):
    action: Literal["return_home"]
    drone: str


class Hold(DroneStep):
    action: Literal["hold"]
    drone: str


class Altitude(DroneStep):
    """Climb or descend to an altitude above home (taking off first when on the ground)."""

    action: Literal["altitude"]
    drone: str
    altitude: Length
    after: Ending = "stay"


class Move(DroneStep):
    """Legs from ``origin`` (before the legs: a decoder writes the schema's order), at ``altitude`` above
    home when given. The origin may be one word, ``here``, ``home`` or a drone's id, as small models write."""

    action: Literal["move"]
    drone: str
    origin: Reference
    legs: list[Leg] = Field(max_length=MAX_LEGS)
    altitude: FlownHeight
    after: Ending

    @field_validator("origin", mode="before")
    @classmethod
    def _origin_word(cls, value: Any, info: ValidationInfo) -> Any:
        if not isinstance(value, str):
            return value
        if value in ORIGIN_WORDS:
            return {"kind": value}
        return {"kind": "drone", "drone": known_drone(value, info)}


#: the polygons a shape's name says the sides of
POLYGON_SIDES = {"triangle": 3, "square": 4, "pentagon": 5, "hexagon": 6, "octagon": 8}


class Pattern(DroneStep):
    """A polygon with sides of ``size``; a rectangle ``size`` by ``spacing``; an orbit of radius ``size``; a
    survey of ``lines`` lines of ``size``, ``spacing`` apart. From where the drone is, first towards
    ``heading`` (null: north), turning ``turn`` (null: right). All required, null when not given."""

    action: Literal["pattern"]
    drone: str
    shape: Literal[
        "triangle", "square", "rectangle", "pentagon", "hexagon", "octagon", "polygon", "orbit", "survey"
    ]
    size: Length
    sides: int | None = Field(ge=3, le=12)
    lines: int | None = Field(ge=1, le=20)
    spacing: Length | None
    heading: Direction | None
    turn: Literal["right", "left"] | None
    altitude: FlownHeight
    after: Ending


class Formation(Strict):
    """The drones (two or more: one drone's circle is an orbit) in a shape ``spacing`` apart, centred where
    they are (or on ``origin``), then ``legs``; ``after`` is every drone's, required as a move's is."""

    action: Literal["formation"]
    drones: DroneIds = Field(min_length=2)
    shape: Literal["line", "column", "wedge", "grid", "circle", "triangle", "square"]
    spacing: Length
    altitude: Length
    legs: list[Leg] = Field(default_factory=list, max_length=MAX_LEGS)
    after: Ending = "stay"
    origin: Reference | None = None


Reading = Literal["battery", "altitude", "position", "flying", "mode"]


class Report(Strict):
    """A question: the host reads ``readings`` of ``drones`` and answers with them; ``pick`` names the
    drone with the highest or lowest first reading."""

    action: Literal["report"]
    drones: DroneIds = Field(min_length=1)
    readings: list[Reading] = Field(min_length=1)
    pick: Literal["none", "highest", "lowest"] = "none"


class Ask(Strict):
    """A question back to the user when the request cannot be planned (nothing flies)."""

    action: Literal["ask"]
    text: str = Field(min_length=1, max_length=300)


_SIMPLE_STEPS = Takeoff | Land | ReturnHome | Hold | Altitude | Move | Pattern | Formation | Report
SimpleStep = Annotated[_SIMPLE_STEPS, Field(discriminator="action")]


#: the most steps a branch, and a plan, hold: bounds the decoder keeps, so that a reply that repeats a
#: step ends soon (a small model at temperature 0 repeated a report step until its token limit)
MAX_BRANCH_STEPS = 4
MAX_PLAN_STEPS = 12
MAX_RESTATEMENT_CHARS = 300


class Condition(DroneStep):
    """``then`` when the drone's reading (less drone ``than``'s: a lead) compares true to ``value`` (% or m),
    else ``otherwise``; both required (``[]`` when not given): a decoder left out an optional one."""

    action: Literal["if"]
    drone: str
    reading: Literal["battery", "altitude"]
    than: str | None = None
    compare: Literal["above", "below", "at_least", "at_most"]
    value: float
    then: list[SimpleStep] = Field(max_length=MAX_BRANCH_STEPS)
    otherwise: list[SimpleStep] = Field(max_length=MAX_BRANCH_STEPS)


class Choose(Strict):
    """The drone of ``among`` with the highest or lowest reading does ``then`` (the drone named in those
    steps is replaced by the one chosen); the others do nothing."""

    action: Literal["choose"]
    among: DroneIds = Field(min_length=2)
    reading: Literal["battery", "altitude"]
    pick: Literal["highest", "lowest"]
    then: list[SimpleStep] = Field(min_length=1, max_length=MAX_BRANCH_STEPS)


Step = Annotated[_SIMPLE_STEPS | Condition | Choose | Ask, Field(discriminator="action")]


class Plan(Strict):
    #: the request restated in plain English, written before the steps (required in the schema, so a
    #: guided decoder writes it first): the model reads its own restatement while it writes the steps
    in_english: str = Field(default="", max_length=MAX_RESTATEMENT_CHARS)
    steps: list[Step] = Field(max_length=MAX_PLAN_STEPS)

    @model_validator(mode="after")
    def _one_ending(self) -> Plan:
        """A landing or return written both as an ``after`` and as the drone's next step is flown once. A
        climb to a height the drone already flew at repeats it: right after that climb, its ``after`` becomes
        the climb's; after a flight, only its landing or return is kept."""
        kept: list[Any] = []
        last: dict[str, int] = {}  # each drone's last step in ``kept``
        heights: dict[str, float] = {}
        for step in self.steps:
            drone = getattr(step, "drone", None)
            at = last.get(drone) if drone else None
            previous = kept[at] if at is not None else None
            if _ends_again(step, previous):
                continue
            if _repeats(step, heights, previous):
                if at is not None and previous is not None and _same_climb(step, previous):
                    kept[at] = previous.model_copy(update={"after": step.after})
                elif step.after != "stay" and not _ended(previous):
                    last = {**last, step.drone: len(kept)}
                    kept.append(_ending_step(step))
                continue
            if isinstance(step, Altitude | Move | Pattern) and step.altitude is not None:
                heights[step.drone] = step.altitude.metres
            drones = [drone] if drone else getattr(step, "drones", [])  # a formation's, a report's
            last = {**last, **dict.fromkeys(drones, len(kept))} if drones else {}
            kept.append(step)
        self.steps = kept
        return self


def _ends_again(step: Any, previous: Any) -> bool:
    """``step`` is the landing or return ``previous`` already ends with."""
    ending = isinstance(step, Land | ReturnHome) and getattr(previous, "after", None) == step.action
    return ending and step.drone in getattr(previous, "drones", [getattr(previous, "drone", None)])


def _repeats(step: Any, heights: dict[str, float], previous: Any) -> TypeGuard[Takeoff | Altitude]:
    """``step`` climbs its drone to a height the plan already flew it at: a takeoff, or a climb after the
    drone's flight ended or repeating the climb before it."""
    if not isinstance(step, Takeoff | Altitude) or heights.get(step.drone) != step.altitude.metres:
        return False
    return isinstance(step, Takeoff) or _ended(previous) or _same_climb(step, previous)


def _ended(previous: Any) -> bool:
    """``previous`` (a drone's step) ends the drone's flight: a landing, a return, or one as its after."""
    return isinstance(previous, Land | ReturnHome) or getattr(previous, "after", "stay") != "stay"


def _ending_step(step: Takeoff | Altitude) -> Land | ReturnHome:
    if step.after == "land":
        return Land(action="land", drone=step.drone)
    return ReturnHome(action="return_home", drone=step.drone)


def _same_climb(takeoff: Takeoff | Altitude, previous: Any) -> bool:
    """``previous`` climbs the takeoff's drone to the takeoff's height and stays: nothing flew between."""
    if isinstance(previous, Move):
        climb_only = all(leg.direction in ("up", "down") for leg in previous.legs)
        return climb_only and previous.origin.kind == "here" and _stays_at(previous, takeoff)
    return isinstance(previous, Altitude) and _stays_at(previous, takeoff)


def _stays_at(previous: Altitude | Move, takeoff: Takeoff | Altitude) -> bool:
    height = previous.altitude.metres if previous.altitude is not None else None
    return previous.drone == takeoff.drone and previous.after == "stay" and height == takeoff.altitude.metres


def known_drone(value: str, info: ValidationInfo) -> str:
    """The id as the fleet spells it; an id outside the fleet (given as validation context) is refused."""
    fleet: list[str] = (info.context or {}).get("fleet") or []
    if not fleet:
        return value
    by_lower = {d.lower(): d for d in fleet}
    if value.lower() not in by_lower:
        raise ValueError(f"drone {value!r} is not in the fleet; the fleet: {', '.join(fleet)}")
    return by_lower[value.lower()]


def parse_plan(data: Any, fleet: list[str]) -> Plan:
    """The plan in ``data`` (a JSON string or decoded JSON), its drone ids checked against ``fleet``."""
    if isinstance(data, str | bytes):
        return Plan.model_validate_json(data, context={"fleet": fleet})
    return Plan.model_validate(data, context={"fleet": fleet})


DRONE_FIELDS = ("drone", "drones", "among", "than")


#: the one-word origins of a move besides the fleet's ids
ORIGIN_WORDS = ["here", "home"]


def plan_schema(fleet: list[str]) -> dict[str, Any]:
    """The plan's JSON schema with every drone field (its string part: itself, its items, or its non-null
    alternative) an ``enum`` of the fleet's ids."""
    schema = copy.deepcopy(_BASE_SCHEMA)
    for definition in schema.get("$defs", {}).values():
        fields = [prop for name, prop in definition.get("properties", {}).items() if name in DRONE_FIELDS]
        for option in (o for prop in fields for o in (prop, prop.get("items", {}), *prop.get("anyOf", []))):
            if option.get("type") == "string":
                option["enum"] = list(fleet)
    schema["$defs"]["Move"]["properties"]["origin"]["anyOf"][0]["enum"] = [*ORIGIN_WORDS, *fleet]
    return schema


def _base_schema() -> dict[str, Any]:
    schema = Plan.model_json_schema()
    for definition in schema.get("$defs", {}).values():
        definition.pop("description", None)
    schema["$defs"]["Move"]["properties"]["origin"] = {
        "anyOf": [{"type": "string"}, {"$ref": "#/$defs/Reference"}]
    }
    schema["required"] = ["in_english", "steps"]
    schema["properties"]["in_english"].pop("default", None)
    for name, given in (("Takeoff", ["after"]), ("Altitude", ["after"]), ("Formation", ["legs", "after"]),
                        ("Condition", ["than"])):  # fmt: skip
        schema["$defs"][name]["required"] += given
        for prop in given:
            schema["$defs"][name]["properties"][prop].pop("default", None)
    return schema


_BASE_SCHEMA = _base_schema()
