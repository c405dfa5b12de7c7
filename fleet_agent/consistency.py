"""Does a valid plan carry what its request gives, read by the fleet's ids and the numbers? A plan can leave
out a drone or a number the request gives, or fly a drone it does not name: each gap is a note the planner
sends back once. A request that names no drone (``all three``) is not read for ids."""

from __future__ import annotations

from typing import Any

from fleet_agent import arithmetic, lexicon
from fleet_agent.plan import DRONE_FIELDS, Condition, Plan, Report, parse_plan
from fleet_agent.units import Unit


def gaps(request: str, fleet: list[str], plan: Plan) -> list[str]:
    """What the plan leaves out of (or adds to) the request: one short note each."""
    data = plan.model_dump(mode="json")
    notes = _drone_gaps(request, fleet, data)
    numbers = _plan_numbers(data)
    for given in _request_numbers(request, fleet):
        if not any(abs(given - n) < 1e-6 for n in numbers):
            notes.append(f"the request gives {given:g}, which no step of the plan has")
    return notes


def read_plan(request: str, fleet: list[str], data: Any) -> tuple[Plan, list[str]]:
    """The decoded reply as the plan the host compiles (every rewrite before compiling, in order), and a note
    for each thing it leaves out of the request; raises the validation error of an invalid plan."""
    data = as_stated(request, split_formation(request, flown_on(as_ended(request, data))))
    data = as_request_says(request, data)
    plan = without_unasked(request, fleet, parse_plan(placed_by_name(request, fleet, data), fleet))
    return questions_of_fleet(request, fleet, plan), gaps(request, fleet, plan)


def without_unasked(request: str, fleet: list[str], plan: Plan) -> Plan:
    """The plan without steps that cannot be meant: a step of a drone the request does not name with a
    number it does not give, when the named drones' steps carry only its numbers (a copied example's step;
    "the others" keep theirs); a step whose numbers are all 0, in a request that gives no 0."""
    named = _named(request, fleet)
    given = _request_numbers(request, fleet)
    if 0 not in given and any(map(_all_zero, plan.steps)):
        plan = plan.model_copy(update={"steps": [s for s in plan.steps if not _all_zero(s)]})
    if not named or not all(_only(_step_numbers(s), given) for s in _steps_of(plan.steps, named)):
        return plan
    return plan.model_copy(update={"steps": _asked(plan.steps, named, given)})


def _all_zero(step: Any) -> bool:
    """A step whose numbers are all 0 goes nowhere (a move of 0 m for a drone kept still, a climb to 0 m
    after a hover); an ``if`` against 0 compares (a question of two drones, read by questions_of_fleet)."""
    numbers = _step_numbers(step)
    return bool(numbers) and not any(numbers) and not isinstance(step, Condition)


def _asked(steps: list[Any], named: set[str], given: list[float]) -> list[Any]:
    """``steps`` without a step of a drone not in ``named`` carrying a number not in ``given``, an
    ``if``'s branches included (a choice's steps name whichever drone; the chosen one flies them)."""
    kept = []
    for step in steps:
        drone = getattr(step, "drone", None)
        if drone not in (None, *named) and not _only(_step_numbers(step), given):
            continue
        if isinstance(step, Condition):
            then, otherwise = _asked(step.then, named, given), _asked(step.otherwise, named, given)
            step = step.model_copy(update={"then": then, "otherwise": otherwise})
        kept.append(step)
    return kept


def _steps_of(steps: list[Any], named: set[str]) -> list[Any]:
    """The steps (branches included) of the drones in ``named``."""
    found = []
    for step in steps:
        if getattr(step, "drone", None) in named:
            found.append(step)
        if isinstance(step, Condition):
            found += _steps_of(step.then + step.otherwise, named)
    return found


def _step_numbers(step: Any) -> list[float]:
    return _plan_numbers(step.model_dump(mode="json", exclude={"then", "otherwise"}))


def _only(numbers: list[float], given: list[float]) -> bool:
    return all(any(abs(n - g) < 1e-6 for g in given) for n in numbers)


def _named(request: str, fleet: list[str]) -> set[str]:
    """The ids that are a word of the request or joined to one by a hyphen ("charlie-ஐ", "ל-alpha")."""
    words = [f"-{w}-" for w in _words(request.lower())]
    return {d for d in fleet if any(f"-{d.lower()}-" in w for w in words)}


def _drone_gaps(request: str, fleet: list[str], data: Any) -> list[str]:
    named = _named(request, fleet)
    if not named:
        return []
    planned = _plan_drones(data)
    notes = [
        f"the request names {d}, which no step of the plan does (as the drone that acts, as a move's "
        f'origin "{d}", or in a hold step when the request leaves {d} alone)'
        for d in sorted(named - planned)
    ]
    notes += [f"the plan has {d}, which the request does not name" for d in sorted(planned - named)]
    return notes


def _words(text: str) -> list[str]:
    """The words of a text, in any script: runs of letters and digits (an id is matched against these)."""
    return "".join(c if c.isalnum() or c in "_-" else " " for c in lexicon.by_script(text)).split()


def _request_numbers(request: str, fleet: list[str]) -> list[float]:
    """The numbers of the request (digits, with a decimal point or comma), a drone id's digits left out."""
    ids = {d.lower() for d in fleet}
    text = " ".join(w for w in lexicon.by_script(request).split() if w.lower().strip(".,;:!?") not in ids)
    return [abs(value) for value in lexicon.numbers(text)]


def _plan_drones(data: Any) -> set[str]:
    found: set[str] = set()
    for key, value in _items(data):
        if key in DRONE_FIELDS:
            items = [value] if isinstance(value, str) else value or []
            found.update(v for v in items if isinstance(v, str))
    return found


def _plan_numbers(data: Any) -> list[float]:
    """The plan's numbers, those its arithmetic values are worked out from included."""
    found = [float(v) for _, v in _items(data) if isinstance(v, int | float) and not isinstance(v, bool)]
    worked = [v for k, v in _items(data) if k == "value" and isinstance(v, str)]
    return found + [n for v in worked for n in arithmetic.numbers(v)]


def _items(data: Any) -> list[tuple[str, Any]]:
    """Every (key, value) of a decoded JSON document, nested ones included."""
    out: list[tuple[str, Any]] = []
    if isinstance(data, dict):
        for key, value in data.items():
            out += [(key, value), *_items(value)]
    elif isinstance(data, list):
        out = [item for value in data for item in _items(value)]
    return out


def as_request_says(request: str, data: Any) -> Any:
    """The decoded plan with what the request's words settle put right, before validation: a length whose
    number the request gives with one unit carries that unit (feet written as metres), and a move from its
    own drone, in a request that speaks of home, is from its home. Words the lexicon does not know leave
    the plan as written."""
    if not isinstance(data, dict) or not isinstance(data.get("steps"), list):
        return data
    units = lexicon.number_units(request)
    for _, value in _items(data):
        if isinstance(value, dict) and {"value", "unit"} <= value.keys():
            given = units.get(value["value"]) if isinstance(value["value"], int | float) else None
            if given is None and value["unit"] == "m" and _fraction(value["value"], units):
                given = units[None]  # "a tenth of a mile" written as 0.1 m
            if given is not None and len(given) == 1:
                value["unit"] = str(next(iter(given)))
    ends = {v for k, v in _items(data) if k in ("action", "after")}
    if "return_home" not in ends and lexicon.says(request, lexicon.HOME_STEMS):
        for step in data["steps"]:
            if _from_itself(step):
                step["origin"] = "home"
    return data


def _from_itself(step: Any) -> bool:
    if not isinstance(step, dict) or step.get("drone") is None:
        return False
    origin = step.get("origin")
    return bool((origin.get("drone") if isinstance(origin, dict) else origin) == step["drone"])


def _fraction(value: Any, units: dict[float | None, set[Unit]]) -> bool:
    """``value`` is a fraction the request does not write in digits, and it names a unit with no number."""
    return isinstance(value, int | float) and 0 < value < 1 and value not in units and None in units


def placed_by_name(request: str, fleet: list[str], data: Any) -> Any:
    """The decoded plan with its one move from ``here`` measured from the drone the request names after its
    distance in the same clause, when that drone is nowhere in the plan ("25 m north of <drone>")."""
    if not isinstance(data, dict) or not isinstance(data.get("steps"), list):
        return data
    moves = [s for s in data["steps"] if _horizontal_move_from_here(s)]
    absent = _named(request, fleet) - _plan_drones(data) - _origins(data["steps"])
    if len(moves) != 1 or len(absent) != 1:
        return data
    other = next(iter(absent))
    distances = {leg["distance"].get("value") for leg in moves[0]["legs"] if _horizontal(leg)}
    if any(_after_number(clause, other, distances) for clause in lexicon.clauses(request)):
        moves[0]["origin"] = other
    return data


def as_ended(request: str, data: Any) -> Any:
    """The decoded plan with no landing or return when the request says a drone stays in the air and nothing
    of coming down or a home, in words the lexicon knows ("let them hover" was planned as a landing)."""
    stays = isinstance(data, dict) and lexicon.says(request, lexicon.STAY_STEMS)
    if stays and not lexicon.says(request, lexicon.DOWN_STEMS + lexicon.HOME_STEMS):
        data["steps"] = _stayed(data.get("steps"))
    return data


_ENDINGS = ("land", "return_home")


def _stayed(steps: Any) -> Any:
    if not isinstance(steps, list):
        return steps
    kept = [s for s in steps if not (isinstance(s, dict) and s.get("action") in _ENDINGS)]
    for step in filter(lambda s: isinstance(s, dict), kept):
        step.update({"after": "stay"} if step.get("after") in _ENDINGS else {})
        step.update({b: _stayed(step[b]) for b in ("then", "otherwise") if b in step})
    return kept


def flown_on(data: Any) -> Any:
    """The decoded plan without the landing or return a drone's step ends with when its next step flies it
    on (a move, a pattern, its return home; a takeoff after a landing keeps it)."""
    steps = data.get("steps") if isinstance(data, dict) else None
    steps = [s for s in steps if isinstance(s, dict)] if isinstance(steps, list) else []
    for k, step in enumerate(steps):
        mine = [s.get("action") for s in steps[k + 1 :] if s.get("drone") == step.get("drone")]
        if mine[:1] in (["move"], ["pattern"], ["return_home"]) and step.get("after") in _ENDINGS:
            step["after"] = "stay"
    return data


def as_stated(request: str, data: Any) -> Any:
    """The decoded plan with its legs going the ways the restatement, then the request (its words win), name
    for their numbers (`_as_said`); a restatement copying the request is not read."""
    said = str(data.get("in_english") or "") if isinstance(data, dict) else ""
    if said and said.strip() != request.strip():
        data = _as_said(said, data)
    return _as_said(request, data, known=bool(lexicon.compass_points(request)))


def _as_said(text: str, data: Any, known: bool = True) -> Any:
    """The plan with the k-th leg of a length going the way ``text`` names after its k-th such number, or
    its one leg or first side the way of the text's one compass word; a drone's first move at no altitude,
    with more legs than the text names ways, climbs to its first leg's number when the text names it with
    no way (with ``known`` false, no leg is given a way and only a move of two legs or more climbs)."""
    steps = data.get("steps") if isinstance(data, dict) else None
    if not isinstance(steps, list):
        return data
    points, ways = lexicon.compass_points(text), lexicon.stated_ways(text)
    unnamed = len(_compass_slots(steps)) - len(points)  # each climb takes one horizontal leg away
    for k, step in enumerate(steps):
        if unnamed > 0 and _climbs_first(ways, steps[:k], step, 1 if known else 2):
            steps[k], unnamed = _climbing(step), unnamed - 1
    slots = _compass_slots(steps)
    if len(slots) == len(points) == 1:
        slots[0][0][slots[0][1]] = points[0]
        return data
    legs = [holder for holder, key in slots if key == "direction" and known]
    for value in {leg["distance"].get("value") for leg in legs}:
        named = [way for number, way in ways if number == value]
        same = [leg for leg in legs if leg["distance"].get("value") == value]
        if len(named) == len(same) and None not in named:
            for leg, way in zip(same, named, strict=True):
                leg["direction"] = way
    return data


def _compass_slots(steps: list[Any]) -> list[tuple[dict[str, Any], str]]:
    """Where the plan names a compass point, in order: each horizontal leg of a move or a formation, each
    pattern's first side (named or not), an ``if``'s and a choice's steps included."""
    slots: list[tuple[dict[str, Any], str]] = []
    for step in filter(lambda s: isinstance(s, dict), steps):
        slots += [(leg, "direction") for leg in step.get("legs") or [] if _horizontal(leg)]
        slots += [(step, "heading")] if step.get("action") == "pattern" else []
        for branch in ("then", "otherwise"):
            slots += _compass_slots(step.get(branch) or []) if isinstance(step.get(branch), list) else []
    return slots


def _climbs_first(ways: list[tuple[float, str | None]], earlier: list[Any], step: Any, legs: int) -> bool:
    """``step`` is its drone's first, a move from where it is at no altitude (or 0 m) with at least ``legs``
    horizontal legs, the first of them first, and the text names that leg's number once, with no way."""
    flat = _horizontal_move_from_here(step) and sum(map(_horizontal, step["legs"])) >= legs
    if not flat or (step.get("altitude") or {}).get("value") or not _horizontal(leg := step["legs"][0]):
        return False
    if step.get("drone") in {s.get("drone") for s in earlier if isinstance(s, dict)}:
        return False
    return [way for number, way in ways if number == leg["distance"].get("value")] == [None]


def _climbing(move: dict[str, Any]) -> dict[str, Any]:
    """The move with its first leg's length as the altitude it flies at; with no leg left, a climb."""
    move["altitude"] = move["legs"].pop(0)["distance"]
    if move["legs"]:
        return move
    return {"action": "altitude", **{k: move.get(k) for k in ("drone", "altitude", "after")}}


def _horizontal(leg: Any) -> bool:
    is_leg = isinstance(leg, dict) and isinstance(leg.get("distance"), dict)
    return is_leg and leg.get("direction") not in ("up", "down")


def _horizontal_move_from_here(step: Any) -> bool:
    move = isinstance(step, dict) and step.get("action") == "move"
    from_here = move and step.get("origin") in ("here", {"kind": "here"})
    return from_here and any(_horizontal(leg) for leg in step.get("legs") or [])


def _origins(steps: list[Any]) -> set[str]:
    origins = [step.get("origin") for step in steps if isinstance(step, dict)]
    found = [origin.get("drone") if isinstance(origin, dict) else origin for origin in origins]
    return {origin for origin in found if isinstance(origin, str)}


def _after_number(clause: str, drone: str, distances: set[Any]) -> bool:
    """``clause`` names ``drone`` after one of ``distances`` (a number)."""
    tokens = lexicon.tokens(clause.lower())
    if drone.lower() not in tokens:
        return False
    before = tokens[: tokens.index(drone.lower())]
    return any(lexicon.number(t) in distances for t in before)


def split_formation(request: str, data: Any) -> Any:
    """The decoded plan with a formation whose drones the request names each right before one of its legs'
    distances ("<a> N m east and <b> M m north") flown as one move each: sent different ways."""
    if not isinstance(data, dict) or not isinstance(data.get("steps"), list):
        return data
    tokens = lexicon.tokens(request.lower())
    steps: list[Any] = []
    for step in data["steps"]:
        pairs = _each_its_leg(step, tokens)
        if pairs is None:
            steps.append(step)
            continue
        altitude = step.get("altitude")
        steps += [
            {"action": "move", "drone": drone, "origin": "here", "legs": [leg], "altitude": altitude,
             "after": "stay"}
            for drone, leg in pairs
        ]  # fmt: skip
    data["steps"] = steps
    return data


def _each_its_leg(step: Any, tokens: list[str]) -> list[tuple[str, Any]] | None:
    """The formation's drones, each with the leg whose distance follows its name in the request before
    the next drone's name; None when the step is not such a formation."""
    formation = isinstance(step, dict) and step.get("action") == "formation"
    if not formation or step.get("origin") not in (None, "here"):
        return None
    drones, legs = step.get("drones") or [], list(step.get("legs") or [])
    if len(drones) < 2 or len(legs) != len(drones) or not all(_horizontal(leg) for leg in legs):
        return None
    at = {d: tokens.index(d.lower()) for d in drones if isinstance(d, str) and d.lower() in tokens}
    order = sorted(at, key=at.__getitem__)
    if len(order) != len(drones):
        return None
    pairs = []
    for k, drone in enumerate(order):
        end = at[order[k + 1]] if k + 1 < len(order) else len(tokens)
        values = [lexicon.number(t) for t in tokens[at[drone] : end]]
        leg = next((leg for leg in legs if leg["distance"].get("value") in values), None)
        if leg is None:
            return None
        legs.remove(leg)
        pairs.append((drone, leg))
    return pairs


def questions_of_fleet(request: str, fleet: list[str], plan: Plan) -> Plan:
    """An ``if`` that only tells, in a request of more drones than its one, or that flies with none of the
    request's numbers (a copied example), read as a report of the named drones (done after the gaps)."""
    drones, given = sorted(_named(request, fleet)) or list(fleet), _request_numbers(request, fleet)
    return plan.model_copy(update={"steps": [_as_report(step, drones, given) for step in plan.steps]})


def _as_report(step: Any, drones: list[str], given: list[float]) -> Any:
    if not isinstance(step, Condition):
        return step
    told = all(isinstance(s, Report) for s in step.then + step.otherwise)
    numbers = [n for s in step.then + step.otherwise for n in _step_numbers(s)]
    copied = bool(numbers) and not any(_only([n], given) for n in [step.value, *numbers])
    if not copied and (not told or drones == [step.drone]):
        return step
    pick = "lowest" if step.compare in ("below", "at_most") else "highest"
    return Report(action="report", drones=drones, readings=[step.reading], pick=pick)
