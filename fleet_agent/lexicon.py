"""The one place the host reads words (``words.toml``): units after a number, a drone's home, staying up or
coming down, compass points. A word read here only settles what the plan says otherwise (a unit, an
origin, an ending, a leg's way); with no word it knows, a request is flown as the model planned it."""

from __future__ import annotations

import tomllib
import unicodedata
from itertools import dropwhile, pairwise, takewhile
from pathlib import Path

from fleet_agent.plan import OPPOSITE
from fleet_agent.units import Unit

_WORDS = tomllib.loads((Path(__file__).parent / "words.toml").read_text(encoding="utf-8"))
#: a unit's words, each the whole word that follows a number ("50 ft", "0,05 km", "100 yards")
UNIT_WORDS = {Unit(unit): frozenset(words.split()) for unit, words in _WORDS["units"].items()}
#: stems of a drone's home, read only to measure a move the model wrote from its own drone from its home
HOME_STEMS = tuple(_WORDS["home"]["stems"].split())
#: each compass word's stem and its point, longest first ("northeast" before "north", "юго" before "юг")
_STEMS = [(s.replace("_", " "), p) for p, stems in _WORDS["points"].items() for s in stems.split()]
_STEMS.sort(key=lambda stem_point: -len(stem_point[0]))
#: compass words that are common words too: each counts only after one of its words ("à l'est", "al sur")
SHARED_POINTS = {word: (s["point"], s["after"].split()) for word, s in _WORDS["shared_points"].items()}
#: stems of staying in the air, and of coming down (a landing, the ground, coming back)
STAY_STEMS, DOWN_STEMS = (tuple(_WORDS["endings"][kind].split()) for kind in ("stay", "down"))

#: from here on (Hebrew, Arabic, Devanagari, Thai, CJK, Hangul...), a stem is found inside a word too: these
#: scripts join letters or write no spaces
_JOINED_SCRIPTS = 0x590
#: what ends a clause of a text (an aside in brackets is a clause of its own: "y = -15 m (x points east)")
CLAUSE_ENDS = (". ", ", ", ";", "!", "?", "\n", "。", "、", "，", "；", "！", "？", "(", ")", "（", "）")


def clauses(text: str) -> list[str]:
    for end in CLAUSE_ENDS:
        text = text.replace(end, "\0")
    return text.split("\0")


def stated_ways(text: str) -> list[tuple[float, str | None]]:
    """Each number of a text with the compass point named after it and before the next number of its
    clause ("30 yards to the north-east": northeast; "25 मीटर पूर्व": east), or, in a clause of one number and
    one point, before it ("北へ20メートル"); None when the clause names none ("flies to 20 m")."""
    found: list[tuple[float, str | None]] = []
    for clause in clauses(text.lower()):
        numbers, points = _numbers_at(clause), _points_at(clause)
        for k, (start, end, value) in enumerate(numbers):
            stop = numbers[k + 1][0] if k + 1 < len(numbers) else len(clause)
            after = [p for at, _, p in points if end <= at < stop]
            before = [p for at, _, p in points if at < start] if len(numbers) == len(points) == 1 else []
            way = next(iter(after + before), None)
            found.append((-value, OPPOSITE[way]) if value < 0 and way else (value, way))
    return found


def numbers(text: str) -> list[float]:
    """The numbers a text writes in digits, signed ("-20 m": -20), in order."""
    return [value for _, _, value in _numbers_at(text)]


def compass_points(text: str) -> list[str]:
    """The compass points a text names, in order (not up or down)."""
    return [point for _, _, point in _points_at(text.lower()) if point not in ("up", "down")]


def _points_at(text: str) -> list[tuple[int, int, str]]:
    """Where each compass point's word starts and ends in a lower-case text, and its point; two named
    together are one diagonal ("nord-ouest", "西北", "tây bắc", "Nordwesten": northwest)."""
    found: list[tuple[int, int, str]] = []
    at = 0
    while at < len(text):
        end, point = _point_word(text, at, found[-1][1] if found else -1)
        if point and found and end > at and _joins(found[-1][2], point, text[found[-1][1] : at]):
            found[-1] = (found[-1][0], end, _diagonal(found[-1][2], point))
        elif point:
            found.append((at, end, point))
        at = max(end, at + 1)
    return found


def _numbers_at(text: str) -> list[tuple[int, int, float]]:
    """Where each number written in digits starts and ends in a text (not one ending a Latin word, "alpha2"),
    and its value (a decimal comma read as a point)."""
    found: list[tuple[int, int, float]] = []
    at = 0
    while at < len(text):
        end = at
        while end < len(text) and (text[end].isdigit() or (end > at and _inside_number(text, end))):
            end += 1
        value = number(text[at:end]) if end > at and not _latin_letter(text[at - 1 : at]) else None
        if value is not None:
            signed = at > 0 and text[at - 1] in "-−" and not text[at - 2 : at - 1].isalnum()
            found.append((at, end, -value if signed else value))
        at = max(end, at + 1)
    return found


def _latin_letter(char: str) -> bool:
    return char.isascii() and char.isalpha()


def _inside_number(text: str, at: int) -> bool:
    return text[at] in ".," and text[at + 1 : at + 2].isdigit()


def _point_word(text: str, at: int, last_end: int) -> tuple[int, str | None]:
    """Where the compass word starting at ``at`` ends, and its point (None: there is none)."""
    starts = at == 0 or not text[at - 1].isalpha() or at == last_end
    for stem, point in _STEMS:
        if text.startswith(stem, at) and (starts or ord(stem[0]) >= _JOINED_SCRIPTS):
            return at + len(stem), point
    word = "".join(takewhile(str.isalpha, text[at:]))
    if starts and word in SHARED_POINTS:
        point, before = SHARED_POINTS[word]
        previous = "".join(takewhile(str.isalpha, text[:at].rstrip(" '’-")[::-1]))[::-1]
        if previous in before or at == last_end:
            return at + len(word), point
    return at, None


def _joins(first: str, second: str, between: str) -> bool:
    """Two points named together (nothing but the first word's ending, a hyphen, a space or an Arabic
    article between them: "północny wschód"), one of north and south, the other of east and west."""
    axes = [p in ("north", "south") for p in (first, second) if p in ("north", "south", "east", "west")]
    return sorted(axes) == [False, True] and not "".join(dropwhile(str.isalpha, between)).strip(" -ال")


def _diagonal(first: str, second: str) -> str:
    return first + second if first in ("north", "south") else second + first


def by_script(text: str) -> str:
    """``text`` with a space where the script of its letters changes (LATIN, HANGUL, CJK, HIRAGANA...): a
    Latin id ends before a Korean or Japanese particle written onto it ("alpha를", "bravoを")."""
    out, last = [], ""
    for c in text:
        name = "" if not c.isalpha() else "LATIN" if c.isascii() else unicodedata.name(c, "?").split()[0]
        script = name.split("-")[0]  # KATAKANA-HIRAGANA (the long vowel mark) goes with either kana
        out.append(" " + c if script and last and script != last else c)
        last = script
    return "".join(out)


def says(text: str, stems: tuple[str, ...]) -> bool:
    """``text`` has a word starting with one of ``stems`` (a stem of three letters or less: that word; a stem
    of a script that joins its letters or writes no spaces: anywhere)."""
    text = text.lower()
    if any(s in text for s in stems if ord(s[0]) >= _JOINED_SCRIPTS):
        return True
    return any(w == s or (len(s) > 3 and w.startswith(s)) for w in tokens(text) for s in stems)


def number_units(text: str) -> dict[float | None, set[Unit]]:
    """Each number of ``text`` written with a unit right after it, and the units it was written with;
    under None, the units written with no number before them ("a tenth of a mile")."""
    found: dict[float | None, set[Unit]] = {}
    for token, word in pairwise(["", *tokens(text.lower())]):
        unit = next((u for u, names in UNIT_WORDS.items() if word in names), None)
        if unit is not None:
            found.setdefault(number(token) if token else None, set()).add(unit)
    return found


def tokens(text: str) -> list[str]:
    """Runs of digits (with a decimal point or comma inside) and runs of letters of one script, in order."""
    out: list[str] = []
    kind = ""
    for c in by_script(text):
        k = "d" if c.isdigit() or (kind == "d" and c in ".,") else "a" if c.isalpha() else ""
        if k and k == kind:
            out[-1] += c
        elif k:
            out.append(c)
        kind = k
    return [t.rstrip(".,") for t in out]


def number(token: str) -> float | None:
    """The number a token of digits writes (a decimal comma read as a point), else None."""
    if not token[:1].isdigit():
        return None
    try:
        return float(token.replace(",", "."))
    except ValueError:
        return None
