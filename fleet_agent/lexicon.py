"""The one place the host reads words: units written after a number, whether the request speaks of a
drone's home, and the compass points of the model's own English restatement. Words of the languages
operators write in; a word matches a stem when it starts with it. A word of the request read here only
ever settles what the plan leaves open (a unit, an origin); the absence of a word changes nothing, so a
request in a language the lexicon does not know is flown as the model planned it. Everything else the
host reads without words (`fleet_agent.consistency`).
"""

from __future__ import annotations

import unicodedata
from itertools import pairwise, takewhile

from fleet_agent.units import Unit

#: a unit's words, each the whole word that follows a number ("50 ft", "0,05 km", "100 yards")
UNIT_WORDS: dict[Unit, frozenset[str]] = {
    Unit.m: frozenset("m metre metres meter meters mètre mètres metro metros metri mtr mts".split()),
    Unit.ft: frozenset("ft feet foot pied pieds pie pies piede piedi pé pés fuß fuss voet".split()),
    Unit.yd: frozenset("yd yds yard yards yarda yardas iarde jarda jardas".split()),
    Unit.km: frozenset(
        "km kms kilometre kilometres kilometer kilometers kilomètre kilomètres kilómetro kilómetros "
        "chilometro chilometri quilômetro quilômetros quilómetro quilómetros".split()
    ),
    Unit.mi: frozenset("mi mile miles milla millas meile meilen miglio miglia milha milhas mijl".split()),
    Unit.nmi: frozenset("nmi".split()),
    Unit.cm: frozenset(
        "cm centimetre centimetres centimeter centimeters centimètre centimètres centímetro centímetros "
        "centimetro centimetri zentimeter".split()
    ),
}

#: stems of a drone's home (its launch point), read only to measure a move the model wrote from its own
#: drone from that drone's home; a request with none of them is left as the model planned it
HOME_STEMS = (
    "home", "return", "rtl", "casa", "maison", "retour", "revien", "rentr", "départ", "depart", "origin",
    "heim", "zurück", "zuruck", "rück", "volv", "vuelv", "regres", "retorn", "ritorn", "rientr", "torn",
    "volta", "volte", "thuis", "terug",
)  # fmt: skip


#: what ends a clause of a text
CLAUSE_ENDS = (". ", ", ", ";", "!", "?", "\n", "。", "、", "，", "；", "！", "？")


def clauses(text: str) -> list[str]:
    for end in CLAUSE_ENDS:
        text = text.replace(end, "\0")
    return text.split("\0")


def stated_directions(text: str) -> list[tuple[float, str | None]]:
    """Each number of an English text (the model's restatement of a request, ``in_english``) with the
    compass direction named after it and before the next number of its clause ("30 yards to the
    north-east": northeast), or None ("flies to 20 m")."""
    found = []
    for clause in clauses(text):
        words = tokens(clause.lower())
        for k, word in enumerate(words):
            if (value := number(word)) is None:
                continue
            points = [p for p in map(_point, takewhile(lambda t: number(t) is None, words[k + 1 :])) if p]
            joined = len(points) > 1 and points[0] in ("north", "south") and points[1] in ("east", "west")
            found.append((value, points[0] + points[1] if joined else next(iter(points), None)))
    return found


def _point(word: str) -> str | None:
    """The compass point a word starts with ("northeast", "westwards"), else None."""
    for first in ("north", "south", "east", "west"):
        if word.startswith(first):
            rest = word[len(first) :] if first in ("north", "south") else ""
            return first + next((p for p in ("east", "west") if rest.startswith(p)), "")
    return None



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
    """``text`` has a word starting with one of ``stems`` (a stem of three letters or less: that word)."""
    return any(w == s or (len(s) > 3 and w.startswith(s)) for w in tokens(text.lower()) for s in stems)


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
