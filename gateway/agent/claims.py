"""What a model's answer claims the drones did, checked against what this turn's calls did.

Every turn ends with a true answer. A small model often answers with what it means to do instead of
doing it (measured on the corpus's dev half, cond-above-forty-hop: "Charlie is above 40 percent, sending
it up to 12 m and back down." twice, and no call ever ran). The host reads the answer sentence by
sentence: a sentence that names a drone (or the request's only drone) with words of an action ("sending
it up", "took off", "flew 30 m east", "landed") and no negation is a claim that the drone acted; a claim
with words of a state only ("is hovering at 12 m", "is on the ground") is checked against the roster. A
claim is backed when a call that acts succeeded on that drone in this turn, or, for a state, when the
roster says the same now.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from gateway.agent.roster import DroneEntry, Roster, drones_named
from gateway.agent.turns import TurnResult

# Words that say a drone did (or is doing) something.
_ACTION_WORDS = re.compile(
    r"\b(?:tak(?:e|es|ing)\s+(?:\w+\s+)?off|took\s+(?:\w+\s+)?off|launch(?:ed|es|ing)?|climb(?:ed|s|ing)?|"
    r"ascend(?:ed|s|ing)?|fl(?:y|ies|ew|own)|sen(?:d|ds|ding|t)|went|head(?:ed|ing)|"
    r"mov(?:e|ed|es|ing)|return(?:ed|s|ing)?|came back|coming back|brought|rais(?:ed|es|ing)|"
    r"lift(?:ed|s|ing)?|land(?:s|ing)|touched down|"
    r"(?:set|put|putting|bring|bringing) (?:\w+ )?(?:back )?(?:up|down))\b",
    re.IGNORECASE,
)
# Words that say what state a drone is in now.
_FLYING_WORDS = re.compile(
    r"\b(?:flying|hover(?:s|ing)?|airborne|in the air|aloft|holding at)\b", re.IGNORECASE
)
_GROUND_WORDS = re.compile(r"\b(?:landed|on the ground|grounded|parked)\b", re.IGNORECASE)
# a drone that did act said to be down again ("came straight back down"), checked against the roster
_DOWN_AGAIN_WORDS = re.compile(
    r"\b(?:landed|on the ground|grounded|touched down|(?:came|come|coming|went|back) (?:\w+ )?down)\b",
    re.IGNORECASE,
)
# Words that turn a sentence into a report of what was not done (a refusal among them), or a guess.
# Words that report a refusal: a sentence with one claims nothing, and an answer with one tells the user
# of a refusal (wording.says_refused)
REFUSAL_WORDS = (
    r"refus\w*|limit\w*|exceed\w*|not allowed|cannot|can't|can not|unable|too (?:far|high|low)|beyond|"
    r"denied|rejected|not possible|impossible|maximum|minimum|max_\w*"
)
_NEGATION = re.compile(
    r"\b(?:not|no|never|none|nothing|neither|instead|stay(?:s|ed|ing)?|leave|left|kept|keep(?:s|ing)?|"
    r"remain(?:s|ed|ing)?|would|could|should|if|may|might|perhaps|probably|possibly|"
    rf"{REFUSAL_WORDS})\b|n't\b",
    re.IGNORECASE,
)


# "alpha is hovering at 15 m": a height the roster can check, for a drone that did act too
_HEIGHT_CLAIM_RE = re.compile(
    r"\b(?:flying|hover(?:s|ing)?|airborne|in the air|aloft|holding)\s+(?:at\s+)?(?:about\s+|around\s+)?"
    r"(\d+(?:\.\d+)?)\s*(?:m|metres|meters)\b",
    re.IGNORECASE,
)
HEIGHT_TOLERANCE_M = 3.0


@dataclass(frozen=True)
class Claim:
    """A drone the answer says acted (or is in a state), with the words that say so and the drone now;
    ``acted``: a call did act on it this turn, but it is not where the answer says."""

    drone_id: str
    words: str
    now: DroneEntry | None
    acted: bool = False


def _sentences(text: str) -> list[str]:
    return [s.strip() for s in re.split(r"(?<=[.!?;])\s+|\n+", text) if s.strip()]


def _named(text: str, ids: Sequence[str]) -> list[str]:
    return [i for i in ids if re.search(rf"\b{re.escape(i)}\b", text, re.IGNORECASE)]


def unbacked(
    answer: str, request: str, result: TurnResult, roster: Roster | None, acts: Callable[[str], bool]
) -> list[Claim]:
    """The claims of ``answer`` that nothing this turn backs (empty when there is no roster to read ids
    from). ``acts(name)`` says whether a tool acts on drones (reads and waits back no claim)."""
    if roster is None:
        return []
    ids = roster.ids
    acted: set[str] = set()
    for call in result.tool_calls:
        if call.ok and acts(call.name):
            named = drones_named(call.arguments)
            acted.update(named if named is not None else ids)  # a fleet call without ids is every drone
    only = _named(request, ids)
    out: dict[str, Claim] = {}
    for sentence in _sentences(answer):
        if _NEGATION.search(sentence):
            continue
        drones = _named(sentence, ids) or (only if len(only) == 1 else [])
        action = _ACTION_WORDS.search(sentence)
        flying, ground = _FLYING_WORDS.search(sentence), _GROUND_WORDS.search(sentence)
        for drone in drones:
            if drone in out:
                continue
            now = next((d for d in roster.drones if d.drone_id == drone), None)
            if drone in acted:
                if len(drones) == 1 and (wrong := _height_unbacked(sentence, drone, now)) is not None:
                    out[drone] = wrong
                continue
            if action is not None:
                out[drone] = Claim(drone, action.group(0), now)
            elif flying is not None and now is not None and now.flying is False:
                out[drone] = Claim(drone, flying.group(0), now)
            elif ground is not None and now is not None and now.flying:
                out[drone] = Claim(drone, ground.group(0), now)
    return list(out.values())


def _height_unbacked(sentence: str, drone: str, now: DroneEntry | None) -> Claim | None:
    """A sentence about one drone that acted, saying it hovers at a height the roster does not show (more
    than HEIGHT_TOLERANCE_M off, or on the ground), or that it is down again while it flies. Measured on
    the dev half (multi-hop-and-hover): both drones flown to 6 m by one formation, the answer said "charlie
    has done a quick hop to 6 m and come straight back down, and alpha is hovering at 15 m"."""
    if now is None or now.flying is None:
        return None
    down = _DOWN_AGAIN_WORDS.search(sentence)
    if down is not None and now.flying:
        return Claim(drone, down.group(0), now, acted=True)
    m = _HEIGHT_CLAIM_RE.search(sentence)
    if m is None:
        return None
    said = float(m.group(1))
    if now.flying and (now.alt_m is None or abs(now.alt_m - said) <= HEIGHT_TOLERANCE_M):
        return None
    return Claim(drone, m.group(0), now, acted=True)
