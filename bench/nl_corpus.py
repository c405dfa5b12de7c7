"""The generalisation corpus of the agent benchmark: 843 requests as people phrase them, with a fixed split.

Each entry is a request in everyday words (not in the words of the tool names), the class it belongs to,
the half it is in, and a check of the outcome against the simulator's truth: where the drones ended (and
the track they flew), what the gateway refused, what the answer said. ``plan`` is the ideal call sequence,
used only by the harness self-check (a scripted endpoint replays it), never as a model result.

THE SPLIT IS FIXED HERE and stratified by class (of the first 40, each class has 5 requests: 3 in one
half, 2 in the other, alternating between classes so that each half holds 20; the 24 added later are dev). The ``dev`` half may be looked at when
the host, its prompts or the tool texts change; the ``test`` half never: it measures how the host does on
requests nobody tuned it for. Do not move entries between halves (except from test to dev once a test
entry has been seen, as below), and do not reword a test entry after seeing a model's result on it (add a
new entry instead and say so in docs/benchmarks.md).

The first 40 entries were written in full before any model ran on them (2026-11-27). Sixteen more, two
per class and all in the ``dev`` half (marked "added later"), were written later the same day, again
before any model ran on them, after the dev half had been tuned on until 17 of its 20 passed: a tuning
set the host passes tells nothing more. The test half is unchanged. Eight more (marked "added on the second day"), again dev only and written before any model ran on them (2026-11-28), where the test half measured weakest: compound, multi, conditional, question. Eight more (marked "added on the third day"), dev only, written before any model ran on them (2026-11-28), in the kinds of request the test half still failed: a choice between drones by their batteries (the dev half had none), a flight out and back, a move with a height from the ground, one drone told to stay while others fly. Eight more (marked "added on the fourth day"), dev only, written before any model ran on them (2026-11-28): a question that picks a drone, out and back, one drone hopping while another flies, a height change after a leg. Eight more (marked "added on the fifth day"), dev only, written before any model ran on them (2026-11-28, a new session): two drones with different orders, out and back by the same distance, a climb during a leg, a hop, a line placed off to one side.

Twenty-four more (2026-11-29, with the typed plan host), in four new classes of six, 3 dev and 3 test each,
written before any model ran on them: distances and heights in other units (feet, yards, kilometres), a
shape one drone flies (square, triangle, hexagon, circle, survey lines), a drone placed relative to another
drone or its home, and requests in French, Spanish and German.

On 2026-11-29 every test entry of ``conditional`` (3), ``formation`` (2) and ``placement`` (3) was moved to
dev because they were seen while tuning (the host's tuning saw the text of some of them; the whole of
those classes' test entries went, not only the ones seen), each marked where it stands. In their place,
eleven new test entries (4 conditional, 3 formation, 4 placement: one more per class than moved), written
before any model ran on them, in new wordings and shapes within each class, some of them in a language
other than English. That left 88 dev and 35 test.

Later on 2026-11-29 (second round) EVERY test entry (35) was moved to dev, each marked "moved to dev on
2026-11-29, second round": the test half's figures had informed a decision about the host, so it no
longer measured requests nobody tuned for. A fresh test half took its place (``_second_test_half``): 36
new requests, 3 a class, written before any model ran on them, in new wordings and shapes within each
class (not rewordings of dev entries): 11 of the 33 outside the ``language`` class are in Dutch, French,
German, Italian or Spanish, and the ``language`` class's 3 in Italian, French and Portuguese. Only the
harness self-check (the scripted ideal plan) has run on them. That leaves 123 dev and 36 test.

On 2026-11-30 EVERY test entry (36, ``_second_round``) was moved to dev, each marked "moved to dev on
2026-11-30": the test half had been measured, and its figures were known to whoever works on the host, so
it no longer measured requests nobody tuned for. A fresh test half took its place (``_third_test_half``,
now ``_third_round``): 36 new requests, 3 a class, written before any model ran on them, in new wordings
and shapes within each class (not rewordings of dev entries): 13 of the 33 outside the ``language`` class
are in Dutch, French, German, Italian, Portuguese or Spanish, spread over 11 classes, and the
``language`` class's 3 in German, Spanish and Dutch. Only the harness self-check (the scripted ideal plan) has run on them. That leaves
159 dev and 36 test.

Later on 2026-11-30 (third round) EVERY test entry (36, ``_third_round``) was moved to dev, each marked
"moved to dev on 2026-11-30, third round": the test half had been measured and its figures were known to
whoever works on the host, so it no longer measured requests nobody tuned for. A fresh test half took its
place (``_fourth_test_half``, now ``_fourth_round``): 36 new requests, 3 a class, written before any model ran on them, in new
wordings and shapes within each class (not rewordings of dev entries): 18 of the 33 outside the
``language`` class are in Dutch, French, German, Italian, Polish, Portuguese or Spanish, spread over 11
classes, and the ``language`` class's 3 in Polish, Portuguese and Dutch. Only the harness self-check (the
scripted ideal plan) has run on them. That leaves 195 dev and 36 test.

Later on 2026-11-30 (fourth round) EVERY test entry (36, ``_fourth_round``) was moved to dev, each marked
"moved to dev on 2026-11-30, fourth round": the test half had been measured and its figures were known to
whoever works on the host, so it no longer measured requests nobody tuned for. A fresh test half took its
place (``_fifth_test_half``, now ``_fifth_round``): 36 new requests, 3 a class, written before any model ran on them, in new
wordings and shapes within each class (not rewordings of dev entries): 23 of the 33 outside the
``language`` class are in Czech, Dutch, French, German, Italian, Polish, Portuguese, Spanish or Swedish,
spread over the 11 classes, and the ``language`` class's 3 in Swedish, Czech and Italian. Only the
harness self-check (the scripted ideal plan) has run on them. That leaves 231 dev and 36 test.

Later on 2026-11-30 (fifth round) EVERY test entry (36, ``_fifth_round``) was moved to dev, each marked
"moved to dev on 2026-11-30, fifth round": the test half had been measured and its figures were known to
whoever works on the host, so it no longer measured requests nobody tuned for. A fresh test half took its
place (``_sixth_test_half``, now ``_sixth_round``): 36 new requests, 3 a class, written before any model ran on them, in new
wordings and shapes within each class (not rewordings of dev entries): 28 of the 33 outside the
``language`` class are in Czech, Danish, Dutch, Finnish, French, German, Italian, Norwegian, Polish,
Portuguese, Romanian, Spanish, Swedish or Turkish, spread over the 11 classes, and the ``language`` class's
3 in Finnish, Turkish and Danish. Only the harness self-check (the scripted ideal plan) has run on them.
That leaves 267 dev and 36 test.

On 2026-12-01 (sixth round) EVERY test entry (36, ``_sixth_round``) was moved to dev, each marked "moved
to dev on 2026-12-01, sixth round": the test half had been measured and its figures were known to whoever
works on the host, so it no longer measured requests nobody tuned for. A fresh test half took its place
(``_seventh_test_half``, now ``_seventh_round``): 36 new requests, 3 a class, written before any model ran on them, in new
wordings and shapes within each class (not rewordings of dev entries): 29 of the 33 outside the
``language`` class are in Catalan, Croatian, Czech, Danish, Dutch, Finnish, French, German, Greek,
Hungarian, Italian, Norwegian, Polish, Portuguese, Romanian, Slovak, Spanish, Swedish or Turkish, spread
over the 11 classes, and the ``language`` class's 3 in Hungarian, Croatian and Slovak. Only the harness
self-check (the scripted ideal plan) has run on them. That leaves 303 dev and 36 test.

Later on 2026-12-01 (seventh round) EVERY test entry (36, ``_seventh_round``) was moved to dev, each marked
"moved to dev on 2026-12-01, seventh round": the test half had been measured (3 runs of the 1.5B model)
and its figures were known to whoever works on the host, so it no longer measured requests nobody tuned
for. A fresh test half took its place (``_eighth_test_half``, now ``_eighth_round``): 36 new requests, 3 a class, written before
any model ran on them, in new wordings and shapes within each class (not rewordings of dev entries): 22 of
the 33 outside the ``language`` class are in Bulgarian, Estonian, Indonesian, Latvian, Lithuanian, Russian,
Slovenian, Spanish, Ukrainian or Vietnamese (Cyrillic and Vietnamese script among them), spread over the
11 classes, and the ``language`` class's 3 in Russian, Vietnamese and Estonian. Only the harness
self-check (the scripted ideal plan) has run on them: 36 of 36 passed. That leaves 339 dev and 36 test.
On 2026-12-02 (eighth round) EVERY test entry (36, ``_eighth_round``) was moved to dev, each marked
"moved to dev on 2026-12-02, eighth round": the test half had been measured (3 runs of the 1.5B model)
and its figures were known to whoever works on the host, so it no longer measured requests nobody tuned
for. A fresh test half took its place (``_ninth_test_half``): 36 new requests, 3 a class, written before
any model ran on them, in new wordings and shapes within each class (not rewordings of dev entries): 22 of
the 33 outside the ``language`` class are in Chinese, Czech, Dutch, French, German, Italian, Japanese,
Korean, Polish, Portuguese, Romanian or Turkish (Chinese, Japanese and Korean script are new), spread over
the 11 classes, and the ``language`` class's 3 in Japanese, Chinese and Korean. Only the harness
self-check (the scripted ideal plan) has run on them: 36 of 36 passed (once a Latin id written onto a
Korean particle was read as named). That leaves 375 dev and 36 test.
Later on 2026-12-02 (ninth round) EVERY test entry (36, ``_ninth_round``) was moved to dev, each marked
"moved to dev on 2026-12-02, ninth round": the test half had been measured (3 runs of the 1.5B model)
and its figures were known to whoever works on the host, so it no longer measured requests nobody tuned
for. A fresh test half took its place (``_tenth_test_half``): 36 new requests, 3 a class, written before
any model ran on them (while the ninth half was measured, before its failures were read), in new wordings and shapes within each class (not rewordings
of dev entries): 22 of the 33 outside the ``language`` class are in Arabic, Catalan, Danish, Finnish,
Greek, Hindi, Hungarian, Indonesian, Norwegian, Russian, Spanish, Swedish, Ukrainian or Vietnamese
(Arabic, Devanagari and Thai script are new), spread over the 11 classes, and the ``language`` class's 3
in Arabic, Hindi and Thai. Only the harness self-check (the scripted ideal plan) has run on them. That
leaves 411 dev and 36 test.
Later on 2026-12-02 (tenth round) EVERY test entry (36, ``_tenth_round``) was moved to dev, each marked
"moved to dev on 2026-12-02, tenth round": the test half had been measured and its figures were known to
whoever works on the host, so it no longer measured requests nobody tuned for. A fresh test half took its
place (``_eleventh_test_half``): 36 new requests, 3 a class, written before any model ran on it, in new
wordings and shapes within each class (not rewordings of dev entries): 22 of the 33 outside the
``language`` class are in Bulgarian, Chinese, Croatian, Czech, Dutch, Estonian, French, Italian, Japanese,
Korean, Latvian, Lithuanian, Malay, Polish, Romanian, Slovak, Slovenian, Swahili, Tagalog or Turkish
(Malay, Swahili and Tagalog are new), spread over the 11 classes, and the ``language`` class's 3 in Hebrew,
Persian and Bengali (Hebrew and Bengali script are new). Only the harness self-check (the scripted ideal
plan) has run on them: 36 of 36 passed. That leaves 447 dev and 36 test.
Later on 2026-12-02 (eleventh round) EVERY test entry (36, ``_eleventh_round``) was moved to dev, each
marked "moved to dev on 2026-12-02, eleventh round", once both models had been measured on it. A fresh
test half took its place (``_twelfth_test_half``): 36 new requests, 3 a class, written before any model
ran on it: 22 of the 33 outside the ``language`` class in 22 languages, one each (Arabic, Chinese, Dutch,
Finnish, French, German, Greek, Hindi, Hungarian, Indonesian, Italian, Japanese, Korean, Polish,
Portuguese, Russian, Spanish, Swedish, Thai, Turkish, Ukrainian, Vietnamese), and the ``language``
class's 3 in Urdu, Tamil and Serbian written in Cyrillic (all three new, and Tamil script). Only the
harness self-check (the scripted ideal plan) has run on them: 36 of 36 passed. That leaves 483 dev and
36 test.
Later on 2026-12-02 (twelfth round) EVERY test entry (36, ``_twelfth_round``) was moved to dev, each
marked "moved to dev on 2026-12-02, twelfth round", once both models had been measured on it. A fresh
test half took its place (``_thirteenth_test_half``): 36 new requests, 3 a class, written before any model
ran on it by a writer who did not read the host's word lists or rules: 22 of the 33 outside the
``language`` class in 22 languages, one each (Afrikaans, Arabic, Azerbaijani, Chinese, Dutch, French,
Galician, German, Hindi, Icelandic, Indonesian, Italian, Japanese, Kazakh, Korean, Polish, Portuguese,
Russian, Spanish, Turkish, Ukrainian, Vietnamese; Afrikaans, Azerbaijani, Galician, Icelandic and Kazakh
are new), and the ``language`` class's 3 in Marathi, Georgian and Armenian (all three new, and Georgian
and Armenian script). Only the harness self-check (the scripted ideal plan) has run on them: 36 of 36
passed. That leaves 519 dev and 36 test.
On 2026-12-03 (thirteenth round) EVERY test entry (36, ``_thirteenth_round``) was moved to dev, each marked
"moved to dev on 2026-12-03, thirteenth round", once both models had been measured on it. A fresh test
half took its place (``_fourteenth_test_half``): 36 new requests, 3 a class, written before any model ran
on it by a writer who did not read the host's word lists or rules: 22 of the 33 outside the ``language``
class in 22 languages, one each (Albanian, Basque, Catalan, Chinese, Croatian, Czech, Esperanto, Finnish,
French, German, Greek, Hebrew, Japanese, Korean, Malay, Persian, Romanian, Spanish, Swedish, Turkish,
Uzbek, Welsh; Albanian, Basque, Esperanto, Uzbek and Welsh are new), and the ``language`` class's 3 in
Nepali, Macedonian and Gujarati (all three new, and Gujarati script). Only the harness self-check (the
scripted ideal plan) has run on them: 36 of 36 passed. That leaves 555 dev and 36 test.
Later on 2026-12-03 (fourteenth round) EVERY test entry (36, ``_fourteenth_round``) was moved to dev, each
marked "moved to dev on 2026-12-03, fourteenth round", once both models had been measured on it. A fresh
test half took its place (``_fifteenth_test_half``): 36 new requests, 3 a class, written before any model
ran on it by a writer who did not read the host's word lists or rules: 22 of the 33 outside the
``language`` class in 22 languages, one each (Arabic, Bengali, Bulgarian, Danish, Dutch, Estonian, Hindi,
Hungarian, Icelandic, Indonesian, Irish, Italian, Latvian, Lithuanian, Norwegian, Polish, Portuguese,
Serbian, Slovenian, Tagalog, Thai, Vietnamese; Irish is new, and Serbian in Latin script), and the
``language`` class's 3 in Ukrainian, Swahili and Punjabi (all three new to the class, and Gurmukhi
script). Only the harness self-check (the scripted ideal plan) has run on them: 36 of 36 passed (once
the Serbian row's check no longer wanted its peak height: the climb from 12 to 22 m overshot to 26 m).
That leaves 591 dev and 36 test.
Later on 2026-12-03 (fifteenth round) EVERY test entry (36, ``_fifteenth_round``) was moved to dev, each
marked "moved to dev on 2026-12-03, fifteenth round", once both models had been measured on it. A fresh
test half took its place (``_sixteenth_test_half``): 36 new requests, 3 a class, written before any model
ran on it by a writer who did not read the host's word lists or rules: 22 of the 33 outside the
``language`` class in 22 languages, one each (Afrikaans, Arabic, Bosnian, Catalan, Chinese, French,
German, Haitian Creole, Hebrew, Hindi, Japanese, Korean, Luxembourgish, Malay, Persian, Portuguese,
Romanian, Russian, Spanish, Swedish, Turkish, Urdu; Bosnian, Haitian Creole and Luxembourgish are new, and
Urdu is new outside the ``language`` class), and the ``language`` class's 3 in Greek, Belarusian and
Malayalam (all three new to the class, Belarusian and Malayalam new to the corpus, and Malayalam script).
Only the harness self-check (the scripted ideal plan) has run on them: 36 of 36 passed, once three ideal
plans named the points they fly to (the host's reading of the request had made a climb of the Japanese
leg west "as far as the height", and a leg east of "15 m east (sorry, west, not east)"; the typed plan has
no heading for the diagonal row, so each drone flies to its slot), and once an Arabic question the typed
plan has no reading for (on which side of alpha charlie stands) gave way to another (whose charge is
nearer bravo's). That leaves 627 dev and 36 test.
Later on 2026-12-03 (sixteenth round) EVERY test entry (36, ``_sixteenth_round``) was moved to dev, each
marked "moved to dev on 2026-12-03, sixteenth round", once both models had been measured on it. A fresh
test half took its place (``_seventeenth_test_half``, now ``_seventeenth_round``): 36 new requests, 3 a class, written before any model
ran on it by a writer who did not read the host's word lists or rules: 22 of the 33 outside the
``language`` class in 22 languages, one each (Bulgarian, Croatian, Czech, Danish, Dutch, Estonian,
Finnish, Greek, Hungarian, Icelandic, Indonesian, Italian, Maltese, Norwegian, Polish, Slovak, Swahili,
Tagalog, Tamil, Thai, Ukrainian, Vietnamese; Maltese is new, and Tamil is new outside the ``language``
class), and the ``language`` class's 3 in Telugu, Kannada and Mongolian (all three new to the corpus, and
Telugu and Kannada script). Only the harness self-check (the scripted ideal plan) has run on them: 36 of
36 passed, once the plan of the two laps round alpha's pad flew four legs a lap (naming a point every 45
degrees made it too long to pass as a plan), and once a Tamil request the host would not let the typed
plan fly (charlie landing on the pad alpha left: the host dropped charlie's leg there, whether to a named
point or of a length the request does not give) gave way to another (charlie staying put while alpha
moves on); an Italian wording was corrected for the language's own sake (a shed of four floors became a
building). That leaves 663 dev and 36 test.
Later on 2026-12-04 (seventeenth round) EVERY test entry (36, ``_seventeenth_round``) was moved to dev, each
marked "moved to dev on 2026-12-04, seventeenth round": the 1.5B model had run 89 of its 108 runs on it
(figures lost with the session that ran them) and its failures had informed changes to the host, so it no
longer measured requests nobody tuned for. A fresh test half took its place (``_eighteenth_test_half``,
now ``_eighteenth_round``): 36 new requests, 3 a class, written before any model ran on it by a writer who
did not read the host's word lists or rules: 22 of the 33 outside the ``language`` class in 22 languages,
one each (Arabic, Chinese, Czech, Dutch, French, German, Hebrew, Hindi, Indonesian, Italian, Japanese,
Korean, Persian, Polish, Portuguese, Romanian, Russian, Spanish, Swedish, Turkish, Ukrainian, Vietnamese),
and the ``language`` class's 3 in Amharic, Sinhala and Tajik (all three new to the corpus, and Ethiopic
and Sinhala script). Only the harness self-check (the scripted ideal plan) has run on them: 36 of 36
passed, once the leapfrog's check no longer wanted alpha's end point in its track (the track can stop
before the drone gets there; the end point is judged on the final state), and once the Polish descent into
a pit below the pad was planned as 15 m down (as an altitude of -5 m, the harness's scripted pilot dropped
the sign, a plan no model could write past the schema's non-negative lengths; the pilot now keeps it) and
its check took the gateway's "below home" refusal as well as one by the 2 m minimum. That leaves 699 dev
and 36 test.
Later on 2026-12-04 (eighteenth round) EVERY test entry (36, ``_eighteenth_round``) was moved to dev, each
marked "moved to dev on 2026-12-04, eighteenth round", once both models had been measured on it (figures
in docs/benchmarks.md). A fresh test half took its place (``_nineteenth_test_half``, now
``_nineteenth_round``): 36 new requests, 3 a class, written before any model ran on it by a writer who did
not read the host's word lists or rules: 22 of the 33 outside the ``language`` class in 22 languages, one
each (Afrikaans, Bengali, Bulgarian, Catalan, Cebuano, Danish, Estonian, Finnish, Greek, Hungarian,
Javanese, Kyrgyz, Lithuanian, Malay, Norwegian, Serbian, Slovak, Slovenian, Swahili, Tagalog, Thai, Urdu;
Cebuano, Javanese and Kyrgyz are new), and the ``language`` class's 3 in Khmer, Lao and Zulu (all three
new to the corpus, and Khmer and Lao script). Only the harness self-check (the scripted ideal plan) has
run on them: 36 of 36 passed at the first run (2026-12-04), the gateway refusing the 3 m row by its 5 m
separation. That leaves 735 dev and 36 test.
Later on 2026-12-05 (nineteenth round) EVERY test entry (36, ``_nineteenth_round``) was moved to dev, each
marked "moved to dev on 2026-12-05, nineteenth round", once both models had been measured on it (figures
in docs/benchmarks.md). A fresh test half took its place (``_twentieth_test_half``, now
``_twentieth_round``): 36 new requests, 3 a class, written before any model ran on it by a writer who did
not read the host's word lists or rules: 22 of the 33 outside the ``language`` class in 22 languages, one
each (Afrikaans, Bengali, Bulgarian, Catalan, Cebuano, Danish, Estonian, Finnish, Greek, Hungarian,
Javanese, Kyrgyz, Lithuanian, Malay, Norwegian, Serbian in Latin script, Slovak, Slovenian, Swahili,
Tagalog, Thai, Urdu: the nineteenth half's 22, none of them new), and the ``language`` class's 3 in
Burmese, Yoruba and Somali (all three new to the corpus, and Myanmar script). Only the harness self-check
(the scripted ideal plan) has run on them: 36 of 36 passed. That leaves 771 dev and 36 test.
Later on 2026-12-05 (twentieth round) EVERY test entry (36, ``_twentieth_round``) was moved to dev, each
marked "moved to dev on 2026-12-05, twentieth round", once both models had been measured on it (figures in
docs/benchmarks.md). A fresh test half took its place (``_twenty_first_test_half``): 36 new requests, 3 a
class, written before any model ran on it by a writer who did not read the host's word lists, rules or
prompts: 22 of the 33 outside the ``language`` class in 22 languages, one each (Arabic, Chinese, Czech,
Dutch, French, German, Hebrew, Hindi, Indonesian, Italian, Japanese, Korean, Persian, Polish, Portuguese,
Romanian, Russian, Spanish, Swedish, Turkish, Ukrainian, Vietnamese: none of them new), and the
``language`` class's 3 in Hausa, Kurdish (Kurmanji) and Odia (all three new to the corpus, and Odia script).
Only the harness self-check (the scripted ideal plan) has run on them: 34 of 36 passed at the first run
(2026-12-06), two ideal plans being wrong, not the requests or their checks (a return to launch after a
landing away from the pad lands where the drone last armed; two legs fly a corner where the request asks
for one straight line); with those plans flying to the point, 36 of 36. That leaves 807 dev and 36 test.

  python bench/nl_missions.py --half test --serve-local 1.5b --runs 3   # the test half, per class
"""

# ruff: noqa: E501  (the entries are laid out one request a block, as a table)

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass
from typing import Any

from bench.agent_harness.missions import (
    ALT_TOL_M,
    HORIZONTAL_TOL_M,
    Check,
    DroneTruth,
    Evidence,
    Mission,
    MissionContext,
    PlannedCall,
    _all,
    airborne_at,
    answer_mentions_number,
    answer_reports_refusal,
    at,
    landed_disarmed,
    max_alt_at_most,
    never_armed,
    reached_alt,
    refusal_seen,
    stayed_within,
    visited,
)
from gateway.fleet.geo import bearing_deg, horizontal_distance_m, ned_offset, offset_position

CLASSES = (
    "single",  # one drone, one simple thing
    "multi",  # several drones in one request
    "compound",  # one drone, several steps in order
    "conditional",  # what to do depends on a reading (battery)
    "formation",  # drones placed together, relative to where they are
    "relative",  # metres north/east/up from where the drone is, in varied phrasings
    "question",  # questions only: nothing may fly
    "refusal",  # requests beyond the gateway's limits: refused, and the user told
    "units",  # distances and heights in feet, yards, kilometres
    "pattern",  # a shape flown by one drone: polygon, circle, survey lines
    "placement",  # a drone placed relative to another drone or to its home
    "language",  # requests in languages other than English (Japanese, Chinese, Korean, French, Spanish, German, Italian, Portuguese, Dutch, Polish, Czech, Swedish, Danish, Norwegian, Finnish, Romanian, Turkish, Hungarian, Croatian, Slovak, Greek, Catalan, Russian, Ukrainian, Bulgarian, Slovenian, Latvian, Lithuanian, Estonian, Indonesian, Vietnamese, Arabic, Hindi, Thai, Hebrew, Persian, Bengali, Burmese, Yoruba, Somali, Hausa, Kurdish, Odia)
)
HALVES = ("dev", "test")
DRONES = ("alpha", "bravo", "charlie")


@dataclass(frozen=True)
class CorpusEntry:
    mission: Mission
    cls: str
    half: str

    @property
    def id(self) -> str:
        return self.mission.id


# --- checks the corpus adds to bench/agent_harness/missions.py ---------------------------------------


def answer_says(ev: Evidence, pattern: str, what: str) -> Check:
    """The final answer matches ``pattern`` (a case-insensitive regular expression)."""
    ok = bool(re.search(pattern, ev.final_text or "", re.IGNORECASE))
    return Check(ok, f"answer {'says' if ok else 'does not say'} {what}")


def _any(*checks: Check) -> Check:
    """One of ``checks`` passes (a question answered either way a reader would accept)."""
    return Check(any(c.ok for c in checks), " or ".join(c.detail for c in checks))


def nobody_armed(ev: Evidence, drones: tuple[str, ...] = DRONES) -> Check:
    return _all(*(never_armed(ev, d) for d in drones))


def _centroid(points: list[DroneTruth]) -> tuple[float, float]:
    return sum(p.lat for p in points) / len(points), sum(p.lon for p in points) / len(points)


def formation_at(
    c: MissionContext,
    ev: Evidence,
    drones: tuple[str, ...],
    alt: float,
    spacing: float,
    north: float,
    east: float,
) -> Check:
    """Every drone airborne at ``alt``; the nearest neighbours ``spacing`` apart (±3 m); the drones' centre
    ``north``/``east`` metres from the centre of their homes (the formation's slots are centred on it)."""
    home_lat = sum(c.homes[d][0] for d in drones) / len(drones)
    home_lon = sum(c.homes[d][1] for d in drones) / len(drones)
    return formation_around(ev, drones, alt, spacing, offset_position(home_lat, home_lon, north, east))


def formation_around(
    ev: Evidence, drones: tuple[str, ...], alt: float, spacing: float, centre: tuple[float, float]
) -> Check:
    """Every drone airborne at ``alt``; the nearest neighbours ``spacing`` apart (±3 m); the drones' centre
    at ``centre`` (lat, lon): a formation placed on a point another drone or a place gives."""
    final = [ev.final[d] for d in drones]
    off = horizontal_distance_m(*_centroid(final), *centre)
    nearest = min(
        horizontal_distance_m(a.lat, a.lon, b.lat, b.lon) for i, a in enumerate(final) for b in final[i + 1 :]
    )
    return _all(
        *(airborne_at(ev, d, alt) for d in drones),
        Check(abs(nearest - spacing) <= 3.0, f"nearest neighbours {nearest:.1f} m apart (want {spacing:g})"),
        Check(off <= HORIZONTAL_TOL_M, f"formation centre {off:.1f} m from where it was asked"),
    )


def rose_to(ev: Evidence, drone: str, alt: float) -> Check:
    """The drone was at ``alt`` or higher (less the tolerance) at some time: a height flown before a later
    step took it lower."""
    top = max((s.alt_rel_m for s in ev.track.get(drone, [])), default=0.0)
    return Check(top >= alt - ALT_TOL_M, f"{drone} rose to {top:.1f} m (want at least {alt:g})")


def farthest_apart(ev: Evidence, drones: tuple[str, ...], want: float) -> Check:
    """The two drones farthest from each other are ``want`` metres apart (±3 m): what tells three drones in
    a ring or a V from three in a row with the same spacing."""
    final = [ev.final[d] for d in drones]
    far = max(
        horizontal_distance_m(a.lat, a.lon, b.lat, b.lon) for i, a in enumerate(final) for b in final[i + 1 :]
    )
    return Check(abs(far - want) <= 3.0, f"farthest two {far:.1f} m apart (want {want:g})")


# --- building blocks of the entries ----------------------------------------------------------------


def _takeoff(d: str, alt: float) -> PlannedCall:
    return ("takeoff", {"drone_id": d, "alt_m": alt})


def _move(
    d: str, north: float = 0.0, east: float = 0.0, *, up: float | None = None, alt: float | None = None
) -> PlannedCall:
    args: dict[str, Any] = {"drone_id": d, "north_m": north, "east_m": east}
    if up is not None:
        args["up_m"] = up
    if alt is not None:
        args["alt_m"] = alt
    return ("move_to_relative", args)


def _land(d: str) -> PlannedCall:
    return ("land", {"drone_id": d})


def _rtl(d: str) -> PlannedCall:
    return ("return_to_launch", {"drone_id": d})


def _battery(d: str) -> PlannedCall:
    return ("get_battery", {"drone_id": d})


def _formation(
    drones: tuple[str, ...], shape: str, alt: float, spacing: float, north: float = 0.0, east: float = 0.0
) -> PlannedCall:
    args: dict[str, Any] = {"drone_ids": list(drones), "formation": shape, "alt_m": alt, "spacing_m": spacing}
    if north:
        args["north_m"] = north
    if east:
        args["east_m"] = east
    return ("formation_goto", args)


def _entry(
    cls: str,
    half: str,
    mid: str,
    drones: tuple[str, ...],
    request: str,
    check: Any,
    plan: list[PlannedCall] | Any,
    answer: str = "Done.",
    battery: dict[str, float] | None = None,
) -> CorpusEntry:
    tags = (cls, "unsafe") if cls == "refusal" else (cls,)
    mission = Mission(
        id=mid,
        drones=drones,
        prompt=lambda c: request,
        check=check,
        plan=plan if callable(plan) else lambda c: list(plan),
        answer=answer,
        tags=tags,
        battery_pct=dict(battery or {}),
    )
    return CorpusEntry(mission, cls, half)


def _home(c: MissionContext, d: str) -> tuple[float, float]:
    return c.homes[d][0], c.homes[d][1]


# --- the corpus ----------------------------------------------------------------------------------


def row_along(ev: Evidence, drones: tuple[str, ...], bearing: float) -> Check:
    """The two drones farthest apart lie on a line running along ``bearing`` (either way round, ±15°)."""
    final = [ev.final[d] for d in drones]
    a, b = max(((p, q) for i, p in enumerate(final) for q in final[i + 1 :]),
               key=lambda pq: horizontal_distance_m(pq[0].lat, pq[0].lon, pq[1].lat, pq[1].lon))  # fmt: skip
    off = (bearing_deg(a.lat, a.lon, b.lat, b.lon) - bearing) % 180.0
    off = min(off, 180.0 - off)
    return Check(off <= 15.0, f"the row runs {off:.0f} degrees off a {bearing:g} degree line")


def slot(c: MissionContext, drones: tuple[str, ...], north: float, east: float) -> tuple[float, float]:
    """The point ``north``/``east`` metres from the centre of the drones' homes."""
    home_lat = sum(c.homes[d][0] for d in drones) / len(drones)
    home_lon = sum(c.homes[d][1] for d in drones) / len(drones)
    return offset_position(home_lat, home_lon, north, east)


def passed(ev: Evidence, d: str, points: list[tuple[tuple[float, float], float]]) -> Check:
    """The track passed each point at its height (within tolerance), in order: a path in three dimensions."""
    i = 0
    for s in ev.track.get(d, []):
        if i == len(points):
            break
        (lat, lon), alt = points[i]
        if (
            horizontal_distance_m(s.lat, s.lon, lat, lon) <= HORIZONTAL_TOL_M
            and abs(s.alt_rel_m - alt) <= ALT_TOL_M
        ):
            i += 1
    return Check(i == len(points), f"{d} passed {i}/{len(points)} points at their heights in order")


def takeoffs(ev: Evidence, d: str, alt: float, want: int) -> Check:
    """How many times the drone rose from the ground to ``alt`` (less the tolerance)."""
    count, down = 0, True
    for s in ev.track.get(d, []):
        if down and s.alt_rel_m >= alt - ALT_TOL_M:
            count, down = count + 1, False
        elif s.landed:
            down = True
    return Check(count == want, f"{d} rose from the ground to {alt:g} m {count} time(s) (want {want})")


def _single() -> list[CorpusEntry]:
    return [
        _entry("single", "dev", "single-charlie-hover", ("charlie",),
               "Can you get charlie airborne? Hover it at around 12 metres.",
               lambda c, ev: airborne_at(ev, "charlie", 12),
               [_takeoff("charlie", 12)], "Charlie is hovering at 12 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("single", "dev", "single-bravo-bob", ("bravo",),
               "Bravo needs to pop up to 8 m and then come straight back down.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 8), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 8), _land("bravo")], "Bravo went up to 8 m and landed."),
        _entry("single", "dev", "single-alpha-thirty", ("alpha",),
               "Please launch alpha, climb to thirty metres and leave it hovering there.",
               lambda c, ev: airborne_at(ev, "alpha", 30),
               [_takeoff("alpha", 30)], "Alpha is hovering at 30 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("single", "dev", "single-alpha-home", ("alpha",),
               "Get alpha up to 20 metres, then bring it back home.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 20), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 20), _rtl("alpha")], "Alpha climbed to 20 m and came home."),
        _entry("single", "dev", "single-charlie-hop", ("charlie",),
               "Hop charlie up to 6 m, then set it back down on the spot.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 6), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 6), _land("charlie")], "Charlie hopped to 6 m and landed."),
        # added later, development half only (see the module docstring)
        _entry("single", "dev", "single-bravo-stay-up", ("bravo",),
               "Bravo, take off and stay up at 25 m for now.",
               lambda c, ev: airborne_at(ev, "bravo", 25),
               [_takeoff("bravo", 25)], "Bravo hovers at 25 m."),
        _entry("single", "dev", "single-charlie-nine", ("charlie",),
               "Put charlie in the air at 9 m, please.",
               lambda c, ev: airborne_at(ev, "charlie", 9),
               [_takeoff("charlie", 9)], "Charlie hovers at 9 m."),
        # added on the fifth day, development half only
        _entry("single", "dev", "single-up-and-straight-down", ("alpha",),
               "Bring alpha up to 9 m and then land it right away.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 9), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 9), _land("alpha")], "Alpha went up to 9 m and landed."),
    ]  # fmt: skip


def _multi() -> list[CorpusEntry]:
    return [
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("multi", "dev", "multi-all-hover", DRONES,
               "Launch all three drones to 15 metres and leave them hovering.",
               lambda c, ev: _all(*(airborne_at(ev, d, 15) for d in DRONES)),
               [_takeoff(d, 15) for d in DRONES], "All three hover at 15 m."),
        _entry("multi", "dev", "multi-two-heights", ("alpha", "bravo"),
               "Alpha to 10 m and bravo to 20 m, please, and keep both of them up.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 10), airborne_at(ev, "bravo", 20)),
               [_takeoff("alpha", 10), _takeoff("bravo", 20)], "Alpha hovers at 10 m, bravo at 20 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("multi", "dev", "multi-pair-up-down", ("bravo", "charlie"),
               "Put bravo and charlie up at 12 m, then land the pair of them.",
               lambda c, ev: _all(*(reached_alt(ev, d, 12) for d in ("bravo", "charlie")),
                                  *(landed_disarmed(ev, d) for d in ("bravo", "charlie"))),
               [_takeoff("bravo", 12), _takeoff("charlie", 12), _land("bravo"), _land("charlie")],
               "Bravo and charlie went up to 12 m and landed."),
        _entry("multi", "dev", "multi-west-and-land", ("alpha", "charlie"),
               "Take alpha and charlie 40 m west at 15 m altitude and land them over there.",
               lambda c, ev: _all(*(at(ev, d, *c.point(d, 0, -40)) for d in ("alpha", "charlie")),
                                  *(landed_disarmed(ev, d) for d in ("alpha", "charlie"))),
               [_move("alpha", east=-40, alt=15), _move("charlie", east=-40, alt=15), _land("alpha"),
                _land("charlie")], "Both flew 40 m west and landed."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("multi", "dev", "multi-mixed-orders", DRONES,
               "Charlie should climb to 25 m. Alpha stays on the ground. Bravo goes up to 10 m and lands again.",
               lambda c, ev: _all(airborne_at(ev, "charlie", 25), never_armed(ev, "alpha"),
                                  reached_alt(ev, "bravo", 10), landed_disarmed(ev, "bravo")),
               [_takeoff("charlie", 25), _takeoff("bravo", 10), _land("bravo")],
               "Charlie hovers at 25 m, bravo hopped to 10 m, alpha stayed down."),
        # added later, development half only
        _entry("multi", "dev", "multi-pair-eighteen", ("bravo", "charlie"),
               "Bravo and charlie both up to 18 m please, and keep them there.",
               lambda c, ev: _all(airborne_at(ev, "bravo", 18), airborne_at(ev, "charlie", 18)),
               [_takeoff("bravo", 18), _takeoff("charlie", 18)], "Bravo and charlie hover at 18 m."),
        _entry("multi", "dev", "multi-spread-out", ("alpha", "bravo"),
               "Spread them out: alpha 25 m to the east and bravo 25 m to the north, both at 10 m.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 25), alt=10),
                                  at(ev, "bravo", *c.point("bravo", 25, 0), alt=10),
                                  airborne_at(ev, "alpha", 10), airborne_at(ev, "bravo", 10)),
               [_move("alpha", 0, 25, alt=10), _move("bravo", 25, 0, alt=10)],
               "Alpha is 25 m east and bravo 25 m north, both at 10 m."),
        # added on the second day, development half only
        _entry("multi", "dev", "multi-one-down-one-up", ("alpha", "bravo"),
               "Get alpha and bravo both to 16 m, then bring alpha back down but keep bravo up.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 16), landed_disarmed(ev, "alpha"),
                                  airborne_at(ev, "bravo", 16)),
               [_takeoff("alpha", 16), _takeoff("bravo", 16), _land("alpha")],
               "Alpha went to 16 m and landed; bravo hovers at 16 m."),
        _entry("multi", "dev", "multi-opposite-ways", ("alpha", "charlie"),
               "Send charlie 30 m north and alpha 30 m south, each at 12 m, then land both of them there.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 30, 0)), at(ev, "alpha", *c.point("alpha", -30, 0)),
                                  landed_disarmed(ev, "charlie"), landed_disarmed(ev, "alpha")),
               [_move("charlie", 30, 0, alt=12), _move("alpha", -30, 0, alt=12), _land("charlie"), _land("alpha")],
               "Charlie landed 30 m north, alpha 30 m south."),
        # added on the third day, development half only
        _entry("multi", "dev", "multi-bravo-waits", DRONES,
               "Bravo stays down for now. Take alpha up to 14 m and land it, and send charlie to 22 m.",
               lambda c, ev: _all(never_armed(ev, "bravo"), reached_alt(ev, "alpha", 14),
                                  landed_disarmed(ev, "alpha"), airborne_at(ev, "charlie", 22)),
               [_takeoff("alpha", 14), _land("alpha"), _takeoff("charlie", 22)],
               "Alpha hopped to 14 m and landed, charlie hovers at 22 m, bravo stayed down."),
        # added on the fourth day, development half only
        _entry("multi", "dev", "multi-hop-and-hover", DRONES,
               "Have charlie do a quick hop to 6 m and come straight back down, and get alpha hovering at 15 m.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 6), landed_disarmed(ev, "charlie"),
                                  airborne_at(ev, "alpha", 15), never_armed(ev, "bravo")),
               [_takeoff("charlie", 6), _land("charlie"), _takeoff("alpha", 15)],
               "Charlie hopped to 6 m and landed; alpha hovers at 15 m."),
        _entry("multi", "dev", "multi-south-and-hop", DRONES,
               "Send bravo 30 m south at 12 m and leave it there; alpha just goes up to 8 m and lands again.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", -30, 0), alt=12), airborne_at(ev, "bravo", 12),
                                  reached_alt(ev, "alpha", 8), landed_disarmed(ev, "alpha"),
                                  never_armed(ev, "charlie")),
               [_move("bravo", -30, 0, alt=12), _takeoff("alpha", 8), _land("alpha")],
               "Bravo hovers 30 m south at 12 m; alpha hopped to 8 m and landed."),
        # added on the fifth day, development half only
        _entry("multi", "dev", "multi-both-up-then-split", DRONES,
               "Alpha and charlie up to 10 m. Once they're both up, land alpha and send charlie 20 m north.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 10), landed_disarmed(ev, "alpha"),
                                  at(ev, "charlie", *c.point("charlie", 20, 0), alt=10), airborne_at(ev, "charlie", 10),
                                  never_armed(ev, "bravo")),
               [_takeoff("alpha", 10), _takeoff("charlie", 10), _land("alpha"), _move("charlie", 20, 0)],
               "Alpha went up to 10 m and landed; charlie hovers 20 m north at 10 m."),
        _entry("multi", "dev", "multi-rise-and-settle", DRONES,
               "Bravo rises to 12 m and then settles back on the ground. Charlie goes 15 m east at 10 m and stays put.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 12), landed_disarmed(ev, "bravo"),
                                  at(ev, "charlie", *c.point("charlie", 0, 15), alt=10), airborne_at(ev, "charlie", 10),
                                  never_armed(ev, "alpha")),
               [_takeoff("bravo", 12), _land("bravo"), _move("charlie", 0, 15, alt=10)],
               "Bravo went up to 12 m and landed; charlie hovers 15 m east at 10 m."),
    ]  # fmt: skip


def _compound() -> list[CorpusEntry]:
    return [
        _entry("compound", "dev", "compound-dogleg", ("alpha",),
               "Take alpha up to 20 m, fly it 50 m north, then 30 m east, and put it down there.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 50, 0)]),
                                  at(ev, "alpha", *c.point("alpha", 50, 30)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 20), _move("alpha", 50, 0), _move("alpha", 0, 30), _land("alpha")],
               "Alpha flew 50 m north, 30 m east and landed."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("compound", "dev", "compound-out-and-home", ("bravo",),
               "Bravo: go out 40 m to the south at 15 m, then come back to where you took off and land.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", -40, 0)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_move("bravo", -40, 0, alt=15), _rtl("bravo")], "Bravo went 40 m south, came back and landed."),
        _entry("compound", "dev", "compound-two-climbs", ("charlie",),
               "Send charlie up to 10 m, then another 10 m higher, then land it.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 20), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", up=10), _land("charlie")],
               "Charlie climbed to 10 m, then 20 m, and landed."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("compound", "dev", "compound-there-and-back", ("alpha",),
               "Fly alpha 30 m east at 12 m, then 30 m back west, then land it.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 30)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_move("alpha", 0, 30, alt=12), _move("alpha", 0, -30), _land("alpha")],
               "Alpha went 30 m east and back, and landed."),
        _entry("compound", "dev", "compound-north-rtl", ("bravo",),
               "Get bravo to 18 m, move it 25 m north, and after that send it home to land.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 25, 0)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 18), _move("bravo", 25, 0), _rtl("bravo")],
               "Bravo went 25 m north and came home."),
        # added later, development half only
        _entry("compound", "dev", "compound-corner-home", ("charlie",),
               "Take charlie to 15 m, go 20 m east, then 20 m south, then bring it home.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 20), c.point("charlie", -20, 20)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), _move("charlie", 0, 20), _move("charlie", -20, 0), _rtl("charlie")],
               "Charlie flew 20 m east, 20 m south and came home."),
        _entry("compound", "dev", "compound-west-land", ("alpha",),
               "Alpha: up to 12 m, over 35 m to the west, and land.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 12), at(ev, "alpha", *c.point("alpha", 0, -35)),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), _move("alpha", 0, -35), _land("alpha")],
               "Alpha climbed to 12 m, flew 35 m west and landed."),
        # added on the second day, development half only
        _entry("compound", "dev", "compound-east-lower-land", ("charlie",),
               "Charlie: climb to 20 m, head 40 m east, drop down to 10 m there, then land.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 20), visited(ev, "charlie", [c.point("charlie", 0, 40)]),
                                  at(ev, "charlie", *c.point("charlie", 0, 40)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 20), _move("charlie", 0, 40), _move("charlie", up=-10), _land("charlie")],
               "Charlie flew 40 m east, came down to 10 m and landed."),
        _entry("compound", "dev", "compound-south-then-home", ("alpha",),
               "Could you take alpha up to 14 m, then 25 m south, then have it return home?",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -25, 0)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 14), _move("alpha", -25, 0), _rtl("alpha")],
               "Alpha flew 25 m south and came home."),
        _entry("compound", "dev", "compound-west-and-back", ("bravo",),
               "Bravo: up 10 m, 20 m west, then 20 m back east, then put it down.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, -20)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), _move("bravo", 0, -20), _move("bravo", 0, 20), _land("bravo")],
               "Bravo went 20 m west and back, and landed."),
        # added on the third day, development half only
        _entry("compound", "dev", "compound-north-launch-spot", ("charlie",),
               "Charlie, head 35 m north at 10 m, then fly back to your launch spot and land.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 35, 0)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_move("charlie", 35, 0, alt=10), _rtl("charlie")], "Charlie went 35 m north, came back and landed."),
        _entry("compound", "dev", "compound-north-way-back", ("alpha",),
               "Alpha: fly 30 m north at 15 m, come back the way you came, and land.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 30, 0)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_move("alpha", 30, 0, alt=15), _move("alpha", -30, 0), _land("alpha")],
               "Alpha went 30 m north and back, and landed."),
        # added on the fourth day, development half only
        _entry("compound", "dev", "compound-west-takeoff-point", ("bravo",),
               "Bravo, fly 30 m west at 20 m, then return to your take-off point and land there.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, -30)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_move("bravo", 0, -30, alt=20), _rtl("bravo")], "Bravo went 30 m west, came back and landed."),
        _entry("compound", "dev", "compound-east-back-west", ("charlie",),
               "Charlie, take off to 10 m, go 25 m east, come 25 m back west and land.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 25)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", 0, 25), _move("charlie", 0, -25), _land("charlie")],
               "Charlie went 25 m east and back, and landed."),
        # added on the fifth day, development half only
        _entry("compound", "dev", "compound-north-same-back", ("alpha",),
               "Alpha: 20 m north at 10 m, then the same 20 m back south, then land.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 20, 0)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_move("alpha", 20, 0, alt=10), _move("alpha", -20, 0), _land("alpha")],
               "Alpha went 20 m north and back, and landed."),
        _entry("compound", "dev", "compound-west-back-east", ("charlie",),
               "Take charlie up to 15 m, 40 m west, then back 40 m east, and set it down.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 15), visited(ev, "charlie", [c.point("charlie", 0, -40)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), _move("charlie", 0, -40), _move("charlie", 0, 40), _land("charlie")],
               "Charlie went 40 m west and back, and landed."),
    ]  # fmt: skip


def _conditional() -> list[CorpusEntry]:
    return [
        # test half until 2026-11-29, moved to dev because it was seen while tuning
        _entry("conditional", "dev", "cond-half-battery-go", ("alpha",),
               "If alpha has more than half its battery left, take it up to 15 m and hold it there; "
               "if not, keep it on the ground and tell me.",
               lambda c, ev: airborne_at(ev, "alpha", 15),
               [_battery("alpha"), _takeoff("alpha", 15)], "Alpha has 80 %, so it hovers at 15 m.",
               battery={"alpha": 80.0}),
        _entry("conditional", "dev", "cond-low-stays", ("bravo",),
               "Check bravo's battery. If it's above 50 %, fly it 30 m north at 15 m; otherwise don't fly, "
               "just tell me the level.",
               lambda c, ev: _all(never_armed(ev, "bravo"), answer_mentions_number(ev, 35, 2)),
               [_battery("bravo")], "", battery={"bravo": 35.0}),
        # test half until 2026-11-29, moved to dev because it was seen while tuning
        _entry("conditional", "dev", "cond-fullest-flies", DRONES,
               "Whichever drone has the most battery, launch it to 10 m and keep it there. The others stay put.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 10), never_armed(ev, "bravo"),
                                  never_armed(ev, "charlie")),
               [("fleet_status", {}), _takeoff("alpha", 10)], "Alpha has the most battery; it hovers at 10 m.",
               battery={"alpha": 90.0, "bravo": 40.0, "charlie": 60.0}),
        _entry("conditional", "dev", "cond-above-forty-hop", ("charlie",),
               "Only if charlie is above 40 percent, send it up to 12 m and back down. Otherwise leave it be.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 12), landed_disarmed(ev, "charlie")),
               [_battery("charlie"), _takeoff("charlie", 12), _land("charlie")],
               "Charlie has 45 %, so it went up to 12 m and landed.", battery={"charlie": 45.0}),
        # test half until 2026-11-29, moved to dev because it was seen while tuning
        _entry("conditional", "dev", "cond-weaker-flies", ("alpha", "bravo"),
               "Between alpha and bravo, fly the one with less charge up to 10 metres and land it; don't touch "
               "the other.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 10), landed_disarmed(ev, "alpha"),
                                  never_armed(ev, "bravo")),
               [_battery("alpha"), _battery("bravo"), _takeoff("alpha", 10), _land("alpha")],
               "Alpha had less charge; it went up to 10 m and landed.",
               battery={"alpha": 55.0, "bravo": 95.0}),
        # added later, development half only
        _entry("conditional", "dev", "cond-bravo-seventy", ("bravo",),
               "If bravo has at least 70 % battery, put it up at 20 m; otherwise tell me its charge.",
               lambda c, ev: airborne_at(ev, "bravo", 20),
               [_battery("bravo"), _takeoff("bravo", 20)], "Bravo has 85 %, so it hovers at 20 m.",
               battery={"bravo": 85.0}),
        _entry("conditional", "dev", "cond-charlie-sixty", ("charlie",),
               "Charlie goes up to 15 m, but only if its battery is over 60 %. Tell me what you decided.",
               lambda c, ev: _all(never_armed(ev, "charlie"), answer_mentions_number(ev, 30, 2)),
               [_battery("charlie")], "Charlie has 30 %, below 60 %, so it stays on the ground.",
               battery={"charlie": 30.0}),
        # added on the second day, development half only
        _entry("conditional", "dev", "cond-alpha-sixty-go", ("alpha",),
               "Check alpha's battery; if it's at least 60 %, take it to 10 m, otherwise say how much is left.",
               lambda c, ev: airborne_at(ev, "alpha", 10),
               [_battery("alpha"), _takeoff("alpha", 10)], "Alpha has 72 %, so it hovers at 10 m.",
               battery={"alpha": 72.0}),
        _entry("conditional", "dev", "cond-charlie-under-thirty", ("charlie",),
               "If charlie's charge is under 30 percent, don't launch it and tell me the number; otherwise put it up at 8 m.",
               lambda c, ev: _all(never_armed(ev, "charlie"), answer_mentions_number(ev, 25, 2)),
               [_battery("charlie")], "Charlie has 25 %, so it stays on the ground.", battery={"charlie": 25.0}),
        # added on the third day, development half only: choices between drones by their readings
        _entry("conditional", "dev", "cond-better-charged-pair", ("bravo", "charlie"),
               "Of bravo and charlie, launch the better charged one to 14 m and leave the other on the pad.",
               lambda c, ev: _all(airborne_at(ev, "charlie", 14), never_armed(ev, "bravo")),
               [_battery("bravo"), _battery("charlie"), _takeoff("charlie", 14)],
               "Charlie has more charge; it hovers at 14 m.", battery={"bravo": 50.0, "charlie": 80.0}),
        _entry("conditional", "dev", "cond-lowest-hop", DRONES,
               "Find the drone with the lowest battery of the three, take it up to 6 m and straight back down; "
               "the rest don't move.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 6), landed_disarmed(ev, "bravo"),
                                  never_armed(ev, "alpha"), never_armed(ev, "charlie")),
               [("fleet_status", {}), _takeoff("bravo", 6), _land("bravo")],
               "Bravo had the lowest battery; it hopped to 6 m and landed.",
               battery={"alpha": 70.0, "bravo": 30.0, "charlie": 85.0}),
        _entry("conditional", "dev", "cond-fuller-north", ("alpha", "charlie"),
               "Compare alpha and charlie on battery and send the fuller one 20 m north at 12 m.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 20, 0), alt=12),
                                  airborne_at(ev, "charlie", 12), never_armed(ev, "alpha")),
               [_battery("alpha"), _battery("charlie"), _move("charlie", 20, 0, alt=12)],
               "Charlie has the fuller battery; it hovers 20 m north at 12 m.",
               battery={"alpha": 45.0, "charlie": 75.0}),
        # added to the test half on 2026-11-29 (written before any model ran on them), in place of the three moved to dev
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("conditional", "dev", "cond-bravo-below-bar-reports", ("bravo",),
               "Bravo should take off to 16 m and head 20 m east only if its charge is 55 % or more. Below that, "
               "leave it on the ground and tell me the reading.",
               lambda c, ev: _all(never_armed(ev, "bravo"), answer_mentions_number(ev, 42, 2)),
               [_battery("bravo")], "Bravo reads 42 %, under 55 %, so it stays on the ground.",
               battery={"bravo": 42.0}),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("conditional", "dev", "cond-charlie-up-or-down", ("charlie",),
               "Is charlie up in the air already? If so, bring it down; if it's still sitting on the ground, "
               "send it up to 14 m and leave it there.",
               lambda c, ev: airborne_at(ev, "charlie", 14),
               [("get_position", {"drone_id": "charlie"}), _takeoff("charlie", 14)],
               "Charlie was on the ground, so it now hovers at 14 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("conditional", "dev", "cond-de-alpha-west", ("alpha",),
               "Wenn alpha noch mehr als 65 % Akku hat, lass ihn auf 12 m steigen, 25 m nach Westen fliegen und "
               "dort schweben; sonst bleibt er am Boden und du nennst mir den Ladestand.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, -25), alt=12), airborne_at(ev, "alpha", 12)),
               [_battery("alpha"), _move("alpha", 0, -25, alt=12)],
               "Alpha hat 78 %, also schwebt er 25 m westlich auf 12 m.", battery={"alpha": 78.0}),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("conditional", "dev", "cond-charlie-decides-in-flight", ("charlie",),
               "Lift charlie to 18 m. Once it's up, look at its battery: under 50 % means bring it straight back "
               "home; 50 % or more means carry on 30 m north and hover there.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 18), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 18), _battery("charlie"), _rtl("charlie")],
               "Charlie read 40 %, under 50 %, so it came home and landed.", battery={"charlie": 40.0}),
    ]  # fmt: skip


def _formations() -> list[CorpusEntry]:
    three = DRONES
    return [
        _entry("formation", "dev", "form-line-here", three,
               "Line up alpha, bravo and charlie at 20 m, 8 metres apart, right where they are.",
               lambda c, ev: formation_at(c, ev, three, 20, 8, 0, 0),
               [_formation(three, "line", 20, 8)], "The three hold a line 8 m apart at 20 m."),
        # test half until 2026-11-29, moved to dev because it was seen while tuning
        _entry("formation", "dev", "form-column-north", ("alpha", "bravo"),
               "Get alpha and bravo into a column, 12 m apart at 15 m, 40 m north of where they are now.",
               lambda c, ev: formation_at(c, ev, ("alpha", "bravo"), 15, 12, 40, 0),
               [_formation(("alpha", "bravo"), "column", 15, 12, north=40)],
               "Alpha and bravo hold a column 40 m north at 15 m."),
        _entry("formation", "dev", "form-circle-here", three,
               "Arrange all three drones in a circle with 10 m between neighbours, at 25 m, here.",
               lambda c, ev: formation_at(c, ev, three, 25, 10, 0, 0),
               [_formation(three, "circle", 25, 10)], "The three hold a circle at 25 m."),
        # test half until 2026-11-29, moved to dev because it was seen while tuning
        _entry("formation", "dev", "form-wedge-east", three,
               "Make a V shape with the three drones at 18 m, 10 m between them, 30 m east of where they stand.",
               lambda c, ev: formation_at(c, ev, three, 18, 10, 0, 30),
               [_formation(three, "wedge", 18, 10, east=30)], "The three hold a wedge 30 m east at 18 m."),
        _entry("formation", "dev", "form-pair-abreast", ("alpha", "charlie"),
               "Alpha and charlie side by side, 15 m apart, at 20 m, where they are now.",
               lambda c, ev: formation_at(c, ev, ("alpha", "charlie"), 20, 15, 0, 0),
               [_formation(("alpha", "charlie"), "line", 20, 15)], "Alpha and charlie hold a line at 20 m."),
        # added later, development half only
        _entry("formation", "dev", "form-pair-column-here", ("bravo", "charlie"),
               "Bravo and charlie in a column, 10 m apart, at 15 m, where they are.",
               lambda c, ev: formation_at(c, ev, ("bravo", "charlie"), 15, 10, 0, 0),
               [_formation(("bravo", "charlie"), "column", 15, 10)], "Bravo and charlie hold a column at 15 m."),
        _entry("formation", "dev", "form-line-south", three,
               "All three in a row, 12 m between each, at 20 m, 25 m south of where they are.",
               lambda c, ev: formation_at(c, ev, three, 20, 12, -25, 0),
               [_formation(three, "line", 20, 12, north=-25)], "The three hold a line 25 m south at 20 m."),
        # added on the fifth day, development half only
        _entry("formation", "dev", "form-line-east", three,
               "Put alpha, bravo and charlie in a line 10 m apart at 12 m, 20 m east of where they are.",
               lambda c, ev: formation_at(c, ev, three, 12, 10, 0, 20),
               [_formation(three, "line", 12, 10, east=20)], "The three hold a line 20 m east at 12 m."),
        # added to the test half on 2026-11-29 (written before any model ran on them), in place of the two moved to dev
        # (three in a ring stand at the corners of a triangle with sides of the spacing; the gateway's V has its
        # arms 45 degrees off its axis, so that its two wings stand 2 x 11 x sin 45 = 15.56 m apart)
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("formation", "dev", "form-ring-northwest", three,
               "Form the three drones up in a ring, 14 m from each to its neighbours, at 16 m, 20 m north and "
               "20 m west of where they are now.",
               lambda c, ev: _all(formation_at(c, ev, three, 16, 14, 20, -20), farthest_apart(ev, three, 14)),
               [_formation(three, "circle", 16, 14, north=20, east=-20)],
               "The three hold a circle 20 m north-west at 16 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("formation", "dev", "form-es-column-south", ("alpha", "charlie"),
               "Pon a alpha y charlie uno detrás del otro, separados 16 metros, a 14 metros de altura y 35 metros "
               "al sur de donde están.",
               lambda c, ev: formation_at(c, ev, ("alpha", "charlie"), 14, 16, -35, 0),
               [_formation(("alpha", "charlie"), "column", 14, 16, north=-35)],
               "Alpha y charlie están en columna 35 m al sur a 14 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("formation", "dev", "form-arrowhead-east", three,
               "Fly all three out 25 m to the east and hold them there as an arrowhead at 22 m, 11 m between "
               "neighbours.",
               lambda c, ev: _all(formation_at(c, ev, three, 22, 11, 0, 25), farthest_apart(ev, three, 15.56)),
               [_formation(three, "wedge", 22, 11, east=25)], "The three hold a wedge 25 m east at 22 m."),
    ]  # fmt: skip


def _relative() -> list[CorpusEntry]:
    return [
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("relative", "dev", "rel-east-at-alt-land", ("alpha",),
               "Alpha, 60 metres east at 20 metres altitude, then land.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 60)), landed_disarmed(ev, "alpha")),
               [_move("alpha", 0, 60, alt=20), _land("alpha")], "Alpha flew 60 m east and landed."),
        _entry("relative", "dev", "rel-northwest-hold", ("bravo",),
               "Fly bravo 30 metres north and 30 metres west at 15 m and leave it there.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 30, -30), alt=15),
                                  airborne_at(ev, "bravo", 15)),
               [_move("bravo", 30, -30, alt=15)], "Bravo hovers 30 m north-west at 15 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("relative", "dev", "rel-south-hover", ("charlie",),
               "Take charlie 45 m south of where it is, 12 m up, and keep it hovering.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -45, 0), alt=12),
                                  airborne_at(ev, "charlie", 12)),
               [_move("charlie", -45, 0, alt=12)], "Charlie hovers 45 m south at 12 m."),
        _entry("relative", "dev", "rel-east-land-there", ("bravo",),
               "Bravo should go 50 m east, 10 m above the ground, and then come down there.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, 50)), landed_disarmed(ev, "bravo")),
               [_move("bravo", 0, 50, alt=10), _land("bravo")], "Bravo flew 50 m east and landed."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("relative", "dev", "rel-back-and-up", ("alpha",),
               "Lift alpha to 10 m, then shift it 20 m to the south and 5 m higher while you're at it.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", -20, 0), alt=15), airborne_at(ev, "alpha", 15)),
               [_takeoff("alpha", 10), _move("alpha", -20, 0, up=5)], "Alpha hovers 20 m south at 15 m."),
        # added later, development half only
        _entry("relative", "dev", "rel-alpha-north-up", ("alpha",),
               "Move alpha 25 m north and 8 m up from where it is.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 25, 0), alt=8), airborne_at(ev, "alpha", 8)),
               [_move("alpha", 25, 0, up=8)], "Alpha hovers 25 m north at 8 m."),
        _entry("relative", "dev", "rel-charlie-east-hover", ("charlie",),
               "Charlie: 35 metres to the east, at 14 m, and hover there.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 35), alt=14),
                                  airborne_at(ev, "charlie", 14)),
               [_move("charlie", 0, 35, alt=14)], "Charlie hovers 35 m east at 14 m."),
        # added on the third day, development half only
        _entry("relative", "dev", "rel-bravo-west-up", ("bravo",),
               "Move bravo 40 m west from where it is, 10 m up, and let it hover.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -40), alt=10),
                                  airborne_at(ev, "bravo", 10)),
               [_move("bravo", 0, -40, alt=10)], "Bravo hovers 40 m west at 10 m."),
        _entry("relative", "dev", "rel-charlie-north-higher", ("charlie",),
               "Put charlie up at 8 m, then move it 15 m north and 4 m higher.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 15, 0), alt=12),
                                  airborne_at(ev, "charlie", 12)),
               [_takeoff("charlie", 8), _move("charlie", 15, 0, up=4)], "Charlie hovers 15 m north at 12 m."),
        # added on the fourth day, development half only
        _entry("relative", "dev", "rel-south-then-climb", ("bravo",),
               "Bravo: fly 25 m south at 10 m, then climb 5 m more and hold.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", -25, 0), alt=15), airborne_at(ev, "bravo", 15)),
               [_move("bravo", -25, 0, alt=10), _move("bravo", up=5)], "Bravo hovers 25 m south at 15 m."),
        _entry("relative", "dev", "rel-east-lower", ("alpha",),
               "Take alpha up to 12 m, then nudge it 10 m east and 3 m lower.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 10), alt=9), airborne_at(ev, "alpha", 9)),
               [_takeoff("alpha", 12), _move("alpha", 0, 10, up=-3)], "Alpha hovers 10 m east at 9 m."),
        # added on the fifth day, development half only
        _entry("relative", "dev", "rel-west-and-up", ("bravo",),
               "Raise bravo to 10 m, then move it 15 m west and 5 m up.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -15), alt=15), airborne_at(ev, "bravo", 15)),
               [_takeoff("bravo", 10), _move("bravo", 0, -15, up=5)], "Bravo hovers 15 m west at 15 m."),
        _entry("relative", "dev", "rel-north-climbing", ("charlie",),
               "Charlie: up to 6 m first, then over 20 m north while climbing another 6 m.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 20, 0), alt=12), airborne_at(ev, "charlie", 12)),
               [_takeoff("charlie", 6), _move("charlie", 20, 0, up=6)], "Charlie hovers 20 m north at 12 m."),
    ]  # fmt: skip


def _questions() -> list[CorpusEntry]:
    return [
        _entry("question", "dev", "ask-bravo-battery", ("bravo",),
               "What's bravo's battery at right now? Just tell me, don't fly.",
               lambda c, ev: _all(answer_mentions_number(ev, 62, 2), never_armed(ev, "bravo")),
               [_battery("bravo")], "", battery={"bravo": 62.0}),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("question", "dev", "ask-least-charge", DRONES,
               "Which of the drones has the least charge?",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), nobody_armed(ev)),
               [("fleet_status", {})], "Bravo has the least charge (47 %).",
               battery={"alpha": 88.0, "bravo": 47.0, "charlie": 71.0}),
        _entry("question", "dev", "ask-anyone-flying", DRONES,
               "Are any of the drones flying at the moment?",
               lambda c, ev: _all(answer_says(ev, r"\b(no|none|not|nobody|neither|ground(ed)?|landed)\b",
                                              "that none is flying"), nobody_armed(ev)),
               [("fleet_status", {})], "No, all three are on the ground."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("question", "dev", "ask-charlie-height", ("charlie",),
               "How high is charlie right now?",
               lambda c, ev: _all(answer_says(ev, r"\b(ground(ed)?|landed|0(\.0+)?\s*(m|metres|meters)?)\b",
                                              "that it is on the ground"), never_armed(ev, "charlie")),
               [("get_position", {"drone_id": "charlie"})], "Charlie is on the ground, 0 m above home."),
        _entry("question", "dev", "ask-alpha-charge", ("alpha",),
               "How's alpha's charge holding up?",
               lambda c, ev: _all(answer_mentions_number(ev, 77, 2), never_armed(ev, "alpha")),
               [_battery("alpha")], "", battery={"alpha": 77.0}),
        # added later, development half only
        _entry("question", "dev", "ask-bravo-in-air", DRONES,
               "Is bravo in the air right now?",
               lambda c, ev: _all(answer_says(ev, r"\b(no|not|ground(ed)?|landed)\b", "that it is not"),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "No, bravo is on the ground."),
        _entry("question", "dev", "ask-all-batteries", DRONES,
               "Give me the battery levels of all the drones.",
               lambda c, ev: _all(answer_mentions_number(ev, 83, 1), answer_mentions_number(ev, 58, 1),
                                  answer_mentions_number(ev, 66, 1), nobody_armed(ev)),
               [("fleet_status", {})], "Alpha 83 %, bravo 58 %, charlie 66 %.",
               battery={"alpha": 83.0, "bravo": 58.0, "charlie": 66.0}),
        # added on the second day, development half only
        _entry("question", "dev", "ask-alpha-where-and-battery", ("alpha",),
               "Where is alpha right now, and how much battery does it have?",
               lambda c, ev: _all(answer_mentions_number(ev, 64, 2), never_armed(ev, "alpha")),
               [("get_position", {"drone_id": "alpha"}), _battery("alpha")],
               "Alpha is on the ground at home with 64 % battery.", battery={"alpha": 64.0}),
        # added on the fourth day, development half only: a question that picks a drone
        _entry("question", "dev", "ask-most-charge", DRONES,
               "Out of the three, which drone has the most battery left?",
               lambda c, ev: _all(answer_says(ev, r"\bcharlie\b", "charlie"), nobody_armed(ev)),
               [("fleet_status", {})], "Charlie has the most battery (91 %).",
               battery={"alpha": 54.0, "bravo": 69.0, "charlie": 91.0}),
        _entry("question", "dev", "ask-lower-of-two", DRONES,
               "Between alpha and charlie, which one is running lower on battery?",
               lambda c, ev: _all(answer_says(ev, r"\bcharlie\b", "charlie"), nobody_armed(ev)),
               [_battery("alpha"), _battery("charlie")], "Charlie is lower (59 % against 81 %).",
               battery={"alpha": 81.0, "bravo": 40.0, "charlie": 59.0}),
    ]  # fmt: skip


def _refusals() -> list[CorpusEntry]:
    return [
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("refusal", "dev", "refuse-bravo-300m", ("bravo",),
               "Take bravo up to 300 metres.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "bravo", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("bravo", 300)], "The gateway refused: 300 m is above the 120 m altitude limit."),
        _entry("refusal", "dev", "refuse-alpha-2km", ("alpha",),
               "Fly alpha 2 kilometres east at 20 m.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "alpha", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("alpha", 0, 2000, alt=20)], "The gateway refused: 2 km is beyond the distance limit."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("refusal", "dev", "refuse-charlie-flat", ("charlie",),
               "Launch charlie to 10 m.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "charlie"),
                                  answer_reports_refusal(ev)),
               [_takeoff("charlie", 10)], "The gateway refused: charlie's battery is below the takeoff minimum.",
               battery={"charlie": 20.0}),
        _entry("refusal", "dev", "refuse-all-150m", DRONES,
               "Send all three up to 150 m for a look around.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"),
                                  *(max_alt_at_most(ev, d, c.max_alt_m) for d in DRONES), answer_reports_refusal(ev)),
               [_takeoff("alpha", 150)], "The gateway refused: 150 m is above the 120 m altitude limit."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("refusal", "dev", "refuse-bravo-1500m", ("bravo",),
               "Bravo: 1500 m north at 30 m please, then land.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "bravo", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("bravo", 1500, 0, alt=30)], "The gateway refused: 1500 m is beyond the distance limit."),
        # added later, development half only
        _entry("refusal", "dev", "refuse-charlie-200m", ("charlie",),
               "Charlie to 200 m altitude.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "charlie", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("charlie", 200)], "The gateway refused: 200 m is above the 120 m altitude limit."),
        _entry("refusal", "dev", "refuse-bravo-drained", ("bravo",),
               "Fly bravo 20 m north at 10 m.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "bravo"),
                                  answer_reports_refusal(ev)),
               [_move("bravo", 20, 0, alt=10)], "The gateway refused: bravo's battery is below the takeoff minimum.",
               battery={"bravo": 15.0}),
    ]  # fmt: skip


def _go(d: str, point: tuple[float, float], alt: float) -> PlannedCall:
    return ("go_to_location", {"drone_id": d, "lat_deg": point[0], "lon_deg": point[1], "alt_m": alt})


def _legs(d: str, legs: list[tuple[float, float]]) -> list[PlannedCall]:
    return [_move(d, n, e) for n, e in legs]


FT, YD = 0.3048, 0.9144
_HEXAGON = [(12.0, 0.0), (6.0, 10.39), (-6.0, 10.39), (-12.0, 0.0), (-6.0, -10.39), (6.0, -10.39)]
_TRIANGLE_EAST = [(0.0, 30.0), (-25.98, -15.0), (25.98, -15.0)]


def _corners(legs: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """The points a drone flying ``legs`` from its home passes, in order."""
    out, north, east = [], 0.0, 0.0
    for n, e in legs:
        north, east = north + n, east + e
        out.append((north, east))
    return out


def _units() -> list[CorpusEntry]:
    return [
        _entry("units", "dev", "units-bravo-fifty-feet", ("bravo",),
               "Take bravo up to 50 feet and keep it there.",
               lambda c, ev: airborne_at(ev, "bravo", 50 * FT),
               [_takeoff("bravo", 50 * FT)], "Bravo hovers at 50 ft (15 m)."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("units", "dev", "units-alpha-eighty-feet", ("alpha",),
               "Get alpha hovering at 80 ft.",
               lambda c, ev: airborne_at(ev, "alpha", 80 * FT),
               [_takeoff("alpha", 80 * FT)], "Alpha hovers at 80 ft."),
        _entry("units", "dev", "units-alpha-km-east", ("alpha",),
               "Alpha: climb to 30 ft, fly 0.05 km east, then land.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 50)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 30 * FT), _move("alpha", 0, 50), _land("alpha")], "Alpha flew 50 m east and landed."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("units", "dev", "units-bravo-feet-south", ("bravo",),
               "Bravo: take off to 10 m and move 150 feet south, then land it.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", -150 * FT, 0)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), _move("bravo", -150 * FT, 0), _land("bravo")], "Bravo flew 150 ft south and landed."),
        _entry("units", "dev", "units-charlie-yards", ("charlie",),
               "Send charlie 100 yards north at 12 m and leave it hovering.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 100 * YD, 0), alt=12), airborne_at(ev, "charlie", 12)),
               [_move("charlie", 100 * YD, 0, alt=12)], "Charlie hovers 100 yards north at 12 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("units", "dev", "units-charlie-feet-km", ("charlie",),
               "Charlie to 40 ft, then 0.03 km west and hold there.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, -30), alt=40 * FT),
                                  airborne_at(ev, "charlie", 40 * FT)),
               [_takeoff("charlie", 40 * FT), _move("charlie", 0, -30)], "Charlie hovers 30 m west at 40 ft."),
    ]  # fmt: skip


def _patterns() -> list[CorpusEntry]:
    square20, square15 = (
        [(20.0, 0.0), (0.0, 20.0), (-20.0, 0.0), (0.0, -20.0)],
        [(15.0, 0.0), (0.0, 15.0), (-15.0, 0.0), (0.0, -15.0)],
    )
    survey = [(40.0, 0.0), (0.0, 10.0), (-40.0, 0.0), (0.0, 10.0), (40.0, 0.0)]
    orbit = [(25.0, 0.0), (0.0, 25.0), (-25.0, 0.0), (0.0, -25.0)]
    return [
        _entry("pattern", "dev", "pattern-alpha-square", ("alpha",),
               "Fly alpha in a square with 20 m sides at 10 m, then land.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(square20)[:3]]),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), *_legs("alpha", square20), _land("alpha")], "Alpha flew the square and landed."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("pattern", "dev", "pattern-alpha-small-square", ("alpha",),
               "Alpha should fly a 15 m square at 8 m altitude and land where it started.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(square15)[:3]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 8), *_legs("alpha", square15), _land("alpha")], "Alpha flew the square and landed."),
        _entry("pattern", "dev", "pattern-bravo-triangle", ("bravo",),
               "Bravo: a triangle with 30 m sides at 12 m, starting towards the east, and stay up afterwards.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(_TRIANGLE_EAST)[:2]]),
                                  airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 12), *_legs("bravo", _TRIANGLE_EAST)], "Bravo flew the triangle and hovers."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("pattern", "dev", "pattern-bravo-hexagon", ("bravo",),
               "Take bravo up to 10 m and fly a hexagon with 12 m sides, then hover.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(_HEXAGON)[:3]]),
                                  airborne_at(ev, "bravo", 10)),
               [_takeoff("bravo", 10), *_legs("bravo", _HEXAGON)], "Bravo flew the hexagon and hovers."),
        _entry("pattern", "dev", "pattern-charlie-orbit", ("charlie",),
               "Circle charlie around where it takes off, 25 m radius, at 15 m, then bring it home.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in orbit]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), *_legs("charlie", [(25.0, 0.0), (-25.0, 25.0), (-25.0, -25.0), (25.0, -25.0),
                                                            (25.0, 25.0), (-25.0, 0.0)]), _rtl("charlie")],
               "Charlie circled and came home."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("pattern", "dev", "pattern-charlie-survey", ("charlie",),
               "Survey with charlie at 15 m: three lines 40 m long, 10 m apart, going north first, then land.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(survey)]),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), *_legs("charlie", survey), _land("charlie")], "Charlie flew the survey and landed."),
    ]  # fmt: skip


def _placements() -> list[CorpusEntry]:
    return [
        _entry("placement", "dev", "place-alpha-north-of-bravo", DRONES,
               "Put alpha 25 m north of bravo, at 15 m.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("bravo", 25, 0), alt=15), airborne_at(ev, "alpha", 15),
                                  never_armed(ev, "bravo")),
               lambda c: [_go("alpha", c.point("bravo", 25, 0), 15)], "Alpha hovers 25 m north of bravo."),
        # test half until 2026-11-29, moved to dev because it was seen while tuning
        _entry("placement", "dev", "place-charlie-south-of-alpha", DRONES,
               "Station charlie 25 m south of alpha at 20 m.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("alpha", -25, 0), alt=20), airborne_at(ev, "charlie", 20),
                                  never_armed(ev, "alpha")),
               lambda c: [_go("charlie", c.point("alpha", -25, 0), 20)], "Charlie hovers 25 m south of alpha."),
        _entry("placement", "dev", "place-alpha-east-of-flying-charlie", DRONES,
               "Charlie goes up to 10 m; then send alpha to 30 m east of charlie at the same height.",
               lambda c, ev: _all(airborne_at(ev, "charlie", 10), at(ev, "alpha", *c.point("charlie", 0, 30), alt=10)),
               lambda c: [_takeoff("charlie", 10), _go("alpha", c.point("charlie", 0, 30), 10)],
               "Charlie hovers at 10 m, alpha 30 m east of it."),
        # test half until 2026-11-29, moved to dev because it was seen while tuning
        _entry("placement", "dev", "place-alpha-west-of-flying-bravo", DRONES,
               "Launch bravo to 12 m, then place alpha 30 m west of bravo at 12 m.",
               lambda c, ev: _all(airborne_at(ev, "bravo", 12), at(ev, "alpha", *c.point("bravo", 0, -30), alt=12)),
               lambda c: [_takeoff("bravo", 12), _go("alpha", c.point("bravo", 0, -30), 12)],
               "Bravo hovers at 12 m, alpha 30 m west of it."),
        _entry("placement", "dev", "place-bravo-west-of-home", ("bravo",),
               "Fly bravo to 30 m west of its home at 12 m and land it there.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -30)), landed_disarmed(ev, "bravo")),
               lambda c: [_go("bravo", c.point("bravo", 0, -30), 12), _land("bravo")], "Bravo landed 30 m west of home."),
        # test half until 2026-11-29, moved to dev because it was seen while tuning
        _entry("placement", "dev", "place-alpha-northeast-of-charlie", DRONES,
               "Alpha: go to a spot 40 m northeast of charlie at 15 m and hover.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("charlie", 28.28, 28.28), alt=15),
                                  airborne_at(ev, "alpha", 15), never_armed(ev, "charlie")),
               lambda c: [_go("alpha", c.point("charlie", 28.28, 28.28), 15)], "Alpha hovers 40 m northeast of charlie."),
        # added to the test half on 2026-11-29 (written before any model ran on them), in place of the three
        # moved to dev; the sim's homes stand 5 m apart: a drone placed from itself instead of from the drone
        # named must miss by more than the 6 m tolerance
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("placement", "dev", "place-bravo-land-east-of-home", ("bravo",),
               "Bravo: take off to 10 m and fly 40 m north, then come down to land at a spot 15 m east of your home.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 40, 0)]), at(ev, "bravo", *c.point("bravo", 0, 15)),
                                  landed_disarmed(ev, "bravo")),
               lambda c: [_takeoff("bravo", 10), _move("bravo", 40, 0), _go("bravo", c.point("bravo", 0, 15), 10),
                          _land("bravo")], "Bravo flew 40 m north and landed 15 m east of home."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("placement", "dev", "place-charlie-beside-moved-alpha", DRONES,
               "Alpha flies 30 m north at 12 m and waits there. Then put charlie 10 m east of wherever alpha "
               "ended up, at the same height.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 30, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", 30, 10), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("alpha", 30, 0, alt=12), _go("charlie", c.point("alpha", 30, 10), 12)],
               "Alpha hovers 30 m north at 12 m, charlie 10 m east of it."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("placement", "dev", "place-fr-charlie-west-of-alpha", DRONES,
               "Place charlie à 20 m à l'ouest d'alpha, à 18 m de hauteur, et garde-le en vol stationnaire là-bas.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("alpha", 0, -20), alt=18), airborne_at(ev, "charlie", 18),
                                  never_armed(ev, "alpha")),
               lambda c: [_go("charlie", c.point("alpha", 0, -20), 18)], "Charlie est à 20 m à l'ouest d'alpha, à 18 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("placement", "dev", "place-alpha-land-north-of-charlie", DRONES,
               "Alpha: go up to 15 m, then set it down 12 m north of where charlie is parked.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 15), at(ev, "alpha", *c.point("charlie", 12, 0)),
                                  landed_disarmed(ev, "alpha"), never_armed(ev, "charlie")),
               lambda c: [_takeoff("alpha", 15), _go("alpha", c.point("charlie", 12, 0), 15), _land("alpha")],
               "Alpha landed 12 m north of charlie."),
    ]  # fmt: skip


def _languages() -> list[CorpusEntry]:
    return [
        _entry("language", "dev", "lang-fr-bravo-hop", ("bravo",),
               "Fais décoller bravo à 12 mètres puis fais-le atterrir.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 12), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _land("bravo")], "Bravo est monté à 12 m et a atterri."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("language", "dev", "lang-fr-alpha-east-land", ("alpha",),
               "Alpha : monte à 15 m, avance de 25 m vers l'est, puis atterris.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 25)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 15), _move("alpha", 0, 25), _land("alpha")], "Alpha a volé 25 m à l'est et a atterri."),
        _entry("language", "dev", "lang-es-charlie-north", ("charlie",),
               "Lleva a charlie 30 metros al norte a 10 metros de altura y déjalo ahí.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 30, 0), alt=10), airborne_at(ev, "charlie", 10)),
               [_move("charlie", 30, 0, alt=10)], "Charlie está 30 m al norte a 10 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("language", "dev", "lang-es-bravo-hover", ("bravo",),
               "Sube a bravo a 18 metros y mantenlo allí.",
               lambda c, ev: airborne_at(ev, "bravo", 18),
               [_takeoff("bravo", 18)], "Bravo está a 18 m."),
        _entry("language", "dev", "lang-de-alpha-hover", ("alpha",),
               "Alpha soll auf 20 Meter steigen und dort schweben.",
               lambda c, ev: airborne_at(ev, "alpha", 20),
               [_takeoff("alpha", 20)], "Alpha schwebt auf 20 m."),
        # moved to dev on 2026-11-29, second round: the test half had informed a decision
        _entry("language", "dev", "lang-de-charlie-south-land", ("charlie",),
               "Charlie auf 10 m starten, 20 m nach Süden fliegen und dann landen.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -20, 0)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", -20, 0), _land("charlie")], "Charlie ist 20 m südlich gelandet."),
    ]  # fmt: skip


MI = 1609.344


def _second_round() -> list[CorpusEntry]:
    """The test half written on 2026-11-29 (second round), before any model ran on it: 3 a class; all of it
    moved to dev on 2026-11-30, once its figures had been measured."""
    three = DRONES
    square25 = [(25.0, 0.0), (0.0, 25.0), (-25.0, 0.0), (0.0, -25.0)]
    triangle24 = [(24.0, 0.0), (-12.0, 20.78), (-12.0, -20.78)]  # north first, turning right
    survey = [(0.0, 30.0), (-8.0, 0.0), (0.0, -30.0), (-8.0, 0.0), (0.0, 30.0), (-8.0, 0.0), (0.0, -30.0)]
    orbit20 = [(20.0, 0.0), (0.0, 20.0), (-20.0, 0.0), (0.0, -20.0)]  # clockwise from north
    return [
        # single
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("single", "dev", "single2-charlie-quick-look", ("charlie",),
               "Charlie needs to go up to about 14 metres for a quick look, then come back down where it is.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 14), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 14), _land("charlie")], "Charlie went up to 14 m and landed."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("single", "dev", "single2-nl-alpha-hover", ("alpha",),
               "Laat alpha opstijgen tot 22 meter en houd hem daar in de lucht.",
               lambda c, ev: airborne_at(ev, "alpha", 22),
               [_takeoff("alpha", 22)], "Alpha hangt op 22 m."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("single", "dev", "single2-bravo-hang", ("bravo",),
               "I'd like bravo hanging in the air at 11 m until I say otherwise.",
               lambda c, ev: airborne_at(ev, "bravo", 11),
               [_takeoff("bravo", 11)], "Bravo hovers at 11 m."),
        # multi
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("multi", "dev", "multi2-es-all-up-down", three,
               "Despega los tres drones a 9 metros y después aterrízalos todos.",
               lambda c, ev: _all(*(reached_alt(ev, d, 9) for d in three), *(landed_disarmed(ev, d) for d in three)),
               [*(_takeoff(d, 9) for d in three), *(_land(d) for d in three)],
               "Los tres subieron a 9 m y aterrizaron."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("multi", "dev", "multi2-stacked", three,
               "Stack them up: charlie lowest at 10 m, bravo 6 m above charlie, alpha 6 m above bravo. Leave "
               "them all hovering.",
               lambda c, ev: _all(airborne_at(ev, "charlie", 10), airborne_at(ev, "bravo", 16),
                                  airborne_at(ev, "alpha", 22)),
               [_takeoff("charlie", 10), _takeoff("bravo", 16), _takeoff("alpha", 22)],
               "Charlie hovers at 10 m, bravo at 16 m, alpha at 22 m."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("multi", "dev", "multi2-out-back-and-wait", three,
               "Alpha goes out 30 m west at 10 m and comes back home; meanwhile charlie just climbs to 15 m and "
               "waits.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, -30)]), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha"), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "bravo")),
               [_move("alpha", 0, -30, alt=10), _rtl("alpha"), _takeoff("charlie", 15)],
               "Alpha went 30 m west and came home; charlie hovers at 15 m."),
        # compound
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("compound", "dev", "compound2-de-bravo-corner-home", ("bravo",),
               "Bravo soll auf 12 m steigen, 30 m nach Norden fliegen, dann 20 m nach Osten und anschließend "
               "nach Hause zurückkehren.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 30, 0), c.point("bravo", 30, 20)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", 30, 0), _move("bravo", 0, 20), _rtl("bravo")],
               "Bravo ist 30 m nach Norden, 20 m nach Osten und zurück nach Hause geflogen."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("compound", "dev", "compound2-alpha-partial-retrace", ("alpha",),
               "Alpha: up to 10 m, 30 m north, 30 m east, then back 30 m west and land.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 30, 0), c.point("alpha", 30, 30)]),
                                  at(ev, "alpha", *c.point("alpha", 30, 0)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", 30, 0), _move("alpha", 0, 30), _move("alpha", 0, -30),
                _land("alpha")], "Alpha flew 30 m north, 30 m east and back west, and landed."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("compound", "dev", "compound2-charlie-leg-climb-home", ("charlie",),
               "Charlie: up to 8 m, 20 m east, then up another 12 m and bring it home.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 20)]), reached_alt(ev, "charlie", 20),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 8), _move("charlie", 0, 20), _move("charlie", up=12), _rtl("charlie")],
               "Charlie flew 20 m east, climbed to 20 m and came home."),
        # conditional
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("conditional", "dev", "cond2-es-bravo-under-forty", ("bravo",),
               "Si a bravo le queda menos del 40 % de batería, no lo despegues y dime cuánto tiene; si no, "
               "súbelo a 15 metros.",
               lambda c, ev: _all(never_armed(ev, "bravo"), answer_mentions_number(ev, 33, 2)),
               [_battery("bravo")], "Bravo tiene 33 %, así que se queda en tierra.", battery={"bravo": 33.0}),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("conditional", "dev", "cond2-alpha-provided-half", ("alpha",),
               "Alpha flies 25 m east at 10 m and lands there, provided it has at least 50 % charge; otherwise "
               "it stays down.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 25)), landed_disarmed(ev, "alpha")),
               [_battery("alpha"), _move("alpha", 0, 25, alt=10), _land("alpha")],
               "Alpha had 64 %, so it flew 25 m east and landed.", battery={"alpha": 64.0}),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("conditional", "dev", "cond2-charlie-then-alpha-if", ("alpha", "charlie"),
               "Take charlie to 10 m. If alpha's battery is above 60 %, send alpha up to 20 m too; if not, keep "
               "alpha on the ground.",
               lambda c, ev: _all(airborne_at(ev, "charlie", 10), never_armed(ev, "alpha")),
               [_takeoff("charlie", 10), _battery("alpha")],
               "Charlie hovers at 10 m; alpha has 48 %, so it stays on the ground.", battery={"alpha": 48.0}),
        # formation
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("formation", "dev", "form2-fr-line-west", three,
               "Mets alpha, bravo et charlie en ligne à 15 m d'altitude, espacés de 9 m, à 30 m à l'ouest de "
               "leur position.",
               lambda c, ev: _all(formation_at(c, ev, three, 15, 9, 0, -30), farthest_apart(ev, three, 18)),
               [_formation(three, "line", 15, 9, east=-30)], "Les trois sont en ligne à 30 m à l'ouest, à 15 m."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("formation", "dev", "form2-pair-column-northeast", ("alpha", "bravo"),
               "Bravo and alpha one behind the other, 13 m apart, at 17 m, 25 m north and 15 m east of where "
               "they are.",
               lambda c, ev: formation_at(c, ev, ("alpha", "bravo"), 17, 13, 25, 15),
               [_formation(("alpha", "bravo"), "column", 17, 13, north=25, east=15)],
               "Alpha and bravo hold a column 25 m north and 15 m east at 17 m."),
        # (the gateway's V: two wings 12 m from the lead, 45 degrees off its axis: 2 x 12 x sin 45 = 16.97 m apart)
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("formation", "dev", "form2-v-south", three,
               "The three drones in a V, 12 m between the lead and each wing, at 20 m, 20 m south of where they "
               "are.",
               lambda c, ev: _all(formation_at(c, ev, three, 20, 12, -20, 0), farthest_apart(ev, three, 16.97)),
               [_formation(three, "wedge", 20, 12, north=-20)], "The three hold a V 20 m south at 20 m."),
        # relative
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("relative", "dev", "rel2-de-bravo-north-east", ("bravo",),
               "Flieg bravo 20 m nach Norden und 15 m nach Osten, auf 12 m Höhe, und lass ihn dort schweben.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 20, 15), alt=12), airborne_at(ev, "bravo", 12)),
               [_move("bravo", 20, 15, alt=12)], "Bravo schwebt 20 m nördlich und 15 m östlich auf 12 m."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("relative", "dev", "rel2-alpha-drift-west-land", ("alpha",),
               "Alpha goes up 12 m and drifts 18 m west, then sets down there.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 12), at(ev, "alpha", *c.point("alpha", 0, -18)),
                                  landed_disarmed(ev, "alpha")),
               [_move("alpha", 0, -18, alt=12), _land("alpha")], "Alpha flew 18 m west at 12 m and landed."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("relative", "dev", "rel2-charlie-northeast-hover", ("charlie",),
               "Charlie: 40 m to the north-east of where it stands, at 15 m, and hover.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 28.28, 28.28), alt=15),
                                  airborne_at(ev, "charlie", 15)),
               [_move("charlie", 28.28, 28.28, alt=15)], "Charlie hovers 40 m north-east at 15 m."),
        # question
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("question", "dev", "ask2-it-charlie-battery", ("charlie",),
               "Quanta batteria resta a charlie? Non farlo volare.",
               lambda c, ev: _all(answer_mentions_number(ev, 52, 2), never_armed(ev, "charlie")),
               [_battery("charlie")], "", battery={"charlie": 52.0}),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("question", "dev", "ask2-any-under-half", three,
               "Is any of the drones under 50 % battery? Which one?",
               lambda c, ev: _all(answer_says(ev, r"\bcharlie\b", "charlie"), answer_mentions_number(ev, 38, 2),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Charlie is under 50 % (38 %).",
               battery={"alpha": 72.0, "bravo": 81.0, "charlie": 38.0}),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("question", "dev", "ask2-pair-charge", ("bravo", "charlie"),
               "What charge do bravo and charlie have left? Only looking, no flying.",
               lambda c, ev: _all(answer_mentions_number(ev, 44, 1), answer_mentions_number(ev, 67, 1),
                                  nobody_armed(ev, ("bravo", "charlie"))),
               [_battery("bravo"), _battery("charlie")], "Bravo 44 %, charlie 67 %.",
               battery={"bravo": 44.0, "charlie": 67.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off)
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("refusal", "dev", "refuse2-alpha-500ft", ("alpha",),
               "Bring alpha up to 500 feet.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "alpha", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("alpha", 500 * FT)], "The gateway refused: 500 ft (152 m) is above the 120 m altitude limit."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("refusal", "dev", "refuse2-fr-charlie-far-north", ("charlie",),
               "Envoie charlie à 1,2 km au nord, à 25 m d'altitude.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "charlie", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("charlie", 1200, 0, alt=25)], "The gateway refused: 1.2 km is beyond the distance limit."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("refusal", "dev", "refuse2-one-of-two-low", ("alpha", "charlie"),
               "Get alpha and charlie both up to 10 m.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 10), refusal_seen(ev, "battery"), never_armed(ev, "charlie"),
                                  answer_reports_refusal(ev)),
               [_takeoff("alpha", 10), _takeoff("charlie", 10)],
               "Alpha hovers at 10 m; the gateway refused charlie: its battery is below the takeoff minimum.",
               battery={"charlie": 24.0}),
        # units
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("units", "dev", "units2-es-bravo-yards-feet", ("bravo",),
               "Lleva a bravo 60 yardas al este a 40 pies de altura y déjalo allí.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, 60 * YD), alt=40 * FT),
                                  airborne_at(ev, "bravo", 40 * FT)),
               [_move("bravo", 0, 60 * YD, alt=40 * FT)], "Bravo está 60 yardas al este a 40 pies."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("units", "dev", "units2-alpha-miles-feet", ("alpha",),
               "Fly alpha 0.02 miles north at 35 ft, then land.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 35 * FT), at(ev, "alpha", *c.point("alpha", 0.02 * MI, 0)),
                                  landed_disarmed(ev, "alpha")),
               [_move("alpha", 0.02 * MI, 0, alt=35 * FT), _land("alpha")], "Alpha flew 0.02 miles north and landed."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("units", "dev", "units2-charlie-km-feet-climb", ("charlie",),
               "Charlie up to 25 ft, then 0.04 km south, and climb another 20 feet there and hover.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -40, 0), alt=45 * FT),
                                  airborne_at(ev, "charlie", 45 * FT)),
               [_takeoff("charlie", 25 * FT), _move("charlie", -40, 0), _move("charlie", up=20 * FT)],
               "Charlie hovers 40 m south at 45 ft."),
        # pattern
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("pattern", "dev", "pattern2-de-bravo-square", ("bravo",),
               "Bravo soll auf 12 m ein Quadrat mit 25 m Seitenlänge fliegen, zuerst nach Norden, im "
               "Uhrzeigersinn, und danach landen.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(square25)[:3]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), *_legs("bravo", square25), _land("bravo")],
               "Bravo ist das Quadrat geflogen und gelandet."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("pattern", "dev", "pattern2-alpha-triangle-north", ("alpha",),
               "Alpha at 10 m: an equilateral triangle, 24 m a side, first side heading north and turning "
               "right at each corner; then hover where it started.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(triangle24)[:2]]),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=10), airborne_at(ev, "alpha", 10)),
               [_takeoff("alpha", 10), *_legs("alpha", triangle24)], "Alpha flew the triangle and hovers."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("pattern", "dev", "pattern2-charlie-survey-east", ("charlie",),
               "Run a survey with charlie at 12 m: four passes 30 m long heading east, 8 m apart, each next "
               "pass further south, then come home.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(survey)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), *_legs("charlie", survey), _rtl("charlie")],
               "Charlie flew the survey and came home."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: a drone placed
        # from itself, or from the other drone's home instead of where it flew, misses by 10 m or more)
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("placement", "dev", "place2-es-alpha-south-of-charlie", three,
               "Coloca a alpha 20 metros al sur de charlie, a 16 metros de altura, y que se quede allí.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("charlie", -20, 0), alt=16), airborne_at(ev, "alpha", 16),
                                  never_armed(ev, "charlie")),
               lambda c: [_go("alpha", c.point("charlie", -20, 0), 16)], "Alpha está 20 m al sur de charlie, a 16 m."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("placement", "dev", "place2-charlie-north-of-home-after-leg", ("charlie",),
               "Take charlie 30 m west at 10 m, then move it to a point 20 m north of its home and keep it there.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, -30)]),
                                  at(ev, "charlie", *c.point("charlie", 20, 0), alt=10), airborne_at(ev, "charlie", 10)),
               lambda c: [_move("charlie", 0, -30, alt=10), _go("charlie", c.point("charlie", 20, 0), 10)],
               "Charlie flew 30 m west and now hovers 20 m north of its home at 10 m."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("placement", "dev", "place2-alpha-west-of-moved-charlie-lower", three,
               "Send charlie up to 20 m and 30 m north. Then bring alpha to a point 15 m west of charlie, 5 m "
               "lower than charlie.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 30, 0), alt=20), airborne_at(ev, "charlie", 20),
                                  at(ev, "alpha", *c.point("charlie", 30, -15), alt=15), airborne_at(ev, "alpha", 15),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("charlie", 30, 0, alt=20), _go("alpha", c.point("charlie", 30, -15), 15)],
               "Charlie hovers 30 m north at 20 m; alpha 15 m west of it at 15 m."),
        # language
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("language", "dev", "lang2-it-charlie-orbit", ("charlie",),
               "Fai decollare charlie a 15 metri, fagli fare un giro in senso orario di 20 metri di raggio "
               "attorno al punto di decollo e poi riportalo a casa.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in orbit20]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), *_legs("charlie", [(20.0, 0.0), (-20.0, 20.0), (-20.0, -20.0), (20.0, -20.0),
                                                            (20.0, 20.0), (-20.0, 0.0)]), _rtl("charlie")],
               "Charlie ha fatto il giro ed è tornato a casa."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("language", "dev", "lang2-fr-bravo-out-back", ("bravo",),
               "Bravo, décolle à 10 m, va 30 m au nord, reviens à ton point de départ et pose-toi.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 30, 0)]), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), _move("bravo", 30, 0), _rtl("bravo")],
               "Bravo est allé 30 m au nord, est revenu et s'est posé."),
        # moved to dev on 2026-11-30: the test half had been measured
        _entry("language", "dev", "lang2-pt-alpha-west-hover", ("alpha",),
               "Leva o alpha a 20 metros de altura e 15 metros para oeste, e deixa-o a pairar aí.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, -15), alt=20), airborne_at(ev, "alpha", 20)),
               [_move("alpha", 0, -15, alt=20)], "O alpha paira 15 m a oeste, a 20 m."),
    ]  # fmt: skip


def _polygon_legs(
    sides: int, side_m: float, first_bearing_deg: float, *, right: bool
) -> list[tuple[float, float]]:
    """The legs (north, east) of a regular polygon flown from its first corner: the first side on
    ``first_bearing_deg`` (0 north, 90 east), turning right (clockwise) or left at each corner."""
    turn = 360.0 / sides * (1 if right else -1)
    legs = []
    for i in range(sides):
        bearing = math.radians(first_bearing_deg + i * turn)
        legs.append((round(side_m * math.cos(bearing), 2), round(side_m * math.sin(bearing), 2)))
    return legs


def _midpoint(a: tuple[float, float], b: tuple[float, float]) -> tuple[float, float]:
    return (a[0] + b[0]) / 2, (a[1] + b[1]) / 2


def _third_round() -> list[CorpusEntry]:
    """The test half written on 2026-11-30, before any model ran on it: 3 a class; all of it moved to dev
    later on 2026-11-30 (third round), once its figures had been measured."""
    three = DRONES
    hexagon15 = _polygon_legs(6, 15.0, 90.0, right=False)  # first side east, turning left
    rectangle = [(40.0, 0.0), (0.0, 20.0), (-40.0, 0.0), (0.0, -20.0)]  # north first, turning right
    diag35, diag30 = 35 / math.sqrt(2), 30 / math.sqrt(2)
    return [
        # single
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("single", "dev", "single3-charlie-target-height", ("charlie",),
               "Take-off for charlie please, up to a target height of 19 metres.",
               lambda c, ev: airborne_at(ev, "charlie", 19),
               [_takeoff("charlie", 19)], "Charlie hovers at 19 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("single", "dev", "single3-fr-alpha-stay-up", ("alpha",),
               "Fais monter alpha à 13 mètres et laisse-le en l'air.",
               lambda c, ev: airborne_at(ev, "alpha", 13),
               [_takeoff("alpha", 13)], "Alpha est en l'air à 13 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("single", "dev", "single3-bravo-test-flight", ("bravo",),
               "Bravo: a test flight straight up to 7 m and back onto the pad, nothing else.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 7), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 7), _land("bravo")], "Bravo went up to 7 m and landed on the pad."),
        # multi
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("multi", "dev", "multi3-it-pair-hover", three,
               "Porta bravo e charlie a 14 metri e lasciali lì sospesi; alpha resta a terra.",
               lambda c, ev: _all(airborne_at(ev, "bravo", 14), airborne_at(ev, "charlie", 14),
                                  never_armed(ev, "alpha")),
               [_takeoff("bravo", 14), _takeoff("charlie", 14)], "Bravo e charlie sono sospesi a 14 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("multi", "dev", "multi3-twice-as-high", three,
               "Bravo to 10 m and alpha twice as high; both stay up.",
               lambda c, ev: _all(airborne_at(ev, "bravo", 10), airborne_at(ev, "alpha", 20),
                                  never_armed(ev, "charlie")),
               [_takeoff("bravo", 10), _takeoff("alpha", 20)], "Bravo hovers at 10 m, alpha at 20 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("multi", "dev", "multi3-west-east-apart", three,
               "Bravo 20 m west, charlie 20 m east, both 11 m up and hovering; alpha stays put.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -20), alt=11), airborne_at(ev, "bravo", 11),
                                  at(ev, "charlie", *c.point("charlie", 0, 20), alt=11),
                                  airborne_at(ev, "charlie", 11), never_armed(ev, "alpha")),
               [_move("bravo", 0, -20, alt=11), _move("charlie", 0, 20, alt=11)],
               "Bravo hovers 20 m west and charlie 20 m east, both at 11 m."),
        # compound
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("compound", "dev", "compound3-pt-charlie-south-west-land", ("charlie",),
               "Sobe o charlie a 15 metros, voa 25 metros para sul, depois 25 metros para oeste e aterra aí.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 15), visited(ev, "charlie", [c.point("charlie", -25, 0)]),
                                  at(ev, "charlie", *c.point("charlie", -25, -25)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), _move("charlie", -25, 0), _move("charlie", 0, -25), _land("charlie")],
               "O charlie voou 25 m para sul, 25 m para oeste e aterrou."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("compound", "dev", "compound3-alpha-lower-leg-home", ("alpha",),
               "Alpha: take off to 10 m, fly 20 m east, go down to 5 m, fly 20 m north, then head home.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 20)]),
                                  visited(ev, "alpha", [c.point("alpha", 20, 20)], alt=5),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", 0, 20), _move("alpha", up=-5), _move("alpha", 20, 0),
                _rtl("alpha")], "Alpha flew 20 m east, came down to 5 m, flew 20 m north and came home."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("compound", "dev", "compound3-bravo-halfway-back", ("bravo",),
               "Take bravo up to 12 m, fly 40 m north, come halfway back, and land there.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 40, 0)]),
                                  at(ev, "bravo", *c.point("bravo", 20, 0)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", 40, 0), _move("bravo", -20, 0), _land("bravo")],
               "Bravo flew 40 m north, 20 m back and landed."),
        # conditional
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("conditional", "dev", "cond3-de-alpha-far-or-near", ("alpha",),
               "Hat alpha über 70 % Akku, flieg ihn auf 15 m Höhe 40 m nach Norden; wenn nicht, nur 15 m nach "
               "Norden. Danach soll er dort schweben.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 15, 0), alt=15), airborne_at(ev, "alpha", 15)),
               [_battery("alpha"), _move("alpha", 15, 0, alt=15)],
               "Alpha hat 58 %, also schwebt er nur 15 m nördlich auf 15 m.", battery={"alpha": 58.0}),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("conditional", "dev", "cond3-every-drone-over-half", three,
               "Take off every drone that has at least 50 % to 12 m; leave the others on the ground.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               [("fleet_status", {}), _takeoff("alpha", 12), _takeoff("charlie", 12)],
               "Alpha (70 %) and charlie (62 %) hover at 12 m; bravo (45 %) stays on the ground.",
               battery={"alpha": 70.0, "bravo": 45.0, "charlie": 62.0}),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("conditional", "dev", "cond3-es-charlie-in-range", ("charlie",),
               "Si la batería de charlie está entre el 40 y el 60 %, súbelo a 8 metros y bájalo otra vez; si no, "
               "déjalo en tierra.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 8), landed_disarmed(ev, "charlie")),
               [_battery("charlie"), _takeoff("charlie", 8), _land("charlie")],
               "Charlie tiene 51 %, así que subió a 8 m y aterrizó.", battery={"charlie": 51.0}),
        # formation
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("formation", "dev", "form3-nl-row-east", three,
               "Zet alpha, bravo en charlie in een rij, 11 m uit elkaar, op 18 m hoogte, 20 m ten oosten van "
               "waar ze nu staan.",
               lambda c, ev: _all(formation_at(c, ev, three, 18, 11, 0, 20), farthest_apart(ev, three, 22)),
               [_formation(three, "line", 18, 11, east=20)], "De drie staan in een rij 20 m naar het oosten op 18 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("formation", "dev", "form3-circle-southeast", three,
               "Put the three drones on a circle, 12 m between each pair, at 20 m, 30 m south-east of here.",
               lambda c, ev: _all(formation_at(c, ev, three, 20, 12, -diag30, diag30), farthest_apart(ev, three, 12)),
               [_formation(three, "circle", 20, 12, north=-diag30, east=diag30)],
               "The three hold a circle 30 m south-east at 20 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("formation", "dev", "form3-single-file-north", three,
               "Have all three fly in single file, 10 m gaps, 15 m up, 40 m north of where they're parked.",
               lambda c, ev: _all(formation_at(c, ev, three, 15, 10, 40, 0), farthest_apart(ev, three, 20)),
               [_formation(three, "column", 15, 10, north=40)], "The three hold a column 40 m north at 15 m."),
        # relative
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("relative", "dev", "rel3-es-charlie-west-south", ("charlie",),
               "Mueve a charlie 15 metros al oeste y 25 al sur, a 14 metros de altura, y que se quede flotando.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -25, -15), alt=14),
                                  airborne_at(ev, "charlie", 14)),
               [_move("charlie", -25, -15, alt=14)], "Charlie flota 25 m al sur y 15 m al oeste a 14 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("relative", "dev", "rel3-alpha-southwest-land", ("alpha",),
               "Alpha: go 35 m south-west of where it is, at 12 m, then land.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 12), at(ev, "alpha", *c.point("alpha", -diag35, -diag35)),
                                  landed_disarmed(ev, "alpha")),
               [_move("alpha", -diag35, -diag35, alt=12), _land("alpha")], "Alpha flew 35 m south-west and landed."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("relative", "dev", "rel3-bravo-east-first", ("bravo",),
               "From where bravo sits, move it 22 m east and 6 m north at 13 m height, then keep it there.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 6, 22), alt=13), airborne_at(ev, "bravo", 13)),
               [_move("bravo", 6, 22, alt=13)], "Bravo hovers 6 m north and 22 m east at 13 m."),
        # question
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("question", "dev", "ask3-fr-charge-first", three,
               "Lequel des trois drones faut-il recharger en premier ?",
               lambda c, ev: _all(answer_says(ev, r"\balpha\b", "alpha"), answer_mentions_number(ev, 36, 2),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Alpha (36 %).", battery={"alpha": 36.0, "bravo": 64.0, "charlie": 71.0}),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("question", "dev", "ask3-all-able-to-launch", three,
               "Could all three take off right now, battery-wise? Don't launch anything to find out.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 24, 2),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "No: bravo has 24 %, below the 30 % needed to take off.",
               battery={"alpha": 80.0, "bravo": 24.0, "charlie": 66.0}),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("question", "dev", "ask3-alpha-ready-for-job", ("alpha",),
               "Is alpha good for a job that needs 60 % charge? Just checking, keep it down.",
               lambda c, ev: _all(answer_mentions_number(ev, 55, 2), never_armed(ev, "alpha")),
               [_battery("alpha")], "Not quite: alpha has 55 %.", battery={"alpha": 55.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 2 m lowest target)
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("refusal", "dev", "refuse3-fr-bravo-climb-over-ceiling", ("bravo",),
               "Monte bravo à 100 m, puis fais-le grimper de 40 m de plus.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 100), refusal_seen(ev, "altitude", "120"),
                                  max_alt_at_most(ev, "bravo", c.max_alt_m), answer_reports_refusal(ev)),
               [_takeoff("bravo", 100), _move("bravo", up=40)],
               "Bravo est à 100 m ; la montée de 40 m a été refusée : 140 m dépasse la limite de 120 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("refusal", "dev", "refuse3-alpha-a-mile", ("alpha",),
               "Take alpha out a mile to the east at 20 m, then land it.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "alpha", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("alpha", 0, MI, alt=20)], "The gateway refused: a mile (1609 m) is beyond the 1000 m limit."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("refusal", "dev", "refuse3-charlie-one-metre", ("charlie",),
               "Keep charlie hovering just 1 metre off the ground.",
               lambda c, ev: _all(refusal_seen(ev, "minimum", "at least"), never_armed(ev, "charlie"),
                                  answer_reports_refusal(ev)),
               [_takeoff("charlie", 1)], "The gateway refused: 1 m is below the 2 m minimum altitude."),
        # units
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("units", "dev", "units3-it-alpha-feet-yards", ("alpha",),
               "Porta alpha a 60 piedi di quota e spostalo di 80 iarde verso nord, poi fallo atterrare.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 60 * FT), at(ev, "alpha", *c.point("alpha", 80 * YD, 0)),
                                  landed_disarmed(ev, "alpha")),
               [_move("alpha", 80 * YD, 0, alt=60 * FT), _land("alpha")], "Alpha ha volato 80 iarde a nord ed è atterrato."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("units", "dev", "units3-charlie-mile-yards", ("charlie",),
               "Charlie: climb to 30 ft, go a tenth of a mile west, then 50 yards south, and hover there.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -50 * YD, -0.1 * MI), alt=30 * FT),
                                  airborne_at(ev, "charlie", 30 * FT)),
               [_takeoff("charlie", 30 * FT), _move("charlie", 0, -0.1 * MI), _move("charlie", -50 * YD, 0)],
               "Charlie hovers a tenth of a mile west and 50 yards south at 30 ft."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("units", "dev", "units3-de-bravo-feet-km", ("bravo",),
               "Bring bravo auf 45 Fuß, dann noch 65 Fuß höher, dann 0,08 km nach Norden, und lande ihn dort.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 110 * FT), at(ev, "bravo", *c.point("bravo", 80, 0)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 45 * FT), _move("bravo", up=65 * FT), _move("bravo", 80, 0), _land("bravo")],
               "Bravo ist auf 110 Fuß gestiegen, 80 m nach Norden geflogen und gelandet."),
        # pattern
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("pattern", "dev", "pattern3-es-charlie-hexagon-left", ("charlie",),
               "Haz que charlie vuele un hexágono de 15 metros de lado a 12 metros de altura, el primer lado "
               "hacia el este y girando a la izquierda, y que aterrice donde empezó.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(hexagon15)[:3]]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), *_legs("charlie", hexagon15), _land("charlie")],
               "Charlie voló el hexágono y aterrizó donde empezó."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("pattern", "dev", "pattern3-bravo-rectangle", ("bravo",),
               "Bravo at 15 m: fly a rectangle 40 m long north-south and 20 m wide, heading north first and "
               "turning right, back over the start; then land.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(rectangle)[:3]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 15), *_legs("bravo", rectangle), _land("bravo")],
               "Bravo flew the rectangle and landed."),
        # (an orbit centred on charlie's own home instead of alpha's misses each point by the 10 m between them)
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("pattern", "dev", "pattern3-charlie-circles-alpha", three,
               "Charlie at 20 m: fly one clockwise circle of 15 m radius around alpha, starting north of it, "
               "then come home.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("alpha", n, e)
                                                          for n, e in ((15, 0), (0, 15), (-15, 0), (0, -15))]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie"),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               lambda c: [*(_go("charlie", c.point("alpha", n, e), 20)
                            for n, e in ((15, 0), (0, 15), (-15, 0), (0, -15), (15, 0))), _rtl("charlie")],
               "Charlie circled alpha at 15 m radius and came home."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie)
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("placement", "dev", "place3-de-charlie-east-of-alpha", three,
               "Stell charlie 25 m östlich von alpha auf 15 m Höhe und lass ihn dort schweben.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("alpha", 0, 25), alt=15), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "alpha")),
               lambda c: [_go("charlie", c.point("alpha", 0, 25), 15)], "Charlie schwebt 25 m östlich von alpha auf 15 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("placement", "dev", "place3-charlie-west-of-bravo-home", three,
               "Send bravo 30 m north at 10 m, then bring charlie to hover 12 m west of the spot bravo took off "
               "from, at 16 m.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 30, 0), alt=10), airborne_at(ev, "bravo", 10),
                                  at(ev, "charlie", *c.point("bravo", 0, -12), alt=16), airborne_at(ev, "charlie", 16),
                                  never_armed(ev, "alpha")),
               lambda c: [_move("bravo", 30, 0, alt=10), _go("charlie", c.point("bravo", 0, -12), 16)],
               "Bravo hovers 30 m north at 10 m; charlie 12 m west of bravo's home at 16 m."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("placement", "dev", "place3-bravo-midway", three,
               "Fly alpha 40 m north and charlie 40 m east, both at 15 m; then bring bravo to the point halfway "
               "between them, also at 15 m.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 40, 0), alt=15), airborne_at(ev, "alpha", 15),
                                  at(ev, "charlie", *c.point("charlie", 0, 40), alt=15), airborne_at(ev, "charlie", 15),
                                  at(ev, "bravo", *_midpoint(c.point("alpha", 40, 0), c.point("charlie", 0, 40)), alt=15),
                                  airborne_at(ev, "bravo", 15)),
               lambda c: [_move("alpha", 40, 0, alt=15), _move("charlie", 0, 40, alt=15),
                          _go("bravo", _midpoint(c.point("alpha", 40, 0), c.point("charlie", 0, 40)), 15)],
               "Alpha hovers 40 m north, charlie 40 m east, bravo halfway between them, all at 15 m."),
        # language
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("language", "dev", "lang3-de-alpha-southeast-land", ("alpha",),
               "Flieg alpha auf 18 m Höhe 30 m nach Südosten und lande ihn dort.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 18), at(ev, "alpha", *c.point("alpha", -diag30, diag30)),
                                  landed_disarmed(ev, "alpha")),
               [_move("alpha", -diag30, diag30, alt=18), _land("alpha")], "Alpha ist 30 m nach Südosten geflogen und gelandet."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("language", "dev", "lang3-es-charlie-west-home", ("charlie",),
               "Despega a charlie hasta 12 metros, llévalo 40 metros al oeste y después tráelo de vuelta a casa.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, -40)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), _move("charlie", 0, -40), _rtl("charlie")],
               "Charlie voló 40 m al oeste y volvió a casa."),
        # moved to dev on 2026-11-30, third round: the test half had been measured
        _entry("language", "dev", "lang3-nl-bravo-north-land", ("bravo",),
               "Laat bravo naar 16 meter stijgen, 20 meter naar het noorden vliegen en daarna landen.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 16), at(ev, "bravo", *c.point("bravo", 20, 0)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 16), _move("bravo", 20, 0), _land("bravo")],
               "Bravo is naar 16 m gestegen, 20 m naar het noorden gevlogen en geland."),
    ]  # fmt: skip


def _fourth_round() -> list[CorpusEntry]:
    """The test half written on 2026-11-30 (fourth round), before any model ran on it: 3 a class; all of
    it moved to dev later on 2026-11-30 (fourth round), once its figures had been measured."""
    three = DRONES
    d25, d30 = 25 / math.sqrt(2), 30 / math.sqrt(2)
    square60ft = _polygon_legs(4, 60 * FT, 0.0, right=True)  # north first, turning right
    pentagon20 = _polygon_legs(5, 20.0, 0.0, right=True)  # north first, turning right
    survey = [(0.0, 25.0), (6.0, 0.0), (0.0, -25.0), (6.0, 0.0)] * 2 + [
        (0.0, 25.0)
    ]  # five passes, east first
    # counter-clockwise around the spot 30 m north of home, 15 m out, from its south side: S, E, N, W, S
    orbit = [(15.0, 0.0), (30.0, 15.0), (45.0, 0.0), (30.0, -15.0), (15.0, 0.0)]
    return [
        # single
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("single", "dev", "single4-pl-bravo-aloft", ("bravo",),
               "Poderwij bravo na 17 metrów i zostaw go w powietrzu.",
               lambda c, ev: airborne_at(ev, "bravo", 17),
               [_takeoff("bravo", 17)], "Bravo wisi na 17 m."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("single", "dev", "single4-charlie-wheels-up", ("charlie",),
               "Charlie: wheels up, climb out to 23 metres and loiter there.",
               lambda c, ev: airborne_at(ev, "charlie", 23),
               [_takeoff("charlie", 23)], "Charlie hovers at 23 m."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("single", "dev", "single4-alpha-vertical-test", ("alpha",),
               "Give alpha a short vertical test: lift to sixteen metres, then touch down again.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 16), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 16), _land("alpha")], "Alpha went up to 16 m and landed."),
        # multi
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("multi", "dev", "multi4-fr-three-heights", three,
               "Fais décoller les trois drones : alpha à 8 m, bravo à 12 m, charlie à 16 m, et laisse-les en l'air.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 8), airborne_at(ev, "bravo", 12),
                                  airborne_at(ev, "charlie", 16)),
               [_takeoff("alpha", 8), _takeoff("bravo", 12), _takeoff("charlie", 16)],
               "Alpha est à 8 m, bravo à 12 m, charlie à 16 m."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("multi", "dev", "multi4-pl-all-but-bravo", three,
               "Wszystkie drony oprócz bravo wznieś na 13 metrów i zostaw je w powietrzu.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 13), airborne_at(ev, "charlie", 13),
                                  never_armed(ev, "bravo")),
               [_takeoff("alpha", 13), _takeoff("charlie", 13)], "Alpha i charlie wiszą na 13 m; bravo stoi."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("multi", "dev", "multi4-each-in-turn", three,
               "One after the other, take each drone up to 9 m and back down: charlie first, then alpha, then bravo.",
               lambda c, ev: _all(*(reached_alt(ev, d, 9) for d in three), *(landed_disarmed(ev, d) for d in three)),
               [_takeoff("charlie", 9), _land("charlie"), _takeoff("alpha", 9), _land("alpha"), _takeoff("bravo", 9),
                _land("bravo")], "Charlie, alpha and bravo each went up to 9 m and landed."),
        # compound
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("compound", "dev", "compound4-bravo-leg-three-times", ("bravo",),
               "Take off bravo to 8 m and fly 15 m east, then repeat that same leg twice more and land.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, 15), c.point("bravo", 0, 30)]),
                                  at(ev, "bravo", *c.point("bravo", 0, 45)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 8), *_legs("bravo", [(0.0, 15.0)] * 3), _land("bravo")],
               "Bravo flew three 15 m legs east and landed 45 m east."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("compound", "dev", "compound4-it-alpha-first-turn", ("alpha",),
               "Porta alpha a 12 metri, vai 35 metri verso est, poi 15 metri verso nord; poi torna al primo punto "
               "di svolta e atterra lì.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 35), c.point("alpha", 15, 35)]),
                                  at(ev, "alpha", *c.point("alpha", 0, 35)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), _move("alpha", 0, 35), _move("alpha", 15, 0), _move("alpha", -15, 0),
                _land("alpha")], "Alpha è andato 35 m a est e 15 m a nord, è tornato alla svolta ed è atterrato."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("compound", "dev", "compound4-charlie-past-home", ("charlie",),
               "Take charlie out 30 m east at 10 m, turn around, fly 50 m west and land.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 30)]),
                                  at(ev, "charlie", *c.point("charlie", 0, -20)), landed_disarmed(ev, "charlie")),
               [_move("charlie", 0, 30, alt=10), _move("charlie", 0, -50), _land("charlie")],
               "Charlie went 30 m east, then 50 m west, and landed 20 m west of home."),
        # conditional
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("conditional", "dev", "cond4-pt-bravo-at-least", ("bravo",),
               "Se o bravo tiver pelo menos 45 % de bateria, leva-o a 12 metros de altura e 20 metros para norte e "
               "deixa-o lá; caso contrário, não o descoles e diz-me quanto tem.",
               lambda c, ev: _all(never_armed(ev, "bravo"), answer_mentions_number(ev, 39, 2)),
               [_battery("bravo")], "O bravo tem 39 %, por isso fica em terra.", battery={"bravo": 39.0}),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("conditional", "dev", "cond4-bravo-if-fuller-than-alpha", three,
               "Take alpha up to 10 m. Then, if bravo has more charge than alpha, send bravo up to 10 m as well; "
               "if not, bravo stays on the ground.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 10), never_armed(ev, "bravo"), never_armed(ev, "charlie")),
               [_takeoff("alpha", 10), _battery("alpha"), _battery("bravo")],
               "Alpha hovers at 10 m; bravo has less charge (55 % against 80 %), so it stays down.",
               battery={"alpha": 80.0, "bravo": 55.0}),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("conditional", "dev", "cond4-pl-charlie-unless-low", ("charlie",),
               "Jeśli charlie ma mniej niż 35 % baterii, zostaw go na ziemi i podaj mi poziom; w przeciwnym razie "
               "wznieś go na 14 m, przeleć nim 25 m na zachód i zostaw go tam.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, -25), alt=14), airborne_at(ev, "charlie", 14)),
               [_battery("charlie"), _move("charlie", 0, -25, alt=14)],
               "Charlie ma 48 %, więc wisi 25 m na zachód na 14 m.", battery={"charlie": 48.0}),
        # formation
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("formation", "dev", "form4-es-column-northwest", three,
               "Pon a los tres drones en columna, uno detrás de otro, con 9 m entre cada uno, a 12 m de altura y "
               "30 m al noroeste de donde están.",
               lambda c, ev: _all(formation_at(c, ev, three, 12, 9, d30, -d30), farthest_apart(ev, three, 18)),
               [_formation(three, "column", 12, 9, north=d30, east=-d30)],
               "Los tres están en columna 30 m al noroeste, a 12 m."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("formation", "dev", "form4-pair-feet-east", ("alpha", "bravo"),
               "Form alpha and bravo into a line 40 feet apart at 60 feet, 30 m east of where they are.",
               lambda c, ev: formation_at(c, ev, ("alpha", "bravo"), 60 * FT, 40 * FT, 0, 30),
               [_formation(("alpha", "bravo"), "line", 60 * FT, 40 * FT, east=30)],
               "Alpha and bravo hold a line 40 ft apart at 60 ft, 30 m east."),
        # (the gateway's V: two wings 10 m from the lead, 45 degrees off its axis: 2 x 10 x sin 45 = 14.14 m apart)
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("formation", "dev", "form4-de-wedge-north", three,
               "Die drei Drohnen sollen als Keil auf 20 m Höhe fliegen, 10 m Abstand zwischen Spitze und jedem "
               "Flügel, 35 m nördlich von ihrem jetzigen Standort.",
               lambda c, ev: _all(formation_at(c, ev, three, 20, 10, 35, 0), farthest_apart(ev, three, 14.14)),
               [_formation(three, "wedge", 20, 10, north=35)], "Die drei fliegen als Keil 35 m nördlich auf 20 m."),
        # relative
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("relative", "dev", "rel4-nl-charlie-southeast", ("charlie",),
               "Vlieg charlie 30 meter naar het zuidoosten op 12 meter hoogte en laat hem daar hangen.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -d30, d30), alt=12),
                                  airborne_at(ev, "charlie", 12)),
               [_move("charlie", -d30, d30, alt=12)], "Charlie hangt 30 m naar het zuidoosten op 12 m."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("relative", "dev", "rel4-alpha-bearing", ("alpha",),
               "Alpha: fly 40 m on a bearing of 060 degrees at 15 m and hover there.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 34.64), alt=15), airborne_at(ev, "alpha", 15)),
               [_move("alpha", 20, 34.64, alt=15)], "Alpha hovers 40 m away on a bearing of 060 at 15 m."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("relative", "dev", "rel4-bravo-further-lower", ("bravo",),
               "Take bravo up to 10 m and 20 m north; from there, go a further 15 m north and 10 m west, coming "
               "down 4 m on the way.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 20, 0)]),
                                  at(ev, "bravo", *c.point("bravo", 35, -10), alt=6), airborne_at(ev, "bravo", 6)),
               [_move("bravo", 20, 0, alt=10), _move("bravo", 15, -10, up=-4)],
               "Bravo hovers 35 m north and 10 m west at 6 m."),
        # question
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("question", "dev", "ask4-fr-ground-and-weakest", three,
               "Est-ce que tous les drones sont au sol ? Et lequel a la batterie la plus faible ?",
               lambda c, ev: _all(answer_says(ev, r"\bcharlie\b", "charlie"), answer_mentions_number(ev, 41, 2),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Oui, tous sont au sol ; charlie a la batterie la plus faible (41 %).",
               battery={"alpha": 74.0, "bravo": 68.0, "charlie": 41.0}),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("question", "dev", "ask4-bravo-and-which-other", three,
               "Give me bravo's charge, and tell me which of the other two has more.",
               lambda c, ev: _all(answer_mentions_number(ev, 66, 1), answer_says(ev, r"\bcharlie\b", "charlie"),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Bravo has 66 %; of the other two, charlie has more (83 % against 52 %).",
               battery={"alpha": 52.0, "bravo": 66.0, "charlie": 83.0}),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("question", "dev", "ask4-de-bravo-charge-flying", ("bravo",),
               "Wie viel Akku hat bravo noch, und fliegt er gerade?",
               lambda c, ev: _all(answer_mentions_number(ev, 63, 2),
                                  answer_says(ev, r"\b(no|not|nein|nicht|ground|boden|landed|gelandet)\b",
                                              "that it is not flying"), never_armed(ev, "bravo")),
               [("get_position", {"drone_id": "bravo"}), _battery("bravo")],
               "Bravo hat 63 % und steht am Boden.", battery={"bravo": 63.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off)
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("refusal", "dev", "refuse4-bravo-far-west-of-charlie", three,
               "Put bravo 1.1 km west of charlie, at 20 m.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "bravo", c.max_distance_m), answer_reports_refusal(ev)),
               lambda c: [_go("bravo", c.point("charlie", 0, -1100), 20)],
               "The gateway refused: that point is about 1095 m from bravo's home, beyond the 1000 m limit."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("refusal", "dev", "refuse4-nl-row-450ft", three,
               "Zet alle drie de drones in een rij op 450 voet hoogte, 10 meter uit elkaar.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"),
                                  *(max_alt_at_most(ev, d, c.max_alt_m) for d in three), answer_reports_refusal(ev)),
               [_formation(three, "line", 450 * FT, 10)],
               "The gateway refused: 450 ft (137 m) is above the 120 m altitude limit."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("refusal", "dev", "refuse4-it-charlie-circle-flat", ("charlie",),
               "Fai volare charlie in cerchio attorno al suo punto di decollo, 20 metri di raggio, a 10 metri di "
               "quota.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "charlie"), answer_reports_refusal(ev)),
               [_takeoff("charlie", 10)], "The gateway refused: charlie's battery is below the takeoff minimum.",
               battery={"charlie": 22.0}),
        # units
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("units", "dev", "units4-charlie-square-feet", ("charlie",),
               "Charlie at 40 ft: fly a square with 60-foot sides, north first and turning right, then land where "
               "it started.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 40 * FT),
                                  visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(square60ft)[:3]]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 40 * FT), *_legs("charlie", square60ft), _land("charlie")],
               "Charlie flew the 60 ft square at 40 ft and landed."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("units", "dev", "units4-alpha-quarter-km", ("alpha",),
               "Lift alpha to 50 ft, take it a quarter of a kilometre south, and set it down there.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 50 * FT), at(ev, "alpha", *c.point("alpha", -250, 0)),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 50 * FT), _move("alpha", -250, 0), _land("alpha")],
               "Alpha climbed to 50 ft, flew 250 m south and landed."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("units", "dev", "units4-pl-bravo-feet-down", ("bravo",),
               "Bravo: wznieś się na 35 stóp, przeleć 200 stóp na północ, potem obniż się o 15 stóp i zawiśnij tam.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 35 * FT),
                                  at(ev, "bravo", *c.point("bravo", 200 * FT, 0), alt=20 * FT),
                                  airborne_at(ev, "bravo", 20 * FT)),
               [_takeoff("bravo", 35 * FT), _move("bravo", 200 * FT, 0), _move("bravo", up=-15 * FT)],
               "Bravo wisi 200 stóp na północ na 20 stopach."),
        # pattern
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("pattern", "dev", "pattern4-charlie-orbit-spot-north", ("charlie",),
               "Charlie at 12 m: orbit the spot 30 m north of its home once, 15 m radius, counter-clockwise starting "
               "from the south side of it; then land back home.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in orbit]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), *_legs("charlie", [(15.0, 0.0), (15.0, 15.0), (15.0, -15.0), (-15.0, -15.0),
                                                            (-15.0, 15.0)]), _rtl("charlie")],
               "Charlie orbited the spot 30 m north and came home."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("pattern", "dev", "pattern4-de-bravo-five-passes", ("bravo",),
               "Bravo soll auf 15 m Höhe ein Feld abfliegen: fünf Bahnen zu je 25 m, die erste nach Osten, dann "
               "abwechselnd hin und zurück, 6 m Abstand zwischen den Bahnen, jede weitere Bahn nördlich der vorigen; "
               "danach landen.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(survey)]),
                                  at(ev, "bravo", *c.point("bravo", 24, 25)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 15), *_legs("bravo", survey), _land("bravo")],
               "Bravo ist die fünf Bahnen abgeflogen und gelandet."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("pattern", "dev", "pattern4-pt-alpha-pentagon", ("alpha",),
               "O alpha deve voar um pentágono de 20 metros de lado a 10 metros de altura, com o primeiro lado para "
               "norte e virando sempre à direita, e no fim ficar a pairar no ponto de partida.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(pentagon20)[:4]]),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=10), airborne_at(ev, "alpha", 10)),
               [_takeoff("alpha", 10), *_legs("alpha", pentagon20)], "O alpha voou o pentágono e paira no início."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: a drone placed
        # from itself, or from the other drone's home instead of where it flew, misses by 10 m or more)
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("placement", "dev", "place4-charlie-parked-south-of-alpha", three,
               "Park charlie on the ground 15 m south of alpha.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("alpha", -15, 0)), landed_disarmed(ev, "charlie"),
                                  never_armed(ev, "alpha")),
               lambda c: [_go("charlie", c.point("alpha", -15, 0), 10), _land("charlie")],
               "Charlie landed 15 m south of alpha."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("placement", "dev", "place4-es-charlie-west-north-of-alpha", three,
               "Coloca a charlie 20 metros al oeste y 10 metros al norte de alpha, a 14 metros de altura, y déjalo "
               "ahí.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("alpha", 10, -20), alt=14), airborne_at(ev, "charlie", 14),
                                  never_armed(ev, "alpha")),
               lambda c: [_go("charlie", c.point("alpha", 10, -20), 14)],
               "Charlie está 20 m al oeste y 10 m al norte de alpha, a 14 m."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("placement", "dev", "place4-it-charlie-southwest-of-moved-alpha", three,
               "Porta alpha 30 metri a nord a 15 metri di quota. Poi metti charlie 20 metri a sud-ovest di alpha, "
               "alla stessa quota, e lasciali lì entrambi.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 30, 0), alt=15), airborne_at(ev, "alpha", 15),
                                  at(ev, "charlie", *c.point("alpha", 30 - 20 / math.sqrt(2), -20 / math.sqrt(2)), alt=15),
                                  airborne_at(ev, "charlie", 15), never_armed(ev, "bravo")),
               lambda c: [_move("alpha", 30, 0, alt=15),
                          _go("charlie", c.point("alpha", 30 - 20 / math.sqrt(2), -20 / math.sqrt(2)), 15)],
               "Alpha è 30 m a nord a 15 m; charlie 20 m a sud-ovest di alpha, alla stessa quota."),
        # language
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("language", "dev", "lang4-pl-bravo-northwest-land", ("bravo",),
               "Wystartuj bravo na 14 metrów, przeleć nim 25 metrów na północny zachód i wyląduj tam.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 14), at(ev, "bravo", *c.point("bravo", d25, -d25)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 14), _move("bravo", d25, -d25), _land("bravo")],
               "Bravo przeleciał 25 m na północny zachód i wylądował."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("language", "dev", "lang4-pt-charlie-climb-more-land", ("charlie",),
               "Põe o charlie a 20 metros de altura, sobe mais 10 metros e depois desce para aterrar.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 30), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 20), _move("charlie", up=10), _land("charlie")],
               "O charlie subiu a 20 m, depois a 30 m, e aterrou."),
        # moved to dev on 2026-11-30, fourth round: the test half had been measured
        _entry("language", "dev", "lang4-nl-pair-up-one-lands", three,
               "Breng alpha en charlie allebei naar 12 meter en laat daarna alleen charlie landen.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 12), reached_alt(ev, "charlie", 12),
                                  landed_disarmed(ev, "charlie"), never_armed(ev, "bravo")),
               [_takeoff("alpha", 12), _takeoff("charlie", 12), _land("charlie")],
               "Alpha hangt op 12 m; charlie is naar 12 m gegaan en geland."),
    ]  # fmt: skip


def landed_formation_at(
    c: MissionContext, ev: Evidence, drones: tuple[str, ...], spacing: float, north: float, east: float
) -> Check:
    """Every drone landed and disarmed; the two farthest apart ``spacing`` apart (±3 m); the drones' centre
    ``north``/``east`` metres from the centre of their homes: a formation flown out and set down."""
    home_lat = sum(c.homes[d][0] for d in drones) / len(drones)
    home_lon = sum(c.homes[d][1] for d in drones) / len(drones)
    want = offset_position(home_lat, home_lon, north, east)
    off = horizontal_distance_m(*_centroid([ev.final[d] for d in drones]), *want)
    return _all(
        *(landed_disarmed(ev, d) for d in drones),
        farthest_apart(ev, drones, spacing),
        Check(off <= HORIZONTAL_TOL_M, f"formation centre {off:.1f} m from where it was asked"),
    )


def _fifth_round() -> list[CorpusEntry]:
    """The test half written on 2026-11-30 (fifth round), before any model ran on it: 3 a class; all of
    it moved to dev later on 2026-11-30 (fifth round), once its figures had been measured."""
    three = DRONES
    octagon10 = _polygon_legs(8, 10.0, 90.0, right=False)  # first side east, turning left
    # four passes of 35 m, the first west, 7 m apart, each next pass south of the one before
    mow = [(0.0, -35.0), (-7.0, 0.0), (0.0, 35.0), (-7.0, 0.0), (0.0, -35.0), (-7.0, 0.0), (0.0, 35.0)]
    # clockwise twice round the spot 20 m east of home, 10 m out, from its west side: W, N, E, S, W (x2)
    ring = [(0.0, 10.0), (10.0, 20.0), (0.0, 30.0), (-10.0, 20.0)]
    lap = [(10.0, 10.0), (-10.0, 10.0), (-10.0, -10.0), (10.0, -10.0)]
    return [
        # single
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("single", "dev", "single5-sv-charlie-hover", ("charlie",),
               "Lyft charlie till 21 meter och låt den sväva kvar där.",
               lambda c, ev: airborne_at(ev, "charlie", 21),
               [_takeoff("charlie", 21)], "Charlie svävar på 21 m."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("single", "dev", "single5-cs-alpha-up-down", ("alpha",),
               "Dron alpha ať vzlétne do 11 metrů a pak hned zase přistane.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 11), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 11), _land("alpha")], "Alpha vzlétla do 11 m a přistála."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("single", "dev", "single5-bravo-report-height", ("bravo",),
               "Climb bravo to 27 m and tell me its altitude once it's up there; it stays in the air.",
               lambda c, ev: _all(airborne_at(ev, "bravo", 27), answer_mentions_number(ev, 27, 3)),
               [_takeoff("bravo", 27), ("get_position", {"drone_id": "bravo"})], "Bravo is up at 27 m."),
        # multi
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("multi", "dev", "multi5-sv-alpha-lands-charlie-stays", three,
               "Alpha ska flyga 20 meter österut på 10 meters höjd och landa där, medan charlie stiger till 15 "
               "meter och stannar i luften. Bravo rör sig inte.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 20)), landed_disarmed(ev, "alpha"),
                                  airborne_at(ev, "charlie", 15), never_armed(ev, "bravo")),
               [_move("alpha", 0, 20, alt=10), _land("alpha"), _takeoff("charlie", 15)],
               "Alpha landade 20 m österut; charlie svävar på 15 m."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("multi", "dev", "multi5-each-north-of-own-pad", three,
               "Send each drone 15 m north of its own pad at 12 m and leave them there.",
               lambda c, ev: _all(*(at(ev, d, *c.point(d, 15, 0), alt=12) for d in three),
                                  *(airborne_at(ev, d, 12) for d in three)),
               [_move(d, 15, 0, alt=12) for d in three], "All three hover 15 m north of their pads at 12 m."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("multi", "dev", "multi5-es-pair-south-hover", three,
               "Manda alpha y charlie 25 metros al sur a 12 metros de altura y déjalos ahí flotando; bravo se "
               "queda en tierra.",
               lambda c, ev: _all(*(at(ev, d, *c.point(d, -25, 0), alt=12) for d in ("alpha", "charlie")),
                                  *(airborne_at(ev, d, 12) for d in ("alpha", "charlie")), never_armed(ev, "bravo")),
               [_move("alpha", -25, 0, alt=12), _move("charlie", -25, 0, alt=12)],
               "Alpha y charlie flotan 25 m al sur a 12 m; bravo sigue en tierra."),
        # compound
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("compound", "dev", "compound5-fr-bravo-back-over-start", ("bravo",),
               "Bravo : décolle à 12 m, file 30 m au nord, puis 30 m à l'est, et reviens en ligne droite "
               "au-dessus de ton point de départ ; reste en l'air là, à 12 m.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 30, 0), c.point("bravo", 30, 30)]),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=12), airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 12), _move("bravo", 30, 0), _move("bravo", 0, 30), _move("bravo", -30, -30)],
               "Bravo est allé 30 m au nord, 30 m à l'est, et se tient au-dessus de son départ à 12 m."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("compound", "dev", "compound5-alpha-two-steps-down", ("alpha",),
               "Alpha: take off to 24 m. Then, twice: fly 15 m west and drop 8 m. Leave it hovering at the end.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 24), visited(ev, "alpha", [c.point("alpha", 0, -15)]),
                                  at(ev, "alpha", *c.point("alpha", 0, -30), alt=8), airborne_at(ev, "alpha", 8)),
               [_takeoff("alpha", 24), _move("alpha", 0, -15), _move("alpha", up=-8), _move("alpha", 0, -15),
                _move("alpha", up=-8)], "Alpha hovers 30 m west at 8 m."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("compound", "dev", "compound5-de-charlie-u-turn", ("charlie",),
               "Charlie: auf 10 m steigen, 20 m nach Süden, 20 m nach Westen, 20 m nach Norden, und dann dort "
               "landen, wo er gerade ist.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -20, 0), c.point("charlie", -20, -20)]),
                                  at(ev, "charlie", *c.point("charlie", 0, -20)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", -20, 0), _move("charlie", 0, -20), _move("charlie", 20, 0),
                _land("charlie")], "Charlie ist 20 m westlich von seinem Start gelandet."),
        # conditional
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("conditional", "dev", "cond5-it-alpha-three-tiers", ("alpha",),
               "Controlla la batteria di alpha: sopra l'80 % portalo 50 metri a nord, tra il 50 e l'80 % solo 20 "
               "metri a nord, sotto il 50 % lascialo a terra. Se vola, a 10 metri di quota, e poi lascialo lì.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 0), alt=10), airborne_at(ev, "alpha", 10)),
               [_battery("alpha"), _move("alpha", 20, 0, alt=10)],
               "Alpha ha il 66 %, quindi è 20 m a nord a 10 m.", battery={"alpha": 66.0}),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("conditional", "dev", "cond5-pt-charlie-twenty-points-more", three,
               "Se a bateria do charlie tiver pelo menos 20 pontos a mais do que a do bravo, manda o charlie 20 "
               "metros para leste a 10 metros de altura; senão, manda o bravo. O que for fica lá a pairar.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, 20), alt=10), airborne_at(ev, "bravo", 10),
                                  never_armed(ev, "charlie"), never_armed(ev, "alpha")),
               [_battery("charlie"), _battery("bravo"), _move("bravo", 0, 20, alt=10)],
               "O charlie tem 71 % e o bravo 58 %: só 13 pontos, por isso o bravo paira 20 m a leste a 10 m.",
               battery={"bravo": 58.0, "charlie": 71.0}),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("conditional", "dev", "cond5-nl-low-ones-stay", three,
               "Laat elke drone met minder dan 40 % batterij aan de grond staan; de rest gaat naar 9 meter en "
               "landt daarna meteen weer.",
               lambda c, ev: _all(never_armed(ev, "alpha"), *(reached_alt(ev, d, 9) for d in ("bravo", "charlie")),
                                  *(landed_disarmed(ev, d) for d in ("bravo", "charlie"))),
               [("fleet_status", {}), _takeoff("bravo", 9), _takeoff("charlie", 9), _land("bravo"), _land("charlie")],
               "Alpha (35 %) blijft staan; bravo en charlie gingen naar 9 m en zijn geland.",
               battery={"alpha": 35.0, "bravo": 77.0, "charlie": 52.0}),
        # formation
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("formation", "dev", "form5-sv-row-west", three,
               "Ställ alla tre drönarna på rad, 7 meter mellan varje, på 14 meters höjd, 20 meter väster om där "
               "de står.",
               lambda c, ev: _all(formation_at(c, ev, three, 14, 7, 0, -20), farthest_apart(ev, three, 14)),
               [_formation(three, "line", 14, 7, east=-20)], "De tre står på rad 20 m västerut på 14 m."),
        # (the gateway's V: two wings 8 m from the lead, 45 degrees off its axis: 2 x 8 x sin 45 = 11.31 m apart)
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("formation", "dev", "form5-es-wedge-south", three,
               "Los tres drones en cuña a 16 metros de altura, 8 metros entre la punta y cada ala, 40 metros al "
               "sur de donde están.",
               lambda c, ev: _all(formation_at(c, ev, three, 16, 8, -40, 0), farthest_apart(ev, three, 11.31)),
               [_formation(three, "wedge", 16, 8, north=-40)], "Los tres vuelan en cuña 40 m al sur a 16 m."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("formation", "dev", "form5-pair-abreast-west-land", ("alpha", "charlie"),
               "Fly alpha and charlie out side by side, 20 m apart at 12 m, 50 m west of where they are, and "
               "land them both there.",
               lambda c, ev: landed_formation_at(c, ev, ("alpha", "charlie"), 20, 0, -50),
               [_formation(("alpha", "charlie"), "line", 12, 20, east=-50), _land("alpha"), _land("charlie")],
               "Alpha and charlie flew 50 m west side by side, 20 m apart, and landed."),
        # relative
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("relative", "dev", "rel5-pl-charlie-south-east-climb", ("charlie",),
               "Dron charlie: leć 18 m na południe i 24 m na wschód na wysokości 11 m, potem wznieś się o 7 m i "
               "zawiśnij tam.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -18, 24), alt=18),
                                  airborne_at(ev, "charlie", 18)),
               [_move("charlie", -18, 24, alt=11), _move("charlie", up=7)], "Charlie wisi 18 m na południe i 24 m "
               "na wschód, na 18 m."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("relative", "dev", "rel5-alpha-half-that-west", ("alpha",),
               "Alpha, move 30 m toward the north and then half that distance toward the west, at 14 m, and stay.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 30, -15), alt=14), airborne_at(ev, "alpha", 14)),
               [_move("alpha", 30, 0, alt=14), _move("alpha", 0, -15)], "Alpha hovers 30 m north and 15 m west at 14 m."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("relative", "dev", "rel5-sv-bravo-out-back-lower", ("bravo",),
               "Flytta bravo 35 meter norrut på 16 meters höjd, sedan 35 meter söderut igen men 6 meter lägre, "
               "och låt den sväva där.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 35, 0)], alt=16),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=10), airborne_at(ev, "bravo", 10)),
               [_move("bravo", 35, 0, alt=16), _move("bravo", -35, 0, up=-6)],
               "Bravo svävar ovanför sin start på 10 m."),
        # question
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("question", "dev", "ask5-it-which-over-half", three,
               "Quali droni hanno almeno il 50 % di batteria? Non farli volare.",
               lambda c, ev: _all(answer_says(ev, r"\balpha\b", "alpha"), answer_mentions_number(ev, 62, 1),
                                  answer_says(ev, r"\bcharlie\b", "charlie"), answer_mentions_number(ev, 81, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Alpha (62 %) e charlie (81 %); bravo ha il 47 %.",
               battery={"alpha": 62.0, "bravo": 47.0, "charlie": 81.0}),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("question", "dev", "ask5-pl-two-drones-height-charge", three,
               "Ile baterii mają bravo i charlie i na jakiej są wysokości? Tylko pytam, niczego nie uruchamiaj.",
               lambda c, ev: _all(answer_mentions_number(ev, 69, 1), answer_mentions_number(ev, 92, 1),
                                  nobody_armed(ev)),
               [("get_position", {"drone_id": "bravo"}), ("get_position", {"drone_id": "charlie"})],
               "Bravo ma 69 %, charlie 92 %; oba stoją na ziemi (0 m).",
               battery={"alpha": 58.0, "bravo": 69.0, "charlie": 92.0}),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("question", "dev", "ask5-status-before-start", three,
               "Quick status before we start: what is each drone's altitude and charge? Don't launch anything.",
               lambda c, ev: _all(*(answer_mentions_number(ev, pct, 1) for pct in (88, 61, 34)), nobody_armed(ev)),
               [("get_position", {})], "All three are on the ground; alpha has 88 %, bravo 61 %, charlie 34 %.",
               battery={"alpha": 88.0, "bravo": 61.0, "charlie": 34.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("refusal", "dev", "refuse5-de-bravo-miles-and-back", ("bravo",),
               "Flieg bravo auf 15 m Höhe 0,7 Meilen nach Norden und dann wieder zurück.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "bravo", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("bravo", 0.7 * MI, 0, alt=15)],
               "The gateway refused: 0.7 miles (1127 m) is beyond the 1000 m limit."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("refusal", "dev", "refuse5-charlie-steps-to-150", ("charlie",),
               "Take charlie up in 25 m steps, pausing at each, until it is at 150 m.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "charlie", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("charlie", 25), *(_move("charlie", up=25) for _ in range(4))],
               "Charlie climbed to 100 m; the step to 125 m was refused: above the 120 m altitude limit."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("refusal", "dev", "refuse5-fr-alpha-skim", ("alpha",),
               "Fais voler alpha 30 m vers le nord en rase-mottes, à 50 cm du sol.",
               lambda c, ev: _all(refusal_seen(ev, "minimum", "at least"), never_armed(ev, "alpha"),
                                  answer_reports_refusal(ev)),
               [_move("alpha", 30, 0, alt=0.5)], "The gateway refused: 0.5 m is below the 2 m minimum altitude."),
        # units
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("units", "dev", "units5-nl-charlie-feet-west", ("charlie",),
               "Laat charlie opstijgen tot 45 voet, vlieg 100 voet naar het westen en laat hem daar hangen.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, -100 * FT), alt=45 * FT),
                                  airborne_at(ev, "charlie", 45 * FT)),
               [_takeoff("charlie", 45 * FT), _move("charlie", 0, -100 * FT)],
               "Charlie hangt 100 voet naar het westen op 45 voet."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("units", "dev", "units5-alpha-ft-miles", ("alpha",),
               "Take alpha to 66 ft, fly it 0.03 miles east, and leave it hovering.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 0.03 * MI), alt=66 * FT),
                                  airborne_at(ev, "alpha", 66 * FT)),
               [_takeoff("alpha", 66 * FT), _move("alpha", 0, 0.03 * MI)], "Alpha hovers 0.03 mi east at 66 ft."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("units", "dev", "units5-pt-bravo-feet-then-metres", ("bravo",),
               "Sobe o bravo a 30 pés, avança 120 pés para norte, depois sobe até aos 20 metros e aterra aí "
               "mesmo.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 120 * FT, 0)], alt=30 * FT),
                                  reached_alt(ev, "bravo", 20), at(ev, "bravo", *c.point("bravo", 120 * FT, 0)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 30 * FT), _move("bravo", 120 * FT, 0), _move("bravo", alt=20), _land("bravo")],
               "O bravo avançou 120 pés para norte, subiu a 20 m e aterrou."),
        # pattern
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("pattern", "dev", "pattern5-fr-alpha-octagon", ("alpha",),
               "Alpha à 12 m : un octogone de 10 m de côté, premier côté vers l'est, en tournant à gauche, puis "
               "pose-toi là où tu as commencé.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(octagon10)[:5]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), *_legs("alpha", octagon10), _land("alpha")],
               "Alpha a volé l'octogone et s'est posé à son départ."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("pattern", "dev", "pattern5-bravo-mow-south", ("bravo",),
               "Bravo, mow the field at 8 m: four passes of 35 m, the first heading west, 7 m apart, each next pass "
               "south of the last; then come home.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(mow)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 8), *_legs("bravo", mow), _rtl("bravo")],
               "Bravo flew the four passes and came home."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("pattern", "dev", "pattern5-cs-charlie-two-laps", ("charlie",),
               "Dron charlie: ve výšce 14 m obleť dvakrát kruh o poloměru 10 m kolem místa 20 m východně od "
               "svého startu, po směru hodinových ručiček, začni na západní straně, a pak zůstaň viset nad "
               "startem.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in [*ring, *ring, ring[0]]]),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=14), airborne_at(ev, "charlie", 14)),
               [_takeoff("charlie", 14), _move("charlie", 0, 10), *_legs("charlie", lap * 2), _move("charlie", 0, -10)],
               "Charlie obletěl kruh dvakrát a visí nad startem ve 14 m."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each places alpha
        # from charlie, so alpha placed from itself, or from where charlie took off instead of where it flew,
        # misses by 10 m or more)
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("placement", "dev", "place5-alpha-stacked-over-charlie", three,
               "Send charlie 20 m east at 12 m. Then stack alpha right above charlie, 10 m higher.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 20), alt=12), airborne_at(ev, "charlie", 12),
                                  at(ev, "alpha", *c.point("charlie", 0, 20), alt=22), airborne_at(ev, "alpha", 22),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("charlie", 0, 20, alt=12), _go("alpha", c.point("charlie", 0, 20), 22)],
               "Charlie hovers 20 m east at 12 m, alpha right above it at 22 m."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("placement", "dev", "place5-de-alpha-over-charlie-pad", three,
               "Flieg charlie auf 10 m 30 m nach Süden und lass ihn dort. Dann bring alpha auf 12 m genau über die "
               "Stelle, von der charlie gestartet ist.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -30, 0), alt=10), airborne_at(ev, "charlie", 10),
                                  at(ev, "alpha", *_home(c, "charlie"), alt=12), airborne_at(ev, "alpha", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("charlie", -30, 0, alt=10), _go("alpha", _home(c, "charlie"), 12)],
               "Charlie schwebt 30 m südlich auf 10 m; alpha schwebt auf 12 m über charlies Startplatz."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("placement", "dev", "place5-cs-alpha-lands-north-of-charlie", three,
               "Charlie vzlétne do 10 m, přeletí 20 m na východ a zůstane tam. Potom ať alpha přistane 15 m "
               "severně od místa, kde charlie visí.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 20), alt=10), airborne_at(ev, "charlie", 10),
                                  at(ev, "alpha", *c.point("charlie", 15, 20)), landed_disarmed(ev, "alpha"),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("charlie", 0, 20, alt=10), _go("alpha", c.point("charlie", 15, 20), 10),
                          _land("alpha")],
               "Charlie visí 20 m východně v 10 m; alpha přistála 15 m severně od něj."),
        # language
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("language", "dev", "lang5-sv-bravo-east-home", ("bravo",),
               "Starta bravo till 13 meter, flyg 30 meter österut och kom sedan hem och landa.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 13), visited(ev, "bravo", [c.point("bravo", 0, 30)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 13), _move("bravo", 0, 30), _rtl("bravo")],
               "Bravo flög 30 m österut, kom hem och landade."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("language", "dev", "lang5-cs-charlie-north-land", ("charlie",),
               "Dron charlie ať vzlétne do 16 metrů, přeletí 25 metrů na sever a tam přistane.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 16), at(ev, "charlie", *c.point("charlie", 25, 0)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 16), _move("charlie", 25, 0), _land("charlie")],
               "Charlie přeletěl 25 m na sever a přistál."),
        # moved to dev on 2026-11-30, fifth round: the test half had been measured
        _entry("language", "dev", "lang5-it-alpha-climb-stay", ("alpha",),
               "Fai salire alpha a 10 metri, poi alzalo di altri 8 metri e tienilo lì.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=18), airborne_at(ev, "alpha", 18)),
               [_takeoff("alpha", 10), _move("alpha", up=8)], "Alpha è a 18 m sopra il suo punto di decollo."),
    ]  # fmt: skip


NM = 1852.0


def _sixth_round() -> list[CorpusEntry]:
    """The test half written on 2026-11-30 (sixth round), before any model ran on it: 3 a class; all of
    it moved to dev on 2026-12-01 (sixth round), once its figures had been measured."""
    three = DRONES
    d15, d20, d35 = 15 / math.sqrt(2), 20 / math.sqrt(2), 35 / math.sqrt(2)
    nne30 = (30 * math.cos(math.radians(22.5)), 30 * math.sin(math.radians(22.5)))
    # 25 m from alpha on a bearing of 120 degrees (clockwise from north)
    b120 = (25 * math.cos(math.radians(120)), 25 * math.sin(math.radians(120)))
    zigzag = [(d15, d15), (-d15, d15)] * 2  # four 15 m legs east, north-east first
    # an expanding square: 10, 10, 20, 20, 30 m, north first, turning right
    expanding = [(10.0, 0.0), (0.0, 10.0), (-20.0, 0.0), (0.0, -20.0), (30.0, 0.0)]
    spokes = [(20.0, 0.0), (-20.0, 0.0), (0.0, 20.0), (0.0, -20.0), (-20.0, 0.0), (20.0, 0.0)]
    return [
        # single
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("single", "dev", "single6-da-alpha-hover", ("alpha",),
               "Send alpha op i 24 meters højde og lad den blive hængende der.",
               lambda c, ev: airborne_at(ev, "alpha", 24),
               [_takeoff("alpha", 24)], "Alpha hænger i 24 m."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("single", "dev", "single6-ro-bravo-up-down", ("bravo",),
               "Ridică drona bravo la 15 metri și apoi aterizeaz-o imediat în același loc.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 15), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 15), _land("bravo")], "Bravo a urcat la 15 m și a aterizat."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("single", "dev", "single6-charlie-await-orders", ("charlie",),
               "Launch charlie, stop the climb at 31 m and keep it waiting up there for further orders.",
               lambda c, ev: airborne_at(ev, "charlie", 31),
               [_takeoff("charlie", 31)], "Charlie is waiting at 31 m."),
        # multi
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("multi", "dev", "multi6-no-alpha-hop-bravo-stays", three,
               "Alpha skal lette til 10 meter og lande igjen, mens bravo stiger til 20 meter og blir der. "
               "Charlie blir stående på bakken.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 10), landed_disarmed(ev, "alpha"),
                                  airborne_at(ev, "bravo", 20), never_armed(ev, "charlie")),
               [_takeoff("alpha", 10), _land("alpha"), _takeoff("bravo", 20)],
               "Alpha var oppe i 10 m og landet; bravo svever i 20 m."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("multi", "dev", "multi6-south-two-land-one-home", three,
               "Send all three 25 m south at 10 m; land alpha and bravo down there, but bring charlie back home.",
               lambda c, ev: _all(*(at(ev, d, *c.point(d, -25, 0)) for d in ("alpha", "bravo")),
                                  *(landed_disarmed(ev, d) for d in three),
                                  visited(ev, "charlie", [c.point("charlie", -25, 0)]),
                                  at(ev, "charlie", *_home(c, "charlie"))),
               [*(_move(d, -25, 0, alt=10) for d in three), _land("alpha"), _land("bravo"), _rtl("charlie")],
               "Alpha and bravo landed 25 m south; charlie flew there and came home."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("multi", "dev", "multi6-tr-alpha-on-bravo-waits", three,
               "Alpha ile bravo'yu 12 metreye kaldır; sonra alpha'yı 30 metre kuzeye gönder, bravo olduğu yerde "
               "beklesin. Charlie yerde kalsın.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 30, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=12), airborne_at(ev, "bravo", 12),
                                  never_armed(ev, "charlie")),
               [_takeoff("alpha", 12), _takeoff("bravo", 12), _move("alpha", 30, 0)],
               "Alpha 30 m kuzeyde, bravo yerinde, ikisi de 12 m'de; charlie yerde."),
        # compound
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("compound", "dev", "compound6-nl-alpha-battery-midway", ("alpha",),
               "Alpha: stijg op tot 12 meter, vlieg 30 meter naar het westen, meld me daar het batterijniveau en "
               "keer dan terug naar huis.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, -30)]), answer_mentions_number(ev, 72, 3),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), _move("alpha", 0, -30), _battery("alpha"), _rtl("alpha")],
               "Alpha had 72 % op 30 m ten westen en is thuis geland.", battery={"alpha": 72.0}),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("compound", "dev", "compound6-cs-charlie-middle-of-first-leg", ("charlie",),
               "Charlie: vzlétni do 15 m, leť 40 m na východ, potom 20 m na sever, pak se vrať nad střed prvního "
               "úseku a tam přistaň.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 40), c.point("charlie", 20, 40)]),
                                  at(ev, "charlie", *c.point("charlie", 0, 20)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), _move("charlie", 0, 40), _move("charlie", 20, 0), _move("charlie", -20, -20),
                _land("charlie")], "Charlie přistál uprostřed prvního úseku, 20 m východně od startu."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("compound", "dev", "compound6-es-alpha-retrace", ("alpha",),
               "Lleva a alpha a 14 metros, vuela 20 metros al norte y luego 30 al este; después deshaz el camino "
               "tramo por tramo y aterriza en casa.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 20, 0), c.point("alpha", 20, 30),
                                                        c.point("alpha", 20, 0), _home(c, "alpha")]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 14), _move("alpha", 20, 0), _move("alpha", 0, 30), _move("alpha", 0, -30),
                _move("alpha", -20, 0), _land("alpha")], "Alpha deshizo el camino y aterrizó en casa."),
        # conditional
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("conditional", "dev", "cond6-fleet-average", three,
               "If the fleet's average battery is above 60 %, launch all three to 10 m and keep them there; if "
               "not, keep everyone down and tell me the average.",
               lambda c, ev: _all(*(airborne_at(ev, d, 10) for d in three)),
               [("fleet_status", {}), *(_takeoff(d, 10) for d in three)],
               "The average is 63 %, so all three hover at 10 m.",
               battery={"alpha": 70.0, "bravo": 55.0, "charlie": 64.0}),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("conditional", "dev", "cond6-pl-bravo-metres-per-percent", ("bravo",),
               "Przeleć bravo na wysokości 10 m na północ o tyle metrów, ile procent baterii mu zostało, i zostaw "
               "go tam w powietrzu.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 42, 0), alt=10), airborne_at(ev, "bravo", 10)),
               [_battery("bravo"), _move("bravo", 42, 0, alt=10)],
               "Bravo ma 42 %, więc wisi 42 m na północ na 10 m.", battery={"bravo": 42.0}),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("conditional", "dev", "cond6-ro-charlie-instead", three,
               "Ridic-o pe alpha la 20 de metri și las-o acolo; dacă alpha are sub 40 % baterie, ridic-o pe charlie "
               "în locul ei.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=20), airborne_at(ev, "charlie", 20),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               [_battery("alpha"), _takeoff("charlie", 20)],
               "Alpha are 33 %, așa că charlie stă la 20 m în locul ei.", battery={"alpha": 33.0, "charlie": 78.0}),
        # formation
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("formation", "dev", "form6-da-pair-southwest", ("alpha", "bravo"),
               "Stil alpha og bravo side om side med 18 meters mellemrum, i 22 meters højde, 35 meter sydvest for "
               "deres nuværende position, og lad dem blive der.",
               lambda c, ev: formation_at(c, ev, ("alpha", "bravo"), 22, 18, -d35, -d35),
               [_formation(("alpha", "bravo"), "line", 22, 18, north=-d35, east=-d35)],
               "Alpha og bravo står side om side 35 m mod sydvest i 22 m."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("formation", "dev", "form6-tr-column-feet-north", three,
               "Üç dronu arka arkaya, aralarında 50 fit olacak şekilde, 40 metre yükseklikte ve bulundukları "
               "yerin 20 metre kuzeyinde sırala.",
               lambda c, ev: _all(formation_at(c, ev, three, 40, 50 * FT, 20, 0), farthest_apart(ev, three, 100 * FT)),
               [_formation(three, "column", 40, 50 * FT, north=20)],
               "Üç drone 20 m kuzeyde, 40 m'de, 50 fit arayla arka arkaya."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("formation", "dev", "form6-fr-line-slid-north", three,
               "Aligne les trois drones à 12 m d'altitude, espacés de 10 m, là où ils sont ; ensuite décale toute "
               "la ligne de 30 m vers le nord et laisse-la là.",
               lambda c, ev: _all(formation_at(c, ev, three, 12, 10, 30, 0), farthest_apart(ev, three, 20)),
               [_formation(three, "line", 12, 10), _formation(three, "line", 12, 10, north=30)],
               "Les trois sont en ligne 30 m au nord, à 12 m."),
        # relative
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("relative", "dev", "rel6-sv-alpha-nne", ("alpha",),
               "Flytta alpha 30 meter mot nordnordost på 12 meters höjd och låt den sväva där.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", *nne30), alt=12), airborne_at(ev, "alpha", 12)),
               [_move("alpha", *nne30, alt=12)], "Alpha svävar 30 m mot nordnordost på 12 m."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("relative", "dev", "rel6-it-charlie-half-higher-sw", ("charlie",),
               "Porta charlie a 12 metri, poi alzalo della metà della sua quota e spostalo di 20 metri verso "
               "sud-ovest; lascialo lì sospeso.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -d20, -d20), alt=18),
                                  airborne_at(ev, "charlie", 18)),
               [_takeoff("charlie", 12), _move("charlie", -d20, -d20, up=6)],
               "Charlie è 20 m a sud-ovest, a 18 m."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("relative", "dev", "rel6-no-bravo-back-toward-start", ("bravo",),
               "Fly bravo 40 meter østover i 10 meters høyde, og trekk den deretter 15 meter tilbake mot "
               "startpunktet; la den sveve der.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, 40)]),
                                  at(ev, "bravo", *c.point("bravo", 0, 25), alt=10), airborne_at(ev, "bravo", 10)),
               [_move("bravo", 0, 40, alt=10), _move("bravo", 0, -15)], "Bravo svever 25 m øst for start i 10 m."),
        # question
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("question", "dev", "ask6-de-spread-of-charges", three,
               "Wie viele Prozentpunkte liegen zwischen dem vollsten und dem leersten Akku der drei Drohnen? "
               "Nichts starten, nur nachsehen.",
               # the typed plan reads, it does not compute: the spread, or the two readings it comes from
               lambda c, ev: _all(_any(answer_mentions_number(ev, 34, 1),
                                       _all(answer_mentions_number(ev, 81, 1), answer_mentions_number(ev, 47, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "34 Prozentpunkte: alpha hat 81 %, bravo 47 %.",
               battery={"alpha": 81.0, "bravo": 47.0, "charlie": 66.0}),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("question", "dev", "ask6-fi-lower-of-pair-airborne", three,
               "Kummalla on vähemmän akkua jäljellä, bravolla vai charliella, ja onko kumpikaan niistä ilmassa? "
               "Älä lennätä mitään.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 52, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Bravolla (52 %); kumpikaan ei ole ilmassa.",
               battery={"alpha": 38.0, "bravo": 52.0, "charlie": 90.0}),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("question", "dev", "ask6-ro-closest-to-half", three,
               "Care dronă are nivelul bateriei cel mai apropiat de 50 %? Nu porni nimic.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 57, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Bravo, cu 57 %.", battery={"alpha": 35.0, "bravo": 57.0, "charlie": 80.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("refusal", "dev", "refuse6-da-charlie-sea-miles", ("charlie",),
               "Flyv charlie 0,6 sømil mod nord i 20 meters højde.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "charlie", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("charlie", 0.6 * NM, 0, alt=20)],
               "The gateway refused: 0.6 nautical miles (1111 m) is beyond the 1000 m limit."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("refusal", "dev", "refuse6-cs-bravo-feet-over-ceiling", ("bravo",),
               "Vzlétni s bravem do 80 m a potom ho zvedni o dalších 150 stop.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "bravo", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("bravo", 80), _move("bravo", up=150 * FT)],
               "Bravo is at 80 m; the climb of 150 ft (to 126 m) was refused: above the 120 m altitude limit."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("refusal", "dev", "refuse6-es-bravo-wide-orbit", ("bravo",),
               "Haz que bravo dé una vuelta alrededor de su punto de despegue con un radio de 1,2 km, a 40 metros "
               "de altura.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "bravo", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("bravo", 1200, 0, alt=40)],
               "The gateway refused: a 1.2 km radius is beyond the 1000 m limit."),
        # units
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("units", "dev", "units6-no-charlie-feet-sea-miles", ("charlie",),
               "Løft charlie til 50 fot, fly den 0,02 sjømil østover og la den henge der.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 0.02 * NM), alt=50 * FT),
                                  airborne_at(ev, "charlie", 50 * FT)),
               [_takeoff("charlie", 50 * FT), _move("charlie", 0, 0.02 * NM)],
               "Charlie henger 0,02 sjømil øst i 50 fot."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("units", "dev", "units6-tr-bravo-feet-west", ("bravo",),
               "Bravo'yu 40 fit yüksekliğe çıkar, 150 fit batıya uçur ve orada indir.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 40 * FT), at(ev, "bravo", *c.point("bravo", 0, -150 * FT)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 40 * FT), _move("bravo", 0, -150 * FT), _land("bravo")],
               "Bravo 40 fite çıktı, 150 fit batıya uçtu ve indi."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("units", "dev", "units6-alpha-yards-height", ("alpha",),
               "Alpha: climb to 50 yards, go 100 yards south, then come down 40 feet and hover there.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 50 * YD),
                                  at(ev, "alpha", *c.point("alpha", -100 * YD, 0), alt=50 * YD - 40 * FT),
                                  airborne_at(ev, "alpha", 50 * YD - 40 * FT)),
               [_takeoff("alpha", 50 * YD), _move("alpha", -100 * YD, 0), _move("alpha", up=-40 * FT)],
               "Alpha hovers 100 yd south at 110 ft (about 33.5 m)."),
        # pattern
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("pattern", "dev", "pattern6-pt-bravo-zigzag", ("bravo",),
               "Leva o bravo a 12 metros e faz um ziguezague para leste: quatro troços de 15 metros, alternando "
               "entre nordeste e sudeste, a começar por nordeste; no fim aterra aí.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(zigzag)]),
                                  at(ev, "bravo", *c.point("bravo", *_corners(zigzag)[-1])),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), *_legs("bravo", zigzag), _land("bravo")],
               "O bravo fez o ziguezague e aterrou 42 m a leste."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("pattern", "dev", "pattern6-de-charlie-expanding-square", ("charlie",),
               "Charlie soll auf 10 m Höhe ein nach außen wachsendes Quadrat als Suchmuster fliegen: Strecken von "
               "10, 10, 20, 20 und 30 m, zuerst nach Norden, nach jeder Strecke rechts abbiegen; danach dort in "
               "der Luft bleiben.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(expanding)]),
                                  at(ev, "charlie", *c.point("charlie", 20, -10), alt=10),
                                  airborne_at(ev, "charlie", 10)),
               [_takeoff("charlie", 10), *_legs("charlie", expanding)],
               "Charlie ist das Suchmuster geflogen und schwebt 20 m nördlich, 10 m westlich auf 10 m."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("pattern", "dev", "pattern6-alpha-spokes", ("alpha",),
               "Alpha at 10 m: fly three 20 m spokes out from its home, north, then east, then south, coming back "
               "over home after each one; land at home at the end.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(spokes)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), *_legs("alpha", spokes), _land("alpha")],
               "Alpha flew the three spokes and landed at home."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: a drone placed
        # from itself, or from the other drone's home instead of where it flew, misses by 10 m or more)
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("placement", "dev", "place6-nl-flanking-bravo", three,
               "Vlieg bravo 30 meter naar het noorden op 15 meter hoogte. Zet daarna alpha 10 meter ten westen en "
               "charlie 10 meter ten oosten van bravo, op dezelfde hoogte.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 30, 0), alt=15),
                                  at(ev, "alpha", *c.point("bravo", 30, -10), alt=15),
                                  at(ev, "charlie", *c.point("bravo", 30, 10), alt=15),
                                  *(airborne_at(ev, d, 15) for d in three)),
               lambda c: [_move("bravo", 30, 0, alt=15), _go("alpha", c.point("bravo", 30, -10), 15),
                          _go("charlie", c.point("bravo", 30, 10), 15)],
               "Bravo hangt 30 m noordelijk op 15 m, alpha 10 m ten westen en charlie 10 m ten oosten ervan."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("placement", "dev", "place6-fi-charlie-bearing-from-alpha", three,
               "Lennätä alpha 12 metrin korkeudessa 20 metriä pohjoiseen. Vie sitten charlie 25 metrin päähän "
               "alphasta suuntaan 120 astetta pohjoisesta myötäpäivään, samaan korkeuteen.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", 20 + b120[0], b120[1]), alt=12),
                                  airborne_at(ev, "charlie", 12), never_armed(ev, "bravo")),
               lambda c: [_move("alpha", 20, 0, alt=12), _go("charlie", c.point("alpha", 20 + b120[0], b120[1]), 12)],
               "Alpha on 20 m pohjoisessa 12 m:ssä; charlie 25 m alphasta suuntaan 120 astetta."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("placement", "dev", "place6-ro-charlie-lands-north-of-bravo", three,
               "Bravo zboară 25 de metri spre vest la 10 metri înălțime și aterizează acolo. Apoi charlie "
               "aterizează la 15 metri la nord de locul unde a aterizat bravo.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -25)), landed_disarmed(ev, "bravo"),
                                  at(ev, "charlie", *c.point("bravo", 15, -25)), landed_disarmed(ev, "charlie"),
                                  never_armed(ev, "alpha")),
               lambda c: [_move("bravo", 0, -25, alt=10), _land("bravo"), _go("charlie", c.point("bravo", 15, -25), 10),
                          _land("charlie")],
               "Bravo a aterizat la 25 m vest; charlie la 15 m nord de el."),
        # language
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("language", "dev", "lang6-fi-alpha-north-land", ("alpha",),
               "Nosta alpha 14 metrin korkeuteen, lennätä se 30 metriä pohjoiseen ja laske se sinne maahan.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 14), at(ev, "alpha", *c.point("alpha", 30, 0)),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 14), _move("alpha", 30, 0), _land("alpha")],
               "Alpha lensi 30 m pohjoiseen ja laskeutui."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("language", "dev", "lang6-tr-bravo-climb-stay", ("bravo",),
               "Bravo'yu 12 metreye kaldır, sonra 8 metre daha yükselt ve orada beklet.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=20), airborne_at(ev, "bravo", 20)),
               [_takeoff("bravo", 12), _move("bravo", up=8)], "Bravo kalkış noktasının üstünde 20 m'de bekliyor."),
        # moved to dev on 2026-12-01, sixth round: the test half had been measured
        _entry("language", "dev", "lang6-da-charlie-west-home", ("charlie",),
               "Lad charlie lette til 16 meter, flyve 25 meter mod vest og derefter flyve hjem og lande.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 16), visited(ev, "charlie", [c.point("charlie", 0, -25)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 16), _move("charlie", 0, -25), _rtl("charlie")],
               "Charlie fløj 25 m mod vest, kom hjem og landede."),
    ]  # fmt: skip


def _seventh_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-01 (seventh round), before any model ran on it: 3 a class; all of
    it moved to dev on 2026-12-01 (seventh round), once its figures had been measured."""
    three = DRONES
    d35 = 35 / math.sqrt(2)
    square15 = [(15.0, 0.0), (0.0, 15.0), (-15.0, 0.0), (0.0, -15.0)]  # north first, turning right
    heptagon12 = _polygon_legs(7, 12.0, 90.0, right=True)  # first side east, turning right
    shuttle = [(30.0, 0.0), (-30.0, 0.0)] * 3  # out 30 m north and back, three times
    # four passes of 30 m, the first south, 8 m apart, each next pass east of the one before
    passes = [(-30.0, 0.0), (0.0, 8.0), (30.0, 0.0), (0.0, 8.0), (-30.0, 0.0), (0.0, 8.0), (30.0, 0.0)]
    r60ft = 60 * FT  # clockwise round home from its north side: N, E, S, W, N, then back to the centre
    orbit60ft = [(r60ft, 0.0), (-r60ft, r60ft), (-r60ft, -r60ft), (r60ft, -r60ft), (r60ft, r60ft)]
    orbit60ft.append((-r60ft, 0.0))
    return [
        # single
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("single", "dev", "single7-ca-alpha-words", ("alpha",),
               "Enlaira l'alpha fins a vint-i-sis metres i deixa'l suspès allà dalt.",
               lambda c, ev: airborne_at(ev, "alpha", 26),
               [_takeoff("alpha", 26)], "L'alpha és a 26 m."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("single", "dev", "single7-el-bravo-up-down", ("bravo",),
               "Σήκωσε το bravo στα 13 μέτρα και μετά προσγείωσέ το ξανά στο ίδιο σημείο.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 13), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 13), _land("bravo")], "Το bravo ανέβηκε στα 13 m και προσγειώθηκε."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("single", "dev", "single7-charlie-off-pad", ("charlie",),
               "Lift charlie 17 m off its pad and keep it hanging there while I check something.",
               lambda c, ev: airborne_at(ev, "charlie", 17),
               [_takeoff("charlie", 17)], "Charlie hangs at 17 m."),
        # multi
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("multi", "dev", "multi7-hr-pair-east-home", three,
               "Bravo i charlie neka odlete 20 metara na istok na visini od 10 metara i zatim se vrate kući; "
               "alpha ostaje na zemlji.",
               lambda c, ev: _all(*(visited(ev, d, [c.point(d, 0, 20)]) for d in ("bravo", "charlie")),
                                  *(at(ev, d, *_home(c, d)) for d in ("bravo", "charlie")),
                                  *(landed_disarmed(ev, d) for d in ("bravo", "charlie")), never_armed(ev, "alpha")),
               [_move("bravo", 0, 20, alt=10), _move("charlie", 0, 20, alt=10), _rtl("bravo"), _rtl("charlie")],
               "Bravo i charlie odletjeli su 20 m na istok i vratili se kući; alpha je ostao na zemlji."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("multi", "dev", "multi7-de-down-one-by-one", three,
               "Bring alle drei Drohnen auf 15 m und hol sie dann einzeln wieder runter, zuerst charlie, dann "
               "bravo; alpha bleibt oben.",
               lambda c, ev: _all(*(reached_alt(ev, d, 15) for d in ("bravo", "charlie")),
                                  landed_disarmed(ev, "charlie"), landed_disarmed(ev, "bravo"),
                                  airborne_at(ev, "alpha", 15)),
               [*(_takeoff(d, 15) for d in three), _land("charlie"), _land("bravo")],
               "Charlie und bravo sind wieder gelandet; alpha schwebt auf 15 m."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("multi", "dev", "multi7-no-pair-south-bravo-hop", three,
               "Alpha og charlie flyr 15 meter sørover i 12 meters høyde og blir hengende der, mens bravo stiger "
               "rett opp til 25 meter og lander igjen.",
               lambda c, ev: _all(*(at(ev, d, *c.point(d, -15, 0), alt=12) for d in ("alpha", "charlie")),
                                  *(airborne_at(ev, d, 12) for d in ("alpha", "charlie")),
                                  reached_alt(ev, "bravo", 25), landed_disarmed(ev, "bravo")),
               [_move("alpha", -15, 0, alt=12), _move("charlie", -15, 0, alt=12), _takeoff("bravo", 25),
                _land("bravo")], "Alpha og charlie henger 15 m sør i 12 m; bravo var oppe i 25 m og landet."),
        # compound
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("compound", "dev", "compound7-ca-bravo-lands-and-again", ("bravo",),
               "Enlaira el bravo fins a 12 metres, fes-lo volar 30 metres cap a l'est i fes-lo aterrar allà; "
               "després torna'l a enlairar fins a 8 metres, fes-lo volar 30 metres cap a l'oest i deixa'l suspès "
               "allà.",
               # set down at the far point: the track passes it near the ground
               lambda c, ev: _all(reached_alt(ev, "bravo", 12), visited(ev, "bravo", [c.point("bravo", 0, 30)], alt=0),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=8), airborne_at(ev, "bravo", 8)),
               [_takeoff("bravo", 12), _move("bravo", 0, 30), _land("bravo"), _takeoff("bravo", 8), _move("bravo", 0, -30)],
               "El bravo ha aterrat 30 m a l'est, s'ha tornat a enlairar i és suspès sobre el seu punt de partida a 8 m."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("compound", "dev", "compound7-sv-alpha-turn-left", ("alpha",),
               "Lyft alpha till 10 meter, flyg 30 meter norrut, sväng sedan vänster och flyg 15 meter till, och "
               "landa där.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 30, 0)]),
                                  at(ev, "alpha", *c.point("alpha", 30, -15)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", 30, 0), _move("alpha", 0, -15), _land("alpha")],
               "Alpha flög 30 m norrut och 15 m västerut och landade."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("compound", "dev", "compound7-tr-charlie-lower-back-over-home", ("charlie",),
               "Charlie'yi 14 metreye kaldır, 25 metre güneye uçur, orada 6 metreye alçalt, sonra kalkış "
               "noktasının üstüne geri getir ve orada havada tut.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 14), visited(ev, "charlie", [c.point("charlie", -25, 0)]),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=6), airborne_at(ev, "charlie", 6)),
               [_takeoff("charlie", 14), _move("charlie", -25, 0), _move("charlie", alt=6), _move("charlie", 25, 0)],
               "Charlie kalkış noktasının üstünde 6 m'de bekliyor."),
        # conditional
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("conditional", "dev", "cond7-nl-charlie-two-thirds", ("charlie",),
               "Heeft charlie minder dan twee derde van zijn batterij over, laat hem dan aan de grond staan en noem "
               "me het percentage; anders gaat hij naar 12 meter en blijft hij daar hangen.",
               lambda c, ev: _all(never_armed(ev, "charlie"), answer_mentions_number(ev, 61, 1)),
               [_battery("charlie")], "Charlie heeft 61 %, minder dan twee derde, dus hij blijft aan de grond.",
               battery={"charlie": 61.0}),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("conditional", "dev", "cond7-fr-bravo-land-or-home", ("bravo",),
               "Emmène bravo à 30 m au nord, à 10 m de hauteur ; une fois là-bas, si sa batterie est sous 45 %, "
               "pose-le sur place, sinon ramène-le à la maison.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 30, 0)], alt=10),
                                  at(ev, "bravo", *c.point("bravo", 30, 0)), landed_disarmed(ev, "bravo")),
               [_move("bravo", 30, 0, alt=10), _battery("bravo"), _land("bravo")],
               "Bravo avait 40 %, il s'est posé à 30 m au nord.", battery={"bravo": 40.0}),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("conditional", "dev", "cond7-fi-fuller-flies-square", three,
               "Alphasta ja charliesta se, jolla on enemmän akkua, lentää 10 metrin korkeudessa neliön, jonka sivu "
               "on 15 metriä, ensimmäinen sivu pohjoiseen ja oikealle kääntyen, ja laskeutuu lähtöpaikalleen; "
               "toinen jää maahan.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(square15)[:3]]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie"),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               [_battery("alpha"), _battery("charlie"), _takeoff("charlie", 10), *_legs("charlie", square15),
                _land("charlie")], "Charliella oli enemmän akkua (83 %); se lensi neliön ja laskeutui.",
               battery={"alpha": 48.0, "charlie": 83.0}),
        # formation (three in a ring stand at the corners of a triangle with sides of the spacing)
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("formation", "dev", "form7-el-triangle-east", three,
               "Βάλε τα τρία drones σε σχηματισμό τριγώνου με πλευρά 16 μέτρων, σε ύψος 14 μέτρων, 25 μέτρα "
               "ανατολικά από το σημείο όπου βρίσκονται, και άφησέ τα εκεί.",
               lambda c, ev: _all(formation_at(c, ev, three, 14, 16, 0, 25), farthest_apart(ev, three, 16)),
               [_formation(three, "circle", 14, 16, east=25)], "Τα τρία drones είναι σε τρίγωνο 25 m ανατολικά, στα 14 m."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("formation", "dev", "form7-column-north-of-charlie", three,
               "Put alpha and bravo in a column 10 m apart at 15 m, centred on the spot 30 m north of charlie.",
               lambda c, ev: _all(formation_around(ev, ("alpha", "bravo"), 15, 10, c.point("charlie", 30, 0)),
                                  never_armed(ev, "charlie")),
               lambda c: [("formation_goto", {"drone_ids": ["alpha", "bravo"], "formation": "column", "alt_m": 15,
                                              "spacing_m": 10, "center_lat_deg": c.point("charlie", 30, 0)[0],
                                              "center_lon_deg": c.point("charlie", 30, 0)[1]})],
               "Alpha and bravo hold a column 10 m apart at 15 m, 30 m north of charlie."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("formation", "dev", "form7-cs-line-then-lower", three,
               "Seřaď všechny tři drony do řady s rozestupy 10 m ve výšce 20 m nad místem, kde stojí, pak celou "
               "řadu sniž na 8 m a nech ji tam viset.",
               lambda c, ev: _all(*(rose_to(ev, d, 20) for d in three), formation_at(c, ev, three, 8, 10, 0, 0),
                                  farthest_apart(ev, three, 20)),
               [_formation(three, "line", 20, 10), _formation(three, "line", 8, 10)],
               "Všechny tři visí v řadě 10 m od sebe v 8 m."),
        # relative
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("relative", "dev", "rel7-es-charlie-signed", ("charlie",),
               "Desplaza a charlie -20 m en dirección norte y +15 m en dirección este, a 12 m de altura, y déjalo "
               "ahí.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -20, 15), alt=12), airborne_at(ev, "charlie", 12)),
               [_move("charlie", -20, 15, alt=12)], "Charlie está 20 m al sur y 15 m al este, a 12 m."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("relative", "dev", "rel7-pl-alpha-same-direction", ("alpha",),
               "Alpha: leć 25 m na zachód na wysokości 10 m, potem jeszcze 25 m w tym samym kierunku, wznosząc się "
               "o 5 m, i zawiśnij tam.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, -25)]),
                                  at(ev, "alpha", *c.point("alpha", 0, -50), alt=15), airborne_at(ev, "alpha", 15)),
               [_move("alpha", 0, -25, alt=10), _move("alpha", 0, -25, up=5)], "Alpha wisi 50 m na zachód na 15 m."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("relative", "dev", "rel7-it-bravo-stop-short", ("bravo",),
               "Porta bravo a 14 metri di quota verso il punto 40 metri a nord, ma fermalo 10 metri prima e "
               "lascialo lì sospeso.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 30, 0), alt=14), airborne_at(ev, "bravo", 14)),
               [_move("bravo", 30, 0, alt=14)], "Bravo è sospeso 30 m a nord, a 14 m."),
        # question (each answered by the readings the host lists)
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("question", "dev", "ask7-hu-how-many-over-half", three,
               "Hány drónnak van 50 százaléknál több töltése? Egyiket se indítsd el.",
               lambda c, ev: _all(answer_mentions_number(ev, 64, 1), answer_mentions_number(ev, 77, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Kettőnek: alpha 64 %, charlie 77 %; bravo 45 %.",
               battery={"alpha": 64.0, "bravo": 45.0, "charlie": 77.0}),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("question", "dev", "ask7-ca-bravo-three-quarters", ("bravo",),
               "Al bravo li queden com a mínim tres quarts de bateria? Només comprova-ho, no l'enlairis.",
               lambda c, ev: _all(answer_mentions_number(ev, 71, 1), never_armed(ev, "bravo")),
               [_battery("bravo")], "Gairebé: el bravo té un 71 %.", battery={"bravo": 71.0}),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("question", "dev", "ask7-el-all-but-bravo", three,
               "Εκτός από το bravo, πόση μπαταρία έχει το καθένα από τα άλλα drones; Μην απογειώσεις κανένα.",
               lambda c, ev: _all(answer_mentions_number(ev, 58, 1), answer_mentions_number(ev, 43, 1),
                                  nobody_armed(ev)),
               [_battery("alpha"), _battery("charlie")], "alpha 58 %, charlie 43 %.",
               battery={"alpha": 58.0, "bravo": 90.0, "charlie": 43.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off)
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("refusal", "dev", "refuse7-ro-charlie-km-height", ("charlie",),
               "Ridică drona charlie la o înălțime de 0,15 kilometri.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "charlie", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("charlie", 150)], "The gateway refused: 0.15 km (150 m) is above the 120 m altitude limit."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("refusal", "dev", "refuse7-alpha-kilometre-square", ("alpha",),
               "Alpha at 30 m: fly a square with 1.5 km sides, first side north, then land where it started.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "alpha", c.max_distance_m), answer_reports_refusal(ev)),
               [_takeoff("alpha", 30), _move("alpha", 1500, 0)],
               "The gateway refused: a 1.5 km side is beyond the 1000 m limit."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("refusal", "dev", "refuse7-sk-charlie-low-beside-alpha", three,
               "Premiestni dron charlie na miesto 20 metrov východne od dronu alpha, vo výške 15 metrov.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "charlie"), answer_reports_refusal(ev)),
               lambda c: [_go("charlie", c.point("alpha", 0, 20), 15)],
               "The gateway refused: charlie's battery is below the takeoff minimum.", battery={"charlie": 19.0}),
        # units
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("units", "dev", "units7-bravo-prime-feet", ("bravo",),
               "Bravo: climb to 55', fly 90' west and hold it there.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -90 * FT), alt=55 * FT),
                                  airborne_at(ev, "bravo", 55 * FT)),
               [_takeoff("bravo", 55 * FT), _move("bravo", 0, -90 * FT)], "Bravo hovers 90 ft west at 55 ft."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("units", "dev", "units7-ro-charlie-orbit-feet", ("charlie",),
               "Drona charlie să zboare un cerc cu raza de 60 de picioare în jurul punctului de decolare, la 12 "
               "metri înălțime, în sensul acelor de ceasornic, începând din partea de nord, și apoi să revină acasă.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e)
                                                          for n, e in ((r60ft, 0), (0, r60ft), (-r60ft, 0), (0, -r60ft))]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), *_legs("charlie", orbit60ft), _rtl("charlie")],
               "Charlie a zburat cercul de 60 de picioare și a revenit acasă."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("units", "dev", "units7-tr-charlie-feet-east-of-alpha", three,
               "Charlie'yi alpha'nın 60 fit doğusuna, 45 fit yüksekliğe götür ve orada havada beklet.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("alpha", 0, 60 * FT), alt=45 * FT),
                                  airborne_at(ev, "charlie", 45 * FT), never_armed(ev, "alpha")),
               lambda c: [_go("charlie", c.point("alpha", 0, 60 * FT), 45 * FT)],
               "Charlie, alpha'nın 60 fit doğusunda 45 fitte bekliyor."),
        # pattern
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("pattern", "dev", "pattern7-no-alpha-heptagon", ("alpha",),
               "Fly alpha rundt en regelmessig mangekant med sju sider på 12 meter hver, i 10 meters høyde; første "
               "side går mot øst, sving til høyre i hvert hjørne, og land der du startet.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(heptagon12)[:5]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), *_legs("alpha", heptagon12), _land("alpha")],
               "Alpha fløy sjukanten og landet der den startet."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("pattern", "dev", "pattern7-sv-bravo-shuttle", ("bravo",),
               "Låt bravo pendla fram och tillbaka tre gånger mellan sin startpunkt och en punkt 30 meter norrut, "
               "på 10 meters höjd, och landa sedan vid startpunkten.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(shuttle)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), *_legs("bravo", shuttle), _land("bravo")],
               "Bravo pendlade tre gånger och landade vid startpunkten."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("pattern", "dev", "pattern7-pl-charlie-passes-east", ("charlie",),
               "Charlie na wysokości 12 m: przeleć cztery równoległe pasy po 30 m, 8 m od siebie, pierwszy na "
               "południe, każdy następny na wschód od poprzedniego; potem wróć do domu.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(passes)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), *_legs("charlie", passes), _rtl("charlie")],
               "Charlie przeleciał cztery pasy i wrócił do domu."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each places one of
        # alpha and charlie from the other, so a drone placed from itself, or from where the other took off
        # instead of where it flew, misses by 10 m or more)
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("placement", "dev", "place7-da-alpha-below-charlie", three,
               "Charlie flyver 15 meter mod nord i 20 meters højde. Placér derefter alpha lige under charlie, 8 "
               "meter lavere, og lad begge blive i luften.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 15, 0), alt=20), airborne_at(ev, "charlie", 20),
                                  at(ev, "alpha", *c.point("charlie", 15, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("charlie", 15, 0, alt=20), _go("alpha", c.point("charlie", 15, 0), 12)],
               "Charlie svæver 15 m mod nord i 20 m; alpha lige under den i 12 m."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("placement", "dev", "place7-fi-chain-west-then-north", three,
               "Vie charlie 14 metrin korkeuteen 20 metriä alphasta länteen. Lennätä sitten alpha 20 metriä "
               "charliesta pohjoiseen samalle korkeudelle ja jätä molemmat ilmaan.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("alpha", 0, -20), alt=14), airborne_at(ev, "charlie", 14),
                                  at(ev, "alpha", *c.point("alpha", 20, -20), alt=14), airborne_at(ev, "alpha", 14),
                                  never_armed(ev, "bravo")),
               lambda c: [_go("charlie", c.point("alpha", 0, -20), 14), _go("alpha", c.point("alpha", 20, -20), 14)],
               "Charlie on 20 m alphasta länteen ja alpha 20 m charliesta pohjoiseen, molemmat 14 m:ssä."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("placement", "dev", "place7-pt-swap-pads", three,
               "Troca o alpha e o charlie de lugar: o alpha vai pairar a 12 metros sobre o ponto de descolagem do "
               "charlie e o charlie a 16 metros sobre o do alpha.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "charlie"), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *_home(c, "alpha"), alt=16), airborne_at(ev, "charlie", 16),
                                  never_armed(ev, "bravo")),
               lambda c: [_go("alpha", _home(c, "charlie"), 12), _go("charlie", _home(c, "alpha"), 16)],
               "O alpha paira a 12 m sobre a descolagem do charlie e o charlie a 16 m sobre a do alpha."),
        # language
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("language", "dev", "lang7-hu-charlie-southwest-land", ("charlie",),
               "A charlie szálljon fel 11 méterre, repüljön 35 métert délnyugatra, aztán ott szálljon le.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 11), at(ev, "charlie", *c.point("charlie", -d35, -d35)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 11), _move("charlie", -d35, -d35), _land("charlie")],
               "A charlie 35 métert repült délnyugatra és leszállt."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("language", "dev", "lang7-hr-bravo-north-hover", ("bravo",),
               "Podigni bravo na 19 metara, odleti s njim 20 metara prema sjeveru i ostavi ga da lebdi tamo.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 20, 0), alt=19), airborne_at(ev, "bravo", 19)),
               [_takeoff("bravo", 19), _move("bravo", 20, 0)], "Bravo lebdi 20 m sjeverno na 19 m."),
        # moved to dev on 2026-12-01, seventh round: the test half had been measured
        _entry("language", "dev", "lang7-sk-alpha-east-home", ("alpha",),
               "Vzlietni s dronom alpha do výšky 9 metrov, preleť 40 metrov na východ a potom sa vráť domov a "
               "pristaň.",
               # (the flight home climbs to the return altitude first: the height is read where the leg ends)
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 40)], alt=9),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 9), _move("alpha", 0, 40), _rtl("alpha")],
               "Alpha preletel 40 m na východ, vrátil sa domov a pristál."),
    ]  # fmt: skip


def _eighth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-01 (eighth round), before any model ran on it: 3 a class; 22 of
    the 33 outside ``language`` in other languages than English (Bulgarian, Estonian, Indonesian, Latvian,
    Lithuanian, Russian, Slovenian, Spanish, Ukrainian, Vietnamese), the ``language`` class's 3 in Russian,
    Vietnamese and Estonian; all of it moved to dev on 2026-12-02 (eighth round), once its figures had been
    measured."""
    three = DRONES
    d20, d25, d30 = 20 / math.sqrt(2), 25 / math.sqrt(2), 30 / math.sqrt(2)
    pentagon = _polygon_legs(5, 20.0, 90.0, right=False)  # first side east, turning left
    rectangle = [(0.0, 40.0), (15.0, 0.0), (0.0, -40.0), (-15.0, 0.0)]  # 40 m east first, turning left
    # an orbit of 12 m radius, counter-clockwise, round a spot 30 m east of home: its four compass points,
    # each to be passed whichever side the orbit starts on
    ring = [(12.0, 30.0), (0.0, 18.0), (-12.0, 30.0), (0.0, 42.0)]
    ring_legs = [(0.0, 30.0), (12.0, 0.0), (-12.0, -12.0), (-12.0, 12.0), (12.0, 12.0), (12.0, -12.0),
                 (-12.0, 0.0)]  # fmt: skip
    return [
        # single
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("single", "dev", "single8-ru-bravo-hover", ("bravo",),
               "Подними bravo на 18 метров и пусть висит там, пока я не скажу.",
               lambda c, ev: airborne_at(ev, "bravo", 18),
               [_takeoff("bravo", 18)], "Bravo висит на 18 м."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("single", "dev", "single8-id-charlie-up-down", ("charlie",),
               "Terbangkan charlie setinggi 11 meter, lalu langsung daratkan lagi di tempat yang sama.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 11), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 11), _land("charlie")], "Charlie naik ke 11 m lalu mendarat lagi."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("single", "dev", "single8-alpha-up-then-lower", ("alpha",),
               "Climb alpha to 35 m, then bring it down to 12 m and keep it there.",
               lambda c, ev: _all(rose_to(ev, "alpha", 35), at(ev, "alpha", *_home(c, "alpha"), alt=12),
                                  airborne_at(ev, "alpha", 12)),
               [_takeoff("alpha", 35), _move("alpha", alt=12)], "Alpha went up to 35 m and now holds 12 m."),
        # multi
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("multi", "dev", "multi8-uk-three-heights", three,
               "Підніми alpha на 10 метрів, bravo на 20 метрів, а charlie на 30 метрів, і нехай усі три зависнуть там.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 10), airborne_at(ev, "bravo", 20),
                                  airborne_at(ev, "charlie", 30)),
               [_takeoff("alpha", 10), _takeoff("bravo", 20), _takeoff("charlie", 30)],
               "Alpha висить на 10 м, bravo на 20 м, charlie на 30 м."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("multi", "dev", "multi8-sl-pair-east-charlie-ground", three,
               "Alpha in bravo naj poletita 20 metrov proti vzhodu na višini 12 metrov in tam ostaneta v zraku; "
               "charlie naj ostane na tleh.",
               lambda c, ev: _all(*(at(ev, d, *c.point(d, 0, 20), alt=12) for d in ("alpha", "bravo")),
                                  *(airborne_at(ev, d, 12) for d in ("alpha", "bravo")), never_armed(ev, "charlie")),
               [_move("alpha", 0, 20, alt=12), _move("bravo", 0, 20, alt=12)],
               "Alpha in bravo lebdita 20 m vzhodno na 12 m; charlie je na tleh."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("multi", "dev", "multi8-opposite-ways-land", three,
               "Bravo goes 25 m north and charlie 25 m south, both at 14 m, and then both land right there. "
               "Leave alpha alone.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 25, 0)), landed_disarmed(ev, "bravo"),
                                  at(ev, "charlie", *c.point("charlie", -25, 0)), landed_disarmed(ev, "charlie"),
                                  never_armed(ev, "alpha")),
               [_move("bravo", 25, 0, alt=14), _move("charlie", -25, 0, alt=14), _land("bravo"), _land("charlie")],
               "Bravo landed 25 m north and charlie 25 m south; alpha stayed down."),
        # compound
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("compound", "dev", "compound8-lt-alpha-two-legs-home", ("alpha",),
               "Pakelk alpha į 10 metrų aukštį, nuskraidink ją 30 metrų į šiaurę, tada 30 metrų į rytus, o tada "
               "grąžink namo ir nutupdyk.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 30, 0), c.point("alpha", 30, 30)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", 30, 0), _move("alpha", 0, 30), _rtl("alpha")],
               "Alpha nuskrido abi atkarpas, grįžo namo ir nusileido."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("compound", "dev", "compound8-bravo-drop-midway", ("bravo",),
               "Bravo: up to 20 m, 15 m west, then drop to 8 m right there, another 15 m west, and hover at the end.",
               lambda c, ev: _all(rose_to(ev, "bravo", 20), visited(ev, "bravo", [c.point("bravo", 0, -15)]),
                                  at(ev, "bravo", *c.point("bravo", 0, -30), alt=8), airborne_at(ev, "bravo", 8)),
               [_takeoff("bravo", 20), _move("bravo", 0, -15), _move("bravo", alt=8), _move("bravo", 0, -15)],
               "Bravo hovers 30 m west at 8 m."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("compound", "dev", "compound8-bg-charlie-half-back-land", ("charlie",),
               "Издигни charlie на 14 метра, прелети с него 40 метра на юг, после го върни половината път обратно "
               "и го приземи там.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -40, 0)]),
                                  at(ev, "charlie", *c.point("charlie", -20, 0)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 14), _move("charlie", -40, 0), _move("charlie", 20, 0), _land("charlie")],
               "Charlie прелетя 40 м на юг, върна се 20 м и кацна."),
        # conditional
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("conditional", "dev", "cond8-lv-bravo-short-hop-if-low", ("bravo",),
               "Ja bravo akumulatora līmenis ir vismaz 50 %, aizlido ar to 30 metrus uz ziemeļiem 12 metru "
               "augstumā; citādi tikai pacel to 5 metrus augstu un nosēdini atpakaļ.",
               lambda c, ev: _all(rose_to(ev, "bravo", 5), max_alt_at_most(ev, "bravo", 8),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_battery("bravo"), _takeoff("bravo", 5), _land("bravo")],
               "Bravo ir 44 %, tāpēc tas tikai pacēlās līdz 5 m un nosēdās.", battery={"bravo": 44.0}),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("conditional", "dev", "cond8-et-alpha-low-goes-home", ("alpha",),
               "Tõsta alpha 12 meetri kõrgusele ja lennuta see 20 meetrit põhja. Kui selle aku on siis alla 45 %, "
               "saada see koju; muidu jäta see sinna õhku.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 20, 0)]), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), _move("alpha", 20, 0), _battery("alpha"), _rtl("alpha")],
               "Alpha aku oli 38 %, nii et see lendas koju ja maandus.", battery={"alpha": 38.0}),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("conditional", "dev", "cond8-fuller-of-bravo-charlie-east", three,
               "Whichever of bravo and charlie has more battery left flies 30 m east at 12 m and hovers there; the "
               "other one stays on the ground, and so does alpha.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 30), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo"), never_armed(ev, "alpha")),
               [("fleet_status", {}), _move("charlie", 0, 30, alt=12)],
               "Charlie (81 %) hovers 30 m east at 12 m; bravo (55 %) and alpha stay down.",
               battery={"alpha": 90.0, "bravo": 55.0, "charlie": 81.0}),
        # formation
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("formation", "dev", "form8-ru-column-east-land", three,
               "Выстрой все три дрона в колонну с интервалом 12 метров на высоте 15 метров, в 30 метрах к востоку "
               "от того места, где они сейчас, а потом посади их там.",
               lambda c, ev: landed_formation_at(c, ev, three, 24, 0, 30),
               [_formation(three, "column", 15, 12, east=30), *(_land(d) for d in three)],
               "Три дрона встали колонной в 30 м к востоку и сели."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("formation", "dev", "form8-id-pair-northwest", ("alpha", "charlie"),
               "Terbangkan alpha dan charlie berdampingan dengan jarak 16 meter, pada ketinggian 18 meter, 25 meter "
               "ke arah barat laut dari posisi mereka sekarang, lalu biarkan keduanya melayang di sana.",
               lambda c, ev: formation_at(c, ev, ("alpha", "charlie"), 18, 16, d25, -d25),
               [_formation(("alpha", "charlie"), "line", 18, 16, north=d25, east=-d25)],
               "Alpha dan charlie melayang berdampingan 25 m ke barat laut pada 18 m."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("formation", "dev", "form8-wedge-feet-overhead", three,
               "Put the three drones in a V, 40 ft between neighbours, 60 ft up, right above where they are now, "
               "and hold them there.",
               lambda c, ev: formation_at(c, ev, three, 60 * FT, 40 * FT, 0, 0),
               [_formation(three, "wedge", 60 * FT, 40 * FT)],
               "The three hold a V at 60 ft (18.3 m), 40 ft (12.2 m) apart."),
        # relative
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("relative", "dev", "rel8-sl-bravo-se-and-up", ("bravo",),
               "Premakni bravo 20 metrov proti jugovzhodu in ga hkrati dvigni za 6 metrov; pred tem naj vzleti na "
               "10 metrov. Nato naj tam lebdi.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", -d20, d20), alt=16), airborne_at(ev, "bravo", 16)),
               [_takeoff("bravo", 10), _move("bravo", -d20, d20, up=6)], "Bravo lebdi 20 m jugovzhodno na 16 m."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("relative", "dev", "rel8-vi-charlie-ne-then-lower", ("charlie",),
               "Cho charlie bay 30 mét về phía đông bắc ở độ cao 12 mét, sau đó hạ độ cao xuống còn 6 mét và giữ "
               "nguyên ở đó.",
               lambda c, ev: _all(rose_to(ev, "charlie", 12), at(ev, "charlie", *c.point("charlie", d30, d30), alt=6),
                                  airborne_at(ev, "charlie", 6)),
               [_move("charlie", d30, d30, alt=12), _move("charlie", alt=6)],
               "Charlie đang lơ lửng 30 m về phía đông bắc, ở độ cao 6 m."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("relative", "dev", "rel8-alpha-third-back", ("alpha",),
               "Take alpha to 15 m, fly it 60 m north, then bring it a third of that distance back towards home and "
               "let it hover.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 60, 0)]),
                                  at(ev, "alpha", *c.point("alpha", 40, 0), alt=15), airborne_at(ev, "alpha", 15)),
               [_takeoff("alpha", 15), _move("alpha", 60, 0), _move("alpha", -20, 0)], "Alpha hovers 40 m north at 15 m."),
        # question
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("question", "dev", "ask8-uk-lowest-charge", three,
               "У якого дрона найменше заряду і скільки саме відсотків у нього лишилося? Нічого не запускай.",
               lambda c, ev: _all(answer_says(ev, r"\bcharlie\b", "charlie"), answer_mentions_number(ev, 41, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Найменше в charlie: 41 %.",
               battery={"alpha": 77.0, "bravo": 58.0, "charlie": 41.0}),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("question", "dev", "ask8-et-alpha-charge-anyone-flying", three,
               "Kas mõni droon on praegu õhus? Ütle mulle ka, kui palju akut alphal alles on. Ära midagi õhku saada.",
               lambda c, ev: _all(answer_mentions_number(ev, 69, 1), nobody_armed(ev)),
               [("fleet_status", {})], "Ükski droon ei ole õhus; alphal on 69 %.",
               battery={"alpha": 69.0, "bravo": 83.0, "charlie": 74.0}),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("question", "dev", "ask8-which-below-half", three,
               "Are all three drones above 50 % battery? Tell me which ones are not. Don't launch anything.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 46, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Not all: bravo has 46 %.",
               battery={"alpha": 72.0, "bravo": 46.0, "charlie": 63.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("refusal", "dev", "refuse8-ru-alpha-450-feet", ("alpha",),
               "Подними alpha на высоту 450 футов.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "alpha", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("alpha", 450 * FT)], "The gateway refused: 450 ft (137 m) is above the 120 m altitude limit."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("refusal", "dev", "refuse8-lt-charlie-far-east", ("charlie",),
               "Nuskraidink charlie 1,3 kilometro į rytus 25 metrų aukštyje.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "charlie", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("charlie", 0, 1300, alt=25)], "The gateway refused: 1.3 km is beyond the 1000 m limit."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("refusal", "dev", "refuse8-all-three-one-low", three,
               "Launch all three to 12 m and keep them up there.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 12), airborne_at(ev, "bravo", 12), refusal_seen(ev, "battery"),
                                  never_armed(ev, "charlie"), answer_reports_refusal(ev)),
               [_takeoff("alpha", 12), _takeoff("bravo", 12), _takeoff("charlie", 12)],
               "Alpha and bravo hover at 12 m; charlie was refused: its battery (22 %) is below the 30 % to take off.",
               battery={"alpha": 80.0, "bravo": 75.0, "charlie": 22.0}),
        # units
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("units", "dev", "units8-bg-alpha-feet-yards", ("alpha",),
               "Издигни alpha на 45 фута, после я придвижи 100 ярда на север и я остави да виси там.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 100 * YD, 0), alt=45 * FT),
                                  airborne_at(ev, "alpha", 45 * FT)),
               [_takeoff("alpha", 45 * FT), _move("alpha", 100 * YD, 0)], "Alpha виси на 100 ярда северно, на 45 фута."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("units", "dev", "units8-es-bravo-km-feet-down", ("bravo",),
               "Sube a bravo a 12 metros, llévalo 0,05 km al sur y después bájalo 15 pies; déjalo ahí en el aire.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", -50, 0), alt=12 - 15 * FT),
                                  airborne_at(ev, "bravo", 12 - 15 * FT)),
               [_takeoff("bravo", 12), _move("bravo", -50, 0), _move("bravo", up=-15 * FT)],
               "Bravo flota 50 m al sur, a 7,4 m."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("units", "dev", "units8-charlie-cm-miles", ("charlie",),
               "Charlie: climb to 1500 cm, then fly 0.02 miles west and land there.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 15), at(ev, "charlie", *c.point("charlie", 0, -0.02 * MI)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), _move("charlie", 0, -0.02 * MI), _land("charlie")],
               "Charlie climbed to 15 m, flew 0.02 mi (32 m) west and landed."),
        # pattern
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("pattern", "dev", "pattern8-ru-alpha-pentagon-left", ("alpha",),
               "Пусть alpha на высоте 12 метров облетит пятиугольник со стороной 20 метров: первая сторона на "
               "восток, поворачивая налево, а потом приземлится там, где закончит.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(pentagon)[:4]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), *_legs("alpha", pentagon), _land("alpha")], "Alpha облетел пятиугольник и сел."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("pattern", "dev", "pattern8-lv-bravo-rectangle-left", ("bravo",),
               "Bravo 10 metru augstumā lai izlido taisnstūri: 40 metrus uz austrumiem, 15 metrus platu, griežoties "
               "pa kreisi; beigās lai atgriežas mājās.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(rectangle)[:3]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), *_legs("bravo", rectangle), _rtl("bravo")],
               "Bravo izlidoja taisnstūri un atgriezās mājās."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("pattern", "dev", "pattern8-charlie-ring-east-ccw", ("charlie",),
               "Fly charlie 30 m east at 12 m, circle that spot once counter-clockwise at a 12 m radius, then "
               "bring it home.",
               lambda c, ev: _all(*(visited(ev, "charlie", [c.point("charlie", n, e)]) for n, e in ring),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), *_legs("charlie", ring_legs), _rtl("charlie")],
               "Charlie circled the spot 30 m east and came home."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # alpha from charlie or charlie from alpha, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("placement", "dev", "place8-uk-alpha-above-charlie", ("alpha", "charlie"),
               "Підніми charlie на 10 метрів і відведи його на 20 метрів на схід. Потім постав alpha точно над "
               "charlie, на 10 метрів вище за нього.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 20), alt=10), airborne_at(ev, "charlie", 10),
                                  at(ev, "alpha", *c.point("charlie", 0, 20), alt=20), airborne_at(ev, "alpha", 20)),
               lambda c: [_takeoff("charlie", 10), _move("charlie", 0, 20), _go("alpha", c.point("charlie", 0, 20), 20)],
               "Charlie висить 20 м на схід на 10 м, alpha над ним на 20 м."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("placement", "dev", "place8-sl-alpha-sw-of-charlie", three,
               "Charlie naj vzleti na 14 metrov in tam lebdi. Nato postavi alpha 20 metrov jugozahodno od charlie, "
               "na isto višino, in naj tudi ona lebdi.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=14), airborne_at(ev, "charlie", 14),
                                  at(ev, "alpha", *c.point("charlie", -d20, -d20), alt=14), airborne_at(ev, "alpha", 14),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("charlie", 14), _go("alpha", c.point("charlie", -d20, -d20), 14)],
               "Charlie lebdi na 14 m; alpha 20 m jugozahodno od njega na isti višini."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("placement", "dev", "place8-charlie-north-of-parked-alpha", three,
               "Leave alpha parked where it is and send charlie to hover 20 m north of it at 15 m.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("alpha", 20, 0), alt=15), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               lambda c: [_go("charlie", c.point("alpha", 20, 0), 15)], "Charlie hovers 20 m north of alpha at 15 m."),
        # language
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("language", "dev", "lang8-ru-charlie-east-land", ("charlie",),
               "Подними charlie на 13 метров, пролети 35 метров на восток и посади его там.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 13), at(ev, "charlie", *c.point("charlie", 0, 35)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 13), _move("charlie", 0, 35), _land("charlie")], "Charlie пролетел 35 м на восток и сел."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("language", "dev", "lang8-vi-alpha-climb-more", ("alpha",),
               "Đưa alpha lên độ cao 9 mét, sau đó cho nó lên cao thêm 7 mét nữa và giữ nó ở đó.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=16), airborne_at(ev, "alpha", 16)),
               [_takeoff("alpha", 9), _move("alpha", up=7)], "Alpha đang ở độ cao 16 m."),
        # moved to dev on 2026-12-02, eighth round: the test half had been measured
        _entry("language", "dev", "lang8-et-bravo-south-home", ("bravo",),
               "Tõsta bravo 16 meetri kõrgusele, lennuta see 20 meetrit lõunasse ja too see siis koju tagasi ning "
               "maanda.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 16), visited(ev, "bravo", [c.point("bravo", -20, 0)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 16), _move("bravo", -20, 0), _rtl("bravo")], "Bravo lendas 20 m lõunasse, tuli koju ja maandus."),
    ]  # fmt: skip


def _ninth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-01 (ninth round), before any model ran on it: 3 a class; 22 of the
    33 outside ``language`` in other languages than English (Chinese, Czech, Dutch, French, German, Italian,
    Japanese, Korean, Polish, Portuguese, Romanian, Turkish), the ``language`` class's 3 in Japanese,
    Chinese and Korean; all of it moved to dev on 2026-12-02 (ninth round), once its figures had been
    measured."""
    three = DRONES
    d10, d20, d25, d30 = (x / math.sqrt(2) for x in (10, 20, 25, 30))
    square25 = _polygon_legs(4, 25.0, 0.0, right=True)  # north first, turning right
    hexagon12 = _polygon_legs(6, 12.0, 90.0, right=True)  # first side east, turning right
    # four lines of 40 m, the first north, 10 m apart, each next line east of the one before
    lines = [(40.0, 0.0), (0.0, 10.0), (-40.0, 0.0), (0.0, 10.0), (40.0, 0.0), (0.0, 10.0), (-40.0, 0.0)]
    return [
        # single
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("single", "dev", "single9-ja-bravo-hover", ("bravo",),
               "bravoを15メートルまで上昇させて、そのままホバリングさせて。",
               lambda c, ev: airborne_at(ev, "bravo", 15),
               [_takeoff("bravo", 15)], "bravoは15 mでホバリング中。"),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("single", "dev", "single9-pt-alpha-hop", ("alpha",),
               "Levanta o alpha a 9 metros e pousa-o logo a seguir no mesmo sítio.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 9), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 9), _land("alpha")], "O alpha subiu a 9 m e pousou."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("single", "dev", "single9-charlie-park-in-air", ("charlie",),
               "Send charlie straight up to 28 m and park it in the air.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=28), airborne_at(ev, "charlie", 28)),
               [_takeoff("charlie", 28)], "Charlie hovers at 28 m over its pad."),
        # multi
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("multi", "dev", "multi9-de-pair-hop-bravo-stays", three,
               "Lass alpha und charlie auf 12 Meter steigen und gleich wieder landen; bravo bleibt am Boden.",
               lambda c, ev: _all(*(reached_alt(ev, d, 12) for d in ("alpha", "charlie")),
                                  *(at(ev, d, *_home(c, d)) for d in ("alpha", "charlie")),
                                  *(landed_disarmed(ev, d) for d in ("alpha", "charlie")), never_armed(ev, "bravo")),
               [_takeoff("alpha", 12), _takeoff("charlie", 12), _land("alpha"), _land("charlie")],
               "Alpha und charlie waren auf 12 m und sind gelandet; bravo blieb am Boden."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("multi", "dev", "multi9-zh-west-and-north", three,
               "让 alpha 向西飞 20 米，bravo 向北飞 20 米，高度都是 10 米，然后都悬停在那里。",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, -20), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "bravo", *c.point("bravo", 20, 0), alt=10), airborne_at(ev, "bravo", 10),
                                  never_armed(ev, "charlie")),
               [_move("alpha", 0, -20, alt=10), _move("bravo", 20, 0, alt=10)],
               "alpha 在西边 20 米、bravo 在北边 20 米悬停，高度 10 米。"),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("multi", "dev", "multi9-bravo-down-charlie-stays", three,
               "Put bravo at 10 m and charlie at 25 m over their own spots, then bring bravo back down; charlie "
               "keeps hovering.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 10), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo"), airborne_at(ev, "charlie", 25),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=25), never_armed(ev, "alpha")),
               [_takeoff("bravo", 10), _takeoff("charlie", 25), _land("bravo")],
               "Bravo went up to 10 m and landed; charlie hovers at 25 m."),
        # compound
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("compound", "dev", "compound9-pl-bravo-east-south-land", ("bravo",),
               "Wznieś bravo na 15 metrów, przeleć nim 40 metrów na wschód, potem 10 metrów na południe i tam "
               "wyląduj.",
               lambda c, ev: _all(rose_to(ev, "bravo", 15), visited(ev, "bravo", [c.point("bravo", 0, 40)]),
                                  at(ev, "bravo", *c.point("bravo", -10, 40)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 15), _move("bravo", 0, 40), _move("bravo", -10, 0), _land("bravo")],
               "Bravo przeleciał 40 m na wschód i 10 m na południe, i wylądował."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("compound", "dev", "compound9-tr-alpha-out-back-hover", ("alpha",),
               "alpha'yı 10 metreye kaldır, 30 metre kuzeye uçur, sonra 30 metre güneye geri getir ve orada "
               "havada beklet.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 30, 0)]),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=10), airborne_at(ev, "alpha", 10)),
               [_takeoff("alpha", 10), _move("alpha", 30, 0), _move("alpha", -30, 0)],
               "alpha 30 m kuzeye gidip döndü, 10 m'de bekliyor."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("compound", "dev", "compound9-charlie-climb-between-home", ("charlie",),
               "Charlie: take off to 8 m, go 20 m northeast, climb another 12 m, then come home.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", d20, d20)]), rose_to(ev, "charlie", 20),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 8), _move("charlie", d20, d20), _move("charlie", up=12), _rtl("charlie")],
               "Charlie flew 20 m northeast, climbed to 20 m and came home."),
        # conditional
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("conditional", "dev", "cond9-fr-charlie-up-if-charged", ("charlie",),
               "Si la batterie de charlie dépasse 60 %, fais-le monter à 20 m et qu'il reste là ; sinon ne fais rien.",
               lambda c, ev: _all(airborne_at(ev, "charlie", 20), at(ev, "charlie", *_home(c, "charlie"), alt=20)),
               [_battery("charlie"), _takeoff("charlie", 20)], "Charlie a 72 % : il est monté à 20 m.",
               battery={"charlie": 72.0}),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("conditional", "dev", "cond9-ro-bravo-low-lands-at-once", ("bravo",),
               "Ridică bravo la 18 metri. Dacă bateria lui e sub 40 %, aterizează-l imediat; altfel trimite-l 25 "
               "de metri spre vest și lasă-l acolo.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 18), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 18), _battery("bravo"), _land("bravo")],
               "Bravo are 35 %, așa că a aterizat imediat.", battery={"bravo": 35.0}),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("conditional", "dev", "cond9-alpha-far-or-near", ("alpha",),
               "If alpha has at least 80 % battery, fly it 50 m south at 15 m and land there; with less, only "
               "20 m south, and land there too.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", -20, 0)), landed_disarmed(ev, "alpha"),
                                  stayed_within(ev, c, "alpha", 30)),
               [_battery("alpha"), _move("alpha", -20, 0, alt=15), _land("alpha")],
               "Alpha has 65 %, so it flew 20 m south and landed.", battery={"alpha": 65.0}),
        # formation
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("formation", "dev", "form9-pt-line-north-hover", three,
               "Coloca os três drones em linha, a 10 metros uns dos outros, a 20 metros de altura, 40 metros a "
               "norte de onde estão, e deixa-os pairar.",
               lambda c, ev: formation_at(c, ev, three, 20, 10, 40, 0),
               [_formation(three, "line", 20, 10, north=40)], "Os três pairam em linha 40 m a norte, a 20 m."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("formation", "dev", "form9-ko-pair-column-overhead", ("alpha", "bravo"),
               "alpha와 bravo를 8미터 간격으로 세로로 줄지어 12미터 높이에 세우고, 지금 위치 그대로 떠 있게 해.",
               lambda c, ev: formation_at(c, ev, ("alpha", "bravo"), 12, 8, 0, 0),
               [_formation(("alpha", "bravo"), "column", 12, 8)], "alpha와 bravo가 12 m에서 8 m 간격으로 떠 있음."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("formation", "dev", "form9-triangle-west-land", three,
               "Fly all three in a triangle, 15 m on each side, at 12 m, 30 m west of here, then land them there.",
               lambda c, ev: landed_formation_at(c, ev, three, 15, 0, -30),
               [_formation(three, "circle", 12, 15, east=-30), *(_land(d) for d in three)],
               "The three flew a 15 m triangle 30 m west and landed."),
        # relative
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("relative", "dev", "rel9-it-bravo-south-lower", ("bravo",),
               "Porta bravo a 20 metri, poi spostalo 25 metri a sud e abbassalo di 8 metri, e lascialo lì.",
               lambda c, ev: _all(rose_to(ev, "bravo", 20), at(ev, "bravo", *c.point("bravo", -25, 0), alt=12),
                                  airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 20), _move("bravo", -25, 0, up=-8)], "Bravo è 25 m a sud, a 12 m."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("relative", "dev", "rel9-nl-charlie-west-twice", ("charlie",),
               "Laat charlie opstijgen tot 10 meter, vlieg 15 meter naar het westen en daarna nog eens 15 meter, "
               "en laat hem daar hangen.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, -30), alt=10), airborne_at(ev, "charlie", 10)),
               [_takeoff("charlie", 10), _move("charlie", 0, -15), _move("charlie", 0, -15)],
               "Charlie hangt 30 m naar het westen op 10 m."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("relative", "dev", "rel9-alpha-sw-then-back-ne", ("alpha",),
               "Alpha to 12 m, then 30 m south-west, then 10 m back north-east, and hover.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -d30, -d30)]),
                                  at(ev, "alpha", *c.point("alpha", -d20, -d20), alt=12), airborne_at(ev, "alpha", 12)),
               [_takeoff("alpha", 12), _move("alpha", -d30, -d30), _move("alpha", d10, d10)],
               "Alpha hovers 20 m south-west of its pad at 12 m."),
        # question
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("question", "dev", "ask9-ja-fullest", three,
               "一番バッテリーが残っているドローンはどれ？何パーセント？飛ばさないで。",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 91, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "一番多いのは bravo: 91 %。",
               battery={"alpha": 62.0, "bravo": 91.0, "charlie": 70.0}),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("question", "dev", "ask9-pl-charlie-enough", three,
               "Ile baterii ma charlie? Czy to wystarczy, żeby wystartował? Nic nie uruchamiaj.",
               lambda c, ev: _all(answer_mentions_number(ev, 27, 1), nobody_armed(ev)),
               [("fleet_status", {})], "Charlie ma 27 %: za mało do startu (30 %).",
               battery={"alpha": 80.0, "bravo": 75.0, "charlie": 27.0}),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("question", "dev", "ask9-alpha-and-charlie-figures", three,
               "What battery do alpha and charlie have? Give me each figure; nothing flies.",
               lambda c, ev: _all(answer_mentions_number(ev, 58, 1), answer_mentions_number(ev, 84, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Alpha 58 %, charlie 84 %.",
               battery={"alpha": 58.0, "bravo": 66.0, "charlie": 84.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("refusal", "dev", "refuse9-tr-bravo-2km-west", ("bravo",),
               "bravo'yu 15 metre yükseklikte 2 kilometre batıya uçur.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "bravo", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("bravo", 0, -2000, alt=15)], "The gateway refused: 2 km is beyond the 1000 m limit."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("refusal", "dev", "refuse9-de-charlie-130m", ("charlie",),
               "Schick charlie auf 130 Meter Höhe.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "charlie", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("charlie", 130)], "The gateway refused: 130 m is above the 120 m altitude limit."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("refusal", "dev", "refuse9-alpha-drained", ("alpha",),
               "Take alpha up to 15 m and fly it 20 m east.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "alpha"), answer_reports_refusal(ev)),
               [_takeoff("alpha", 15), _move("alpha", 0, 20)],
               "The gateway refused: alpha's battery (18 %) is below the 30 % to take off.", battery={"alpha": 18.0}),
        # units
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("units", "dev", "units9-ro-bravo-feet-km", ("bravo",),
               "Ridică bravo la 50 de picioare, apoi du-l 0,04 km spre est și lasă-l acolo.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, 40), alt=50 * FT),
                                  airborne_at(ev, "bravo", 50 * FT)),
               [_takeoff("bravo", 50 * FT), _move("bravo", 0, 40)], "Bravo plutește 40 m spre est, la 15,2 m."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("units", "dev", "units9-cs-charlie-yards-land", ("charlie",),
               "Vzlétni s charlie do 12 metrů, přeleť 30 yardů na sever a přistaň.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 12), at(ev, "charlie", *c.point("charlie", 30 * YD, 0)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), _move("charlie", 30 * YD, 0), _land("charlie")],
               "Charlie přeletěl 30 yardů (27 m) na sever a přistál."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("units", "dev", "units9-alpha-feet-yards-se", ("alpha",),
               "Alpha: 60 ft up, then 25 yards south-east, and hover there.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", -25 * YD / math.sqrt(2), 25 * YD / math.sqrt(2)),
                                     alt=60 * FT), airborne_at(ev, "alpha", 60 * FT)),
               [_takeoff("alpha", 60 * FT), _move("alpha", -25 * YD / math.sqrt(2), 25 * YD / math.sqrt(2))],
               "Alpha hovers 25 yd (23 m) south-east at 60 ft (18.3 m)."),
        # pattern
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("pattern", "dev", "pattern9-de-alpha-square-right", ("alpha",),
               "alpha soll in 10 Metern Höhe ein Quadrat mit 25 Meter Seitenlänge fliegen, erste Seite nach "
               "Norden, rechts herum, und danach landen.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(square25)[:3]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), *_legs("alpha", square25), _land("alpha")], "Alpha flog das Quadrat und landete."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("pattern", "dev", "pattern9-zh-bravo-hexagon-home", ("bravo",),
               "让 bravo 在 15 米高度飞一个边长 12 米的六边形，第一条边朝东，向右转，飞完后返航。",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(hexagon12)[:5]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 15), *_legs("bravo", hexagon12), _rtl("bravo")], "bravo 飞完六边形并返航。"),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("pattern", "dev", "pattern9-charlie-four-lines-east", ("charlie",),
               "Survey with charlie at 15 m: 4 lines of 40 m, 10 m apart, the first line north, each next line "
               "east of the last, then bring it home.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(lines)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), *_legs("charlie", lines), _rtl("charlie")],
               "Charlie flew the four lines and came home."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # alpha from charlie or charlie from alpha, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("placement", "dev", "place9-fr-charlie-east-of-alpha", three,
               "Fais décoller alpha à 12 m et laisse-le en l'air. Ensuite envoie charlie 15 m à l'est d'alpha, à "
               "la même hauteur.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", 0, 15), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 12), _go("charlie", c.point("alpha", 0, 15), 12)],
               "Alpha est à 12 m ; charlie est 15 m à l'est d'alpha, à 12 m."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("placement", "dev", "place9-ko-alpha-north-of-charlie", three,
               "charlie 북쪽 25미터 지점으로 alpha를 보내서 10미터 높이에서 떠 있게 해. charlie는 그대로 둬.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("charlie", 25, 0), alt=10), airborne_at(ev, "alpha", 10),
                                  never_armed(ev, "charlie"), never_armed(ev, "bravo")),
               lambda c: [_go("alpha", c.point("charlie", 25, 0), 10)], "alpha는 charlie 북쪽 25 m, 10 m 높이에 있음."),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("placement", "dev", "place9-alpha-north-of-moved-charlie", three,
               "Fly charlie 30 m east at 12 m. Then put alpha 10 m north of where charlie is, at the same height.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 30), alt=12), airborne_at(ev, "charlie", 12),
                                  at(ev, "alpha", *c.point("charlie", 10, 30), alt=12), airborne_at(ev, "alpha", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("charlie", 0, 30, alt=12), _go("alpha", c.point("charlie", 10, 30), 12)],
               "Charlie hovers 30 m east at 12 m; alpha 10 m north of it."),
        # language
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("language", "dev", "lang9-ja-charlie-north-land", ("charlie",),
               "charlieを12メートルまで上げて、北へ30メートル飛ばしてから、そこに着陸させて。",
               lambda c, ev: _all(reached_alt(ev, "charlie", 12), at(ev, "charlie", *c.point("charlie", 30, 0)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), _move("charlie", 30, 0), _land("charlie")], "charlieは北へ30 m飛んで着陸した。"),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("language", "dev", "lang9-zh-alpha-southwest-land", ("alpha",),
               "把 alpha 升到 14 米，向西南飞 25 米，然后在那里降落。",
               lambda c, ev: _all(reached_alt(ev, "alpha", 14), at(ev, "alpha", *c.point("alpha", -d25, -d25)),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 14), _move("alpha", -d25, -d25), _land("alpha")], "alpha 向西南飞了 25 米并降落。"),
        # moved to dev on 2026-12-02, ninth round: the test half had been measured
        _entry("language", "dev", "lang9-ko-bravo-east-hover", ("bravo",),
               "bravo를 16미터로 올리고 동쪽으로 20미터 이동한 다음 거기서 계속 떠 있게 해.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, 20), alt=16), airborne_at(ev, "bravo", 16)),
               [_takeoff("bravo", 16), _move("bravo", 0, 20)], "bravo는 동쪽 20 m, 16 m 높이에 떠 있음."),
    ]  # fmt: skip


def _tenth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-02 (tenth round), before any model ran on it: 3 a class; 22 of the
    33 outside ``language`` in other languages than English (Arabic, Catalan, Danish, Finnish, Greek, Hindi,
    Hungarian, Indonesian, Norwegian, Russian, Spanish, Swedish, Ukrainian, Vietnamese), the ``language``
    class's 3 in Arabic, Hindi and Thai (Arabic, Devanagari and Thai script are new); all of it moved to dev
    later on 2026-12-02 (tenth round), once its figures had been measured."""
    three = DRONES
    d20yd = 20 * YD / math.sqrt(2)
    triangle20 = _polygon_legs(3, 20.0, 180.0, right=False)  # first side south, turning left
    square20 = _polygon_legs(4, 20.0, 270.0, right=False)  # first side west, turning left
    pentagon15 = _polygon_legs(5, 15.0, 90.0, right=True)  # first side east, turning right
    return [
        # single
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("single", "dev", "single10-es-charlie-hover", ("charlie",),
               "Sube a charlie hasta 22 metros y déjalo quieto en el aire.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=22), airborne_at(ev, "charlie", 22)),
               [_takeoff("charlie", 22)], "Charlie está quieto a 22 m."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("single", "dev", "single10-ar-alpha-hop", ("alpha",),
               "ارفع alpha إلى 10 أمتار ثم أنزله في مكانه.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 10), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _land("alpha")], "ارتفع alpha إلى 10 m ثم هبط."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("single", "dev", "single10-bravo-sit-at-35", ("bravo",),
               "Launch bravo and let it sit at 35 m.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=35), airborne_at(ev, "bravo", 35)),
               [_takeoff("bravo", 35)], "Bravo sits at 35 m over its pad."),
        # multi
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("multi", "dev", "multi10-sv-all-three-hover", three,
               "Lyft alla tre drönarna till 15 meter och låt dem sväva där.",
               lambda c, ev: _all(*(at(ev, d, *_home(c, d), alt=15) for d in three),
                                  *(airborne_at(ev, d, 15) for d in three)),
               [_takeoff(d, 15) for d in three], "Alla tre svävar på 15 m."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("multi", "dev", "multi10-hi-alpha-north-charlie-hop", three,
               "alpha को 10 मीटर की ऊँचाई पर 20 मीटर उत्तर ले जाओ, और charlie को 8 मीटर तक उठाकर वापस उतार दो।",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 0), alt=10), airborne_at(ev, "alpha", 10),
                                  reached_alt(ev, "charlie", 8), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie"), never_armed(ev, "bravo")),
               [_move("alpha", 20, 0, alt=10), _takeoff("charlie", 8), _land("charlie")],
               "alpha 20 m उत्तर में 10 m पर है; charlie 8 m तक जाकर उतर गया।"),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("multi", "dev", "multi10-two-heights-both-land", three,
               "Take bravo to 10 m and charlie to 20 m, then land both of them; alpha stays put.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 10), reached_alt(ev, "charlie", 20),
                                  *(at(ev, d, *_home(c, d)) for d in ("bravo", "charlie")),
                                  *(landed_disarmed(ev, d) for d in ("bravo", "charlie")), never_armed(ev, "alpha")),
               [_takeoff("bravo", 10), _takeoff("charlie", 20), _land("bravo"), _land("charlie")],
               "Bravo went to 10 m and charlie to 20 m; both landed. Alpha stayed down."),
        # compound
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("compound", "dev", "compound10-hu-alpha-west-north-home", ("alpha",),
               "Emeld alpha-t 12 méterre, repülj vele 20 métert nyugatra, aztán 20 métert északra, végül hozd haza.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, -20), c.point("alpha", 20, -20)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), _move("alpha", 0, -20), _move("alpha", 20, 0), _rtl("alpha")],
               "Alpha repült nyugatra, majd északra, és hazajött."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("compound", "dev", "compound10-el-charlie-east-climb-land", ("charlie",),
               "Σήκωσε το charlie στα 10 μέτρα, πέτα το 25 μέτρα ανατολικά, ανέβασέ το άλλα 10 μέτρα και μετά "
               "προσγείωσέ το εκεί.",
               lambda c, ev: _all(rose_to(ev, "charlie", 20), at(ev, "charlie", *c.point("charlie", 0, 25)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", 0, 25), _move("charlie", up=10), _land("charlie")],
               "Το charlie πέταξε 25 m ανατολικά, ανέβηκε στα 20 m και προσγειώθηκε."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("compound", "dev", "compound10-bravo-south-east-hold", ("bravo",),
               "Bravo: up to 14 m, 15 m south, 15 m east, then hold there in the air.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", -15, 0)]),
                                  at(ev, "bravo", *c.point("bravo", -15, 15), alt=14), airborne_at(ev, "bravo", 14)),
               [_takeoff("bravo", 14), _move("bravo", -15, 0), _move("bravo", 0, 15)],
               "Bravo holds 15 m south and 15 m east of its pad at 14 m."),
        # conditional
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("conditional", "dev", "cond10-es-alpha-north-if-charged", ("alpha",),
               "Si alpha tiene más del 50 % de batería, llévalo 30 m al norte a 12 m de altura y déjalo allí; si "
               "no, déjalo en tierra.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 30, 0), alt=12), airborne_at(ev, "alpha", 12)),
               [_battery("alpha"), _move("alpha", 30, 0, alt=12)], "Alpha tiene 78 %: está 30 m al norte a 12 m.",
               battery={"alpha": 78.0}),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("conditional", "dev", "cond10-sv-charlie-low-stays", ("charlie",),
               "Om charlies batteri är under 45 %, låt den stå kvar på marken; annars lyft den till 16 meter och "
               "landa igen.",
               lambda c, ev: _all(never_armed(ev, "charlie"), answer_mentions_number(ev, 40, 2)),
               [_battery("charlie")], "Charlie har 40 %: den står kvar på marken.", battery={"charlie": 40.0}),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("conditional", "dev", "cond10-bravo-at-least-70-goes-high", ("bravo",),
               "If bravo's battery is at least 70 %, send it up to 25 m and bring it home; otherwise only up to "
               "10 m and land.",
               lambda c, ev: _all(rose_to(ev, "bravo", 25), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo")),
               [_battery("bravo"), _takeoff("bravo", 25), _rtl("bravo")],
               "Bravo has 70 %, so it went up to 25 m and came home.", battery={"bravo": 70.0}),
        # formation
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("formation", "dev", "form10-es-column-south", three,
               "Pon a alpha, bravo y charlie en columna, separados 8 m, a 15 m de altura y 30 m al sur de donde "
               "están; que se queden ahí.",
               lambda c, ev: _all(formation_at(c, ev, three, 15, 8, -30, 0), farthest_apart(ev, three, 16)),
               [_formation(three, "column", 15, 8, north=-30)], "Los tres están en columna 30 m al sur, a 15 m."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("formation", "dev", "form10-da-pair-east-land", ("alpha", "charlie"),
               "Flyv alpha og charlie side om side med 12 meters afstand i 10 meters højde, 20 meter mod øst, og "
               "land dem der.",
               lambda c, ev: landed_formation_at(c, ev, ("alpha", "charlie"), 12, 0, 20),
               [_formation(("alpha", "charlie"), "line", 10, 12, east=20), _land("alpha"), _land("charlie")],
               "Alpha og charlie fløj 20 m mod øst og landede 12 m fra hinanden."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("formation", "dev", "form10-ring-overhead", three,
               "Put the three drones in a circle with 10 m between neighbours at 18 m, right above where they "
               "stand, and keep them there.",
               lambda c, ev: _all(formation_at(c, ev, three, 18, 10, 0, 0), farthest_apart(ev, three, 10)),
               [_formation(three, "circle", 18, 10)], "The three hold a 10 m ring at 18 m overhead."),
        # relative
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("relative", "dev", "rel10-fi-alpha-higher-north", ("alpha",),
               "Nosta alpha 10 metriin, sitten 5 metriä ylemmäs ja 20 metriä pohjoiseen, ja jätä se sinne.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 0), alt=15), airborne_at(ev, "alpha", 15)),
               [_takeoff("alpha", 10), _move("alpha", 20, 0, up=5)], "Alpha on 20 m pohjoiseen, 15 m korkeudessa."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("relative", "dev", "rel10-no-bravo-east-half-back", ("bravo",),
               "Løft bravo til 12 meter, fly 40 meter østover og deretter 20 meter tilbake vestover, og la den "
               "sveve der.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, 40)]),
                                  at(ev, "bravo", *c.point("bravo", 0, 20), alt=12), airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 12), _move("bravo", 0, 40), _move("bravo", 0, -20)],
               "Bravo svever 20 m øst for hjemmet, på 12 m."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("relative", "dev", "rel10-charlie-drop-and-west", ("charlie",),
               "Charlie up to 25 m, then drop it by 15 m and move it 10 m west; keep it flying.",
               lambda c, ev: _all(rose_to(ev, "charlie", 25), at(ev, "charlie", *c.point("charlie", 0, -10), alt=10),
                                  airborne_at(ev, "charlie", 10)),
               [_takeoff("charlie", 25), _move("charlie", 0, -10, up=-15)], "Charlie flies 10 m west at 10 m."),
        # question
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("question", "dev", "ask10-ru-lowest-charge", three,
               "Какой дрон разряжен больше всех и сколько у него осталось? Ничего не запускай.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 45, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Меньше всего у bravo: 45 %.",
               battery={"alpha": 77.0, "bravo": 45.0, "charlie": 63.0}),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("question", "dev", "ask10-ar-every-battery", three,
               "كم نسبة البطارية في كل طائرة؟ لا تُقلع أيًّا منها.",
               lambda c, ev: _all(answer_mentions_number(ev, 81, 1), answer_mentions_number(ev, 67, 1),
                                  answer_mentions_number(ev, 54, 1), nobody_armed(ev)),
               [("fleet_status", {})], "alpha 81 %، bravo 67 %، charlie 54 %.",
               battery={"alpha": 81.0, "bravo": 67.0, "charlie": 54.0}),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("question", "dev", "ask10-bravo-charge-no-move", three,
               "How much charge is left in bravo? Just tell me, don't move anything.",
               lambda c, ev: _all(answer_mentions_number(ev, 73, 1), nobody_armed(ev)),
               [("fleet_status", {})], "Bravo has 73 %.", battery={"alpha": 60.0, "bravo": 73.0, "charlie": 88.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off)
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("refusal", "dev", "refuse10-vi-alpha-150m", ("alpha",),
               "Đưa alpha lên độ cao 150 mét.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "alpha", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("alpha", 150)], "The gateway refused: 150 m is above the 120 m altitude limit."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("refusal", "dev", "refuse10-sv-bravo-drained", ("bravo",),
               "Lyft bravo till 12 meter och flyg den 30 meter norrut.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "bravo"), answer_reports_refusal(ev)),
               [_takeoff("bravo", 12), _move("bravo", 30, 0)],
               "The gateway refused: bravo's battery (22 %) is below the 30 % to take off.", battery={"bravo": 22.0}),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("refusal", "dev", "refuse10-charlie-one-and-a-half-km", ("charlie",),
               "Fly charlie 1.5 km north at 20 m.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "charlie", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("charlie", 1500, 0, alt=20)], "The gateway refused: 1.5 km is beyond the 1000 m limit."),
        # units
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("units", "dev", "units10-ca-alpha-feet-hover", ("alpha",),
               "Puja alpha a 45 peus i deixa'l suspès a l'aire.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=45 * FT), airborne_at(ev, "alpha", 45 * FT)),
               [_takeoff("alpha", 45 * FT)], "Alpha és suspès a 45 peus (13,7 m)."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("units", "dev", "units10-hu-bravo-km-west-land", ("bravo",),
               "Emeld bravo-t 10 méterre, vidd 0,03 kilométerre nyugatra, és ott tedd le.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 10), at(ev, "bravo", *c.point("bravo", 0, -30)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), _move("bravo", 0, -30), _land("bravo")], "Bravo 30 m-rel nyugatra leszállt."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("units", "dev", "units10-charlie-feet-yards-nw", ("charlie",),
               "Charlie: climb to 30 feet, fly 20 yards north-west, and land.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 30 * FT), at(ev, "charlie", *c.point("charlie", d20yd, -d20yd)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 30 * FT), _move("charlie", d20yd, -d20yd), _land("charlie")],
               "Charlie flew 20 yd (18 m) north-west and landed."),
        # pattern
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("pattern", "dev", "pattern10-es-charlie-triangle-left", ("charlie",),
               "Que charlie vuele un triángulo de 20 m de lado a 12 m de altura, primer lado hacia el sur, girando "
               "a la izquierda, y que aterrice al final.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(triangle20)[:2]]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), *_legs("charlie", triangle20), _land("charlie")],
               "Charlie voló el triángulo y aterrizó."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("pattern", "dev", "pattern10-el-alpha-square-left", ("alpha",),
               "Πέτα το alpha σε τετράγωνο πλευράς 20 μέτρων στα 15 μέτρα, πρώτη πλευρά προς τα δυτικά, στρίβοντας "
               "αριστερά, και μετά άφησέ το να αιωρείται.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(square20)[:3]]),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=15), airborne_at(ev, "alpha", 15)),
               [_takeoff("alpha", 15), *_legs("alpha", square20)], "Το alpha πέταξε το τετράγωνο και αιωρείται."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("pattern", "dev", "pattern10-bravo-pentagon-home", ("bravo",),
               "Bravo flies a pentagon at 10 m, sides of 15 m, first side east, turning right, then returns home.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(pentagon15)[:4]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), *_legs("bravo", pentagon15), _rtl("bravo")], "Bravo flew the pentagon and came home."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # alpha from charlie or charlie from alpha, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("placement", "dev", "place10-uk-charlie-north-of-alpha", three,
               "Відправ charlie на 20 метрів на північ від alpha, на висоту 15 метрів, і залиш його там.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("alpha", 20, 0), alt=15), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               lambda c: [_go("charlie", c.point("alpha", 20, 0), 15)], "charlie на 20 м на північ від alpha, на 15 м."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("placement", "dev", "place10-id-alpha-west-of-charlie", three,
               "Terbangkan alpha ke titik 15 meter di sebelah barat charlie, pada ketinggian 10 meter, dan biarkan "
               "di sana.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("charlie", 0, -15), alt=10), airborne_at(ev, "alpha", 10),
                                  never_armed(ev, "charlie"), never_armed(ev, "bravo")),
               lambda c: [_go("alpha", c.point("charlie", 0, -15), 10)], "alpha 15 m di barat charlie, pada 10 m."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("placement", "dev", "place10-charlie-south-of-hovering-alpha", three,
               "Take alpha up to 15 m and leave it. Put charlie 10 m south of alpha at the same height.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=15), airborne_at(ev, "alpha", 15),
                                  at(ev, "charlie", *c.point("alpha", -10, 0), alt=15), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 15), _go("charlie", c.point("alpha", -10, 0), 15)],
               "Alpha hovers at 15 m; charlie 10 m south of it at 15 m."),
        # language
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("language", "dev", "lang10-ar-bravo-north-land", ("bravo",),
               "ارفع bravo إلى 15 مترًا، ثم طر به 30 مترًا نحو الشمال، ثم أنزله هناك.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 15), at(ev, "bravo", *c.point("bravo", 30, 0)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 15), _move("bravo", 30, 0), _land("bravo")], "طار bravo 30 m شمالًا وهبط."),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("language", "dev", "lang10-hi-charlie-east-hover", ("charlie",),
               "charlie को 12 मीटर तक उठाओ, फिर 25 मीटर पूर्व की ओर ले जाओ और वहीं हवा में रहने दो।",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 25), alt=12), airborne_at(ev, "charlie", 12)),
               [_takeoff("charlie", 12), _move("charlie", 0, 25)], "charlie 25 m पूर्व में 12 m पर है।"),
        # moved to dev on 2026-12-02, tenth round: the test half had been measured
        _entry("language", "dev", "lang10-th-alpha-south-home", ("alpha",),
               "ยก alpha ขึ้นไปที่ 10 เมตร บินไปทางใต้ 20 เมตร แล้วพากลับบ้าน",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -20, 0)]), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", -20, 0), _rtl("alpha")], "alpha บินไปทางใต้ 20 m แล้วกลับบ้าน"),
    ]  # fmt: skip


def _eleventh_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-02 (eleventh round), before any model ran on it: 3 a class; 22 of
    the 33 outside ``language`` in other languages than English (Bulgarian, Chinese, Croatian, Czech, Dutch,
    Estonian, French, Italian, Japanese, Korean, Latvian, Lithuanian, Malay, Polish, Romanian, Slovak,
    Slovenian, Swahili, Tagalog, Turkish), the ``language`` class's 3 in Hebrew, Persian and Bengali (Hebrew
    and Bengali script are new); all of it moved to dev later on 2026-12-02 (eleventh round), once its
    figures had been measured."""
    three = DRONES
    d20, d25, d30 = (x / math.sqrt(2) for x in (20, 25, 30))
    d1200 = 1200 / math.sqrt(2)
    d80yd = 80 * YD / math.sqrt(2)
    d002mi = 0.02 * MI / math.sqrt(2)
    triangle25 = _polygon_legs(3, 25.0, 45.0, right=True)  # first side north-east, turning right
    # three passes of 30 m, the first west, 8 m apart, each next one south of the one before
    passes = [(0.0, -30.0), (-8.0, 0.0), (0.0, 30.0), (-8.0, 0.0), (0.0, -30.0)]
    rectangle = [(30.0, 0.0), (0.0, -10.0), (-30.0, 0.0), (0.0, 10.0)]  # 30 m north first, turning left
    return [
        # single
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("single", "dev", "single11-hr-alpha-hover", ("alpha",),
               "Podigni alpha na 24 metra iznad mjesta gdje stoji i neka tamo lebdi.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=24), airborne_at(ev, "alpha", 24)),
               [_takeoff("alpha", 24)], "Alpha lebdi na 24 m iznad svog mjesta."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("single", "dev", "single11-ms-charlie-hop", ("charlie",),
               "Naikkan charlie ke 7 meter, kemudian turunkan semula di tempat ia berlepas.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 7), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 7), _land("charlie")], "Charlie naik ke 7 m dan mendarat semula."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("single", "dev", "single11-bravo-low-hold", ("bravo",),
               "Bravo, lift off and hold at 6 metres over the pad until further notice.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=6), airborne_at(ev, "bravo", 6)),
               [_takeoff("bravo", 6)], "Bravo holds at 6 m over its pad."),
        # multi
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("multi", "dev", "multi11-sk-pair-south-north", three,
               "Pošli alpha 15 metrov na juh a charlie 15 metrov na sever, oba vo výške 11 metrov, a nechaj ich "
               "tam visieť; bravo ostane na zemi.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", -15, 0), alt=11), airborne_at(ev, "alpha", 11),
                                  at(ev, "charlie", *c.point("charlie", 15, 0), alt=11), airborne_at(ev, "charlie", 11),
                                  never_armed(ev, "bravo")),
               [_move("alpha", -15, 0, alt=11), _move("charlie", 15, 0, alt=11)],
               "Alpha visí 15 m na juh a charlie 15 m na sever, oba na 11 m; bravo je na zemi."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("multi", "dev", "multi11-sw-all-three-hop", three,
               "Paisha alpha, bravo na charlie hadi mita 9, kisha zishushe zote tatu pale zilipoanzia.",
               lambda c, ev: _all(*(reached_alt(ev, d, 9) for d in three), *(at(ev, d, *_home(c, d)) for d in three),
                                  *(landed_disarmed(ev, d) for d in three)),
               [*(_takeoff(d, 9) for d in three), *(_land(d) for d in three)],
               "Zote tatu zilipanda hadi 9 m na zikatua tena."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("multi", "dev", "multi11-charlie-west-alpha-same-height", three,
               "Lift charlie to 12 m and fly it 25 m west; once it's there, bring alpha up to the same height "
               "over its own pad. Bravo doesn't fly.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, -25), alt=12), airborne_at(ev, "charlie", 12),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=12), airborne_at(ev, "alpha", 12),
                                  never_armed(ev, "bravo")),
               [_takeoff("charlie", 12), _move("charlie", 0, -25), _takeoff("alpha", 12)],
               "Charlie hovers 25 m west at 12 m; alpha hovers over its pad at 12 m. Bravo stayed down."),
        # compound
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("compound", "dev", "compound11-lv-bravo-sw-north-land", ("bravo",),
               "Pacel bravo 12 metru augstumā, aizlido 20 metrus uz dienvidrietumiem, tad 20 metrus uz ziemeļiem "
               "un tur nosēdini.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 12), visited(ev, "bravo", [c.point("bravo", -d20, -d20)]),
                                  at(ev, "bravo", *c.point("bravo", 20 - d20, -d20)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", -d20, -d20), _move("bravo", 20, 0), _land("bravo")],
               "Bravo aizlidoja uz dienvidrietumiem, tad uz ziemeļiem un nosēdās."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("compound", "dev", "compound11-tl-alpha-north-lower-home", ("alpha",),
               "Paliparin si alpha hanggang 15 metro, ilipad ito nang 30 metro pahilaga, ibaba ito sa 6 na metro "
               "doon, saka ibalik sa pinagmulan nito para lumapag.",
               lambda c, ev: _all(rose_to(ev, "alpha", 15), visited(ev, "alpha", [c.point("alpha", 30, 0)], alt=6),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 15), _move("alpha", 30, 0), _move("alpha", alt=6), _rtl("alpha")],
               "Lumipad si alpha nang 30 m pahilaga, bumaba sa 6 m, at bumalik para lumapag."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("compound", "dev", "compound11-charlie-three-sides-land", ("charlie",),
               "Charlie: take off to 10 m, fly 20 m east, 20 m north, then 20 m west, and land there.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 20), c.point("charlie", 20, 20)]),
                                  at(ev, "charlie", *c.point("charlie", 20, 0)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", 0, 20), _move("charlie", 20, 0), _move("charlie", 0, -20),
                _land("charlie")],
               "Charlie flew east, north and west and landed 20 m north of its pad."),
        # conditional
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("conditional", "dev", "cond11-bg-charlie-east-unless-low", ("charlie",),
               "Ако батерията на charlie е под 50 %, остави го на земята; иначе го издигни на 10 метра, прелети "
               "20 метра на изток и го приземи там.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 10), at(ev, "charlie", *c.point("charlie", 0, 20)),
                                  landed_disarmed(ev, "charlie")),
               [_battery("charlie"), _takeoff("charlie", 10), _move("charlie", 0, 20), _land("charlie")],
               "Charlie има 63 %: прелетя 20 м на изток и кацна.", battery={"charlie": 63.0}),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("conditional", "dev", "cond11-ko-fuller-of-alpha-bravo", three,
               "alpha와 bravo 중 배터리가 더 많은 쪽을 15미터로 띄워서 그대로 떠 있게 하고, 나머지는 땅에 둬.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=15), airborne_at(ev, "bravo", 15),
                                  never_armed(ev, "alpha"), never_armed(ev, "charlie")),
               [("fleet_status", {}), _takeoff("bravo", 15)], "bravo(71 %)가 15 m에 떠 있음; alpha(48 %)는 땅에 있음.",
               battery={"alpha": 48.0, "bravo": 71.0, "charlie": 90.0}),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("conditional", "dev", "cond11-charlie-three-bands", ("charlie",),
               "If charlie has between 40 and 70 % battery, take it to 10 m and hover; above 70 %, to 25 m; "
               "below 40 %, leave it down.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=25), airborne_at(ev, "charlie", 25)),
               [_battery("charlie"), _takeoff("charlie", 25)], "Charlie has 76 %, so it hovers at 25 m.",
               battery={"charlie": 76.0}),
        # formation
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("formation", "dev", "form11-it-line-southwest", three,
               "Metti alpha, bravo e charlie uno accanto all'altro, a 9 metri di distanza, a 14 metri di quota, "
               "20 metri a sud-ovest di dove sono adesso, e lasciali sospesi lì.",
               lambda c, ev: _all(formation_at(c, ev, three, 14, 9, -d20, -d20), farthest_apart(ev, three, 18)),
               [_formation(three, "line", 14, 9, north=-d20, east=-d20)],
               "I tre sono affiancati 20 m a sud-ovest, a 14 m, 9 m l'uno dall'altro."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("formation", "dev", "form11-fr-triangle-east", three,
               "Placez les trois drones en triangle de 12 m de côté, à 20 m d'altitude, 30 m à l'est de leur "
               "position actuelle, et laissez-les en vol stationnaire.",
               lambda c, ev: _all(formation_at(c, ev, three, 20, 12, 0, 30), farthest_apart(ev, three, 12)),
               [_formation(three, "circle", 20, 12, east=30)], "Les trois tiennent un triangle de 12 m, 30 m à l'est, à 20 m."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("formation", "dev", "form11-pair-column-southeast-land", ("alpha", "bravo"),
               "Line alpha and bravo up one behind the other, 15 m apart at 10 m, 20 m south-east of where they "
               "are now, then set both down there.",
               lambda c, ev: landed_formation_at(c, ev, ("alpha", "bravo"), 15, -d20, d20),
               [_formation(("alpha", "bravo"), "column", 10, 15, north=-d20, east=d20), _land("alpha"), _land("bravo")],
               "Alpha and bravo flew in a column 20 m south-east and landed 15 m apart."),
        # relative
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("relative", "dev", "rel11-et-charlie-west-and-up", ("charlie",),
               "Tõsta charlie 8 meetri kõrgusele, seejärel vii see 15 meetrit läände ja ühtlasi 10 meetrit "
               "kõrgemale ning jäta sinna hõljuma.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, -15), alt=18), airborne_at(ev, "charlie", 18)),
               [_takeoff("charlie", 8), _move("charlie", 0, -15, up=10)], "Charlie hõljub 15 m läänes, 18 m kõrgusel."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("relative", "dev", "rel11-ja-bravo-southeast-lower", ("bravo",),
               "bravoを20メートルまで上げて、南東へ25メートル動かしてから、5メートル下げてそのまま浮かせておいて。",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", -d25, d25)], alt=20),
                                  at(ev, "bravo", *c.point("bravo", -d25, d25), alt=15), airborne_at(ev, "bravo", 15)),
               [_takeoff("bravo", 20), _move("bravo", -d25, d25), _move("bravo", up=-5)],
               "bravoは南東25 m、高度15 mで浮いている。"),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("relative", "dev", "rel11-alpha-north-west-offset", ("alpha",),
               "Move alpha 18 m north and 24 m west of where it sits, 10 m up, and keep it hovering there.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 18, -24), alt=10), airborne_at(ev, "alpha", 10)),
               [_move("alpha", 18, -24, alt=10)], "Alpha hovers 18 m north and 24 m west of its pad at 10 m."),
        # question
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("question", "dev", "ask11-sl-charlie-charge", three,
               "Koliko baterije ima še charlie? Samo povej, nobenega drona ne dvigni.",
               lambda c, ev: _all(answer_mentions_number(ev, 52, 1), nobody_armed(ev)),
               [("fleet_status", {})], "Charlie ima 52 %.", battery={"alpha": 88.0, "bravo": 70.0, "charlie": 52.0}),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("question", "dev", "ask11-zh-under-forty", three,
               "三架无人机里，哪一架的电量低于 40%？告诉我是多少，别让它们起飞。",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 36, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "bravo 的电量低于 40%：36 %。",
               battery={"alpha": 71.0, "bravo": 36.0, "charlie": 58.0}),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("question", "dev", "ask11-fullest-and-lead", three,
               "Which drone has the most charge, and by how many points does it lead the next best? Don't fly "
               "anything.",
               # the typed plan reads, it does not compute: the lead, or the two readings it comes from
               lambda c, ev: _all(answer_says(ev, r"\bcharlie\b", "charlie"),
                                  _any(answer_mentions_number(ev, 18, 1),
                                       _all(answer_mentions_number(ev, 82, 1), answer_mentions_number(ev, 64, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Charlie has the most, 82 %: 18 points ahead of alpha (64 %).",
               battery={"alpha": 64.0, "bravo": 59.0, "charlie": 82.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off)
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("refusal", "dev", "refuse11-pl-alpha-far-southwest", ("alpha",),
               "Wyślij alpha 1,2 km na południowy zachód na wysokości 20 metrów.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "alpha", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("alpha", -d1200, -d1200, alt=20)], "The gateway refused: 1.2 km is beyond the 1000 m limit."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("refusal", "dev", "refuse11-tr-bravo-400-feet", ("bravo",),
               "bravo'yu 400 fit yüksekliğe çıkar ve orada tut.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "bravo", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("bravo", 400 * FT)], "The gateway refused: 400 ft (121.9 m) is above the 120 m altitude limit."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("refusal", "dev", "refuse11-pair-charlie-drained", three,
               "Alpha and charlie: take off to 15 m and both fly 20 m south.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", -20, 0), alt=15), airborne_at(ev, "alpha", 15),
                                  refusal_seen(ev, "battery"), never_armed(ev, "charlie"), never_armed(ev, "bravo"),
                                  answer_reports_refusal(ev)),
               [_takeoff("alpha", 15), _move("alpha", -20, 0), _takeoff("charlie", 15)],
               "Alpha hovers 20 m south at 15 m; charlie was refused: its battery (24 %) is below the 30 % to take off.",
               battery={"alpha": 80.0, "charlie": 24.0}),
        # units
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("units", "dev", "units11-nl-charlie-feet-yards-west", ("charlie",),
               "Laat charlie opstijgen tot 25 voet, vlieg 100 yard naar het westen en land daar.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 25 * FT), at(ev, "charlie", *c.point("charlie", 0, -100 * YD)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 25 * FT), _move("charlie", 0, -100 * YD), _land("charlie")],
               "Charlie vloog 100 yard (91 m) naar het westen en landde."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("units", "dev", "units11-sw-bravo-feet-miles-ne", ("bravo",),
               "Paisha bravo hadi futi 70, kisha ipeleke maili 0.02 kuelekea kaskazini mashariki, na iache ielee "
               "hapo.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", d002mi, d002mi), alt=70 * FT),
                                  airborne_at(ev, "bravo", 70 * FT)),
               [_takeoff("bravo", 70 * FT), _move("bravo", d002mi, d002mi)],
               "Bravo inaelea maili 0.02 (32 m) kaskazini mashariki, futi 70 (21 m) juu."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("units", "dev", "units11-alpha-yards-up-ne-land", ("alpha",),
               "Send alpha up 40 yards, move it 80 yards to the north-east, and set it down there.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 40 * YD), at(ev, "alpha", *c.point("alpha", d80yd, d80yd)),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 40 * YD), _move("alpha", d80yd, d80yd), _land("alpha")],
               "Alpha climbed to 40 yd (36.6 m), flew 80 yd (73.2 m) north-east and landed."),
        # pattern
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("pattern", "dev", "pattern11-ro-charlie-triangle-right", ("charlie",),
               "Fă-l pe charlie să zboare un triunghi cu latura de 25 de metri, la 12 metri înălțime: prima latură "
               "spre nord-est, apoi virează la dreapta; la final să aterizeze.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(triangle25)[:2]]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), *_legs("charlie", triangle25), _land("charlie")],
               "Charlie a zburat triunghiul și a aterizat."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("pattern", "dev", "pattern11-cs-alpha-passes-west-south", ("alpha",),
               "Alpha ať ve výšce 10 metrů proletí 3 pruhy dlouhé 30 metrů, první směrem na západ, 8 metrů od "
               "sebe, každý další jižněji, a pak ať se vrátí domů.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(passes)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), *_legs("alpha", passes), _rtl("alpha")], "Alpha proletěl 3 pruhy a vrátil se domů."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("pattern", "dev", "pattern11-bravo-rectangle-left", ("bravo",),
               "Bravo: fly a 30 by 10 m rectangle at 8 m, the long sides running north-south, first leg north, "
               "turning left, then land where it started.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(rectangle)[:3]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 8), *_legs("bravo", rectangle), _land("bravo")], "Bravo flew the rectangle and landed."),
        # placement (the sim's homes stand apart west to east, alpha, bravo, charlie: each entry places alpha
        # from charlie or charlie from alpha, so that a drone placed from itself misses)
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("placement", "dev", "place11-lt-charlie-lands-east-of-alpha", three,
               "Nuskraidink charlie į tašką 30 metrų į rytus nuo alpha, 12 metrų aukštyje, ir ten jį nutupdyk.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 12), at(ev, "charlie", *c.point("alpha", 0, 30)),
                                  landed_disarmed(ev, "charlie"), never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               lambda c: [_go("charlie", c.point("alpha", 0, 30), 12), _land("charlie")],
               "Charlie nusileido 30 m į rytus nuo alpha."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("placement", "dev", "place11-sk-alpha-west-below-moved-charlie", three,
               "Vznes charlie do 18 metrov a posuň ho 20 metrov na juh. Potom daj alpha 10 metrov západne od "
               "charlie, o 8 metrov nižšie, a nechaj oba visieť.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -20, 0), alt=18), airborne_at(ev, "charlie", 18),
                                  at(ev, "alpha", *c.point("charlie", -20, -10), alt=10), airborne_at(ev, "alpha", 10),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("charlie", 18), _move("charlie", -20, 0), _go("alpha", c.point("charlie", -20, -10), 10)],
               "Charlie visí 20 m na juh na 18 m; alpha 10 m západne od neho na 10 m."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("placement", "dev", "place11-alpha-lands-north-of-hovering-charlie", three,
               "Bring charlie up to 10 m and keep it there, then set alpha down on the ground 12 m due north of "
               "charlie.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=10), airborne_at(ev, "charlie", 10),
                                  at(ev, "alpha", *c.point("charlie", 12, 0)), landed_disarmed(ev, "alpha"),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("charlie", 10), _go("alpha", c.point("charlie", 12, 0), 8), _land("alpha")],
               "Charlie hovers at 10 m; alpha landed 12 m north of it."),
        # language
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("language", "dev", "lang11-he-charlie-northwest-land", ("charlie",),
               "הרם את charlie לגובה 14 מטר, הטס אותו 30 מטר לכיוון צפון-מערב, ואז הנחת אותו שם.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 14), at(ev, "charlie", *c.point("charlie", d30, -d30)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 14), _move("charlie", d30, -d30), _land("charlie")],
               "charlie טס 30 m צפון-מערבה ונחת."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("language", "dev", "lang11-fa-alpha-west-hover", ("alpha",),
               "alpha را تا ارتفاع 18 متری بالا ببر، بعد 25 متر به سمت غرب ببرش و همان‌جا در هوا نگهش دار.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, -25), alt=18), airborne_at(ev, "alpha", 18)),
               [_takeoff("alpha", 18), _move("alpha", 0, -25)], "alpha در 25 m غرب، در ارتفاع 18 m در هواست."),
        # moved to dev on 2026-12-02, eleventh round: the test half had been measured
        _entry("language", "dev", "lang11-bn-bravo-south-home", ("bravo",),
               "bravo-কে 12 মিটার উঁচুতে তোলো, তারপর দক্ষিণ দিকে 35 মিটার উড়িয়ে নিয়ে যাও, শেষে বাড়িতে ফিরিয়ে "
               "এনে নামাও।",
               # the return home climbs to its own height: the leg south is checked at 12 m instead
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", -35, 0)], alt=12),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", -35, 0), _rtl("bravo")], "bravo দক্ষিণে 35 m উড়ে বাড়ি ফিরে নেমেছে।"),
    ]  # fmt: skip


def _twelfth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-02 (twelfth round), before any model ran on it: 3 a class; 22 of
    the 33 outside ``language`` in other languages than English (Arabic, Chinese, Dutch, Finnish, French,
    German, Greek, Hindi, Hungarian, Indonesian, Italian, Japanese, Korean, Polish, Portuguese, Russian,
    Spanish, Swedish, Thai, Turkish, Ukrainian, Vietnamese), the ``language`` class's 3 in Urdu, Tamil and
    Serbian written in Cyrillic (the three languages are new, and Tamil script with them); all of it moved
    to dev later on 2026-12-02 (twelfth round), once both models had been measured on it."""
    three = DRONES
    d20, d25 = (x / math.sqrt(2) for x in (20, 25))
    d50yd = 50 * YD / math.sqrt(2)
    d08mi = 0.8 * MI / math.sqrt(2)
    square18 = _polygon_legs(4, 18.0, 180.0, right=False)  # first side south, turning left
    # four passes of 30 m, the first east, 8 m apart, each next one north of the one before
    passes = [(0.0, 30.0), (8.0, 0.0), (0.0, -30.0), (8.0, 0.0), (0.0, 30.0), (8.0, 0.0), (0.0, -30.0)]
    # clockwise round the pad at a 20 m radius from its east side: E, S, W, N, E, then back to the centre
    orbit20 = [(0.0, 20.0), (-20.0, -20.0), (20.0, -20.0), (20.0, 20.0), (-20.0, 20.0), (0.0, -20.0)]
    return [
        # single
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("single", "dev", "single12-pt-bravo-above-pad", ("bravo",),
               "Suba o bravo até 17 metros acima da base dele e deixe-o parado no ar.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=17), airborne_at(ev, "bravo", 17)),
               [_takeoff("bravo", 17)], "O bravo está parado a 17 m acima da base."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("single", "dev", "single12-th-alpha-hop", ("alpha",),
               "ยก alpha ขึ้นไปที่ความสูง 11 เมตร แล้วให้ลงจอดตรงจุดเดิม",
               lambda c, ev: _all(reached_alt(ev, "alpha", 11), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 11), _land("alpha")], "alpha ขึ้นไปที่ 11 m แล้วลงจอดที่เดิม"),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("single", "dev", "single12-charlie-camera-check", ("charlie",),
               "Charlie's going up for a camera check: 32 m straight above its pad, and it waits there for me.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=32), airborne_at(ev, "charlie", 32)),
               [_takeoff("charlie", 32)], "Charlie waits at 32 m over its pad."),
        # multi
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("multi", "dev", "multi12-sv-three-ways-home", three,
               "Skicka ut alla tre 20 meter åt olika håll på 12 meters höjd: alpha västerut, bravo norrut och "
               "charlie österut. Ta sedan hem dem allihop.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, -20)]),
                                  visited(ev, "bravo", [c.point("bravo", 20, 0)]),
                                  visited(ev, "charlie", [c.point("charlie", 0, 20)]),
                                  *(at(ev, d, *_home(c, d)) for d in three), *(landed_disarmed(ev, d) for d in three)),
               [_move("alpha", 0, -20, alt=12), _move("bravo", 20, 0, alt=12), _move("charlie", 0, 20, alt=12),
                *(_rtl(d) for d in three)],
               "Alla tre flög 20 m ut, alpha västerut, bravo norrut, charlie österut, och landade hemma."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("multi", "dev", "multi12-zh-pair-south-bravo-high", three,
               "让 alpha 和 charlie 都升到 10 米，再各自向南飞 25 米，在那里悬停；bravo 只在原地升到 20 米待命。",
               lambda c, ev: _all(*(at(ev, d, *c.point(d, -25, 0), alt=10) for d in ("alpha", "charlie")),
                                  *(airborne_at(ev, d, 10) for d in ("alpha", "charlie")),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=20), airborne_at(ev, "bravo", 20)),
               [_takeoff("alpha", 10), _move("alpha", -25, 0), _takeoff("charlie", 10), _move("charlie", -25, 0),
                _takeoff("bravo", 20)],
               "alpha 和 charlie 在南边 25 米、10 米高悬停；bravo 在原地 20 米待命。"),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("multi", "dev", "multi12-alpha-nw-land-bravo-up", three,
               "Alpha goes 20 m north-west at 14 m and sets down there; bravo climbs to 9 m over its pad and "
               "stays up; charlie is not to move.",
               lambda c, ev: _all(rose_to(ev, "alpha", 14), at(ev, "alpha", *c.point("alpha", d20, -d20)),
                                  landed_disarmed(ev, "alpha"), at(ev, "bravo", *_home(c, "bravo"), alt=9),
                                  airborne_at(ev, "bravo", 9), never_armed(ev, "charlie")),
               [_move("alpha", d20, -d20, alt=14), _land("alpha"), _takeoff("bravo", 9)],
               "Alpha landed 20 m north-west; bravo hovers at 9 m over its pad; charlie stayed down."),
        # compound
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("compound", "dev", "compound12-de-charlie-corner-climb-home", ("charlie",),
               "Bring charlie auf 10 Meter, flieg 25 Meter nach Norden, dann 15 Meter nach Osten, steig dort "
               "um 10 Meter und komm anschließend nach Hause.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 25, 0), c.point("charlie", 25, 15)]),
                                  visited(ev, "charlie", [c.point("charlie", 25, 15)], alt=20),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", 25, 0), _move("charlie", 0, 15), _move("charlie", up=10),
                _rtl("charlie")],
               "Charlie flog 25 m nach Norden, 15 m nach Osten, stieg auf 20 m und kam nach Hause."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("compound", "dev", "compound12-vi-alpha-south-west-back", ("alpha",),
               "Cho alpha cất cánh lên 12 mét, bay 30 mét về phía nam, rồi 20 mét về phía tây, sau đó quay lại "
               "20 mét về phía đông và giữ nó lơ lửng ở đó.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -30, 0), c.point("alpha", -30, -20)]),
                                  at(ev, "alpha", *c.point("alpha", -30, 0), alt=12), airborne_at(ev, "alpha", 12)),
               [_takeoff("alpha", 12), _move("alpha", -30, 0), _move("alpha", 0, -20), _move("alpha", 0, 20)],
               "alpha đang lơ lửng 30 m về phía nam, ở độ cao 12 m."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("compound", "dev", "compound12-bravo-east-then-past-pad", ("bravo",),
               "Bravo: up to 12 m, 20 m east, then 40 m west, back past its pad, and land it there.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 12),
                                  visited(ev, "bravo", [c.point("bravo", 0, 20), c.point("bravo", 0, -20)]),
                                  at(ev, "bravo", *c.point("bravo", 0, -20)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", 0, 20), _move("bravo", 0, -40), _land("bravo")],
               "Bravo flew 20 m east, then 40 m west, and landed 20 m west of its pad."),
        # conditional
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("conditional", "dev", "cond12-es-both-or-one", three,
               "Mira la batería de alpha y de charlie. Si los dos tienen más del 50 %, súbelos a 12 metros; si "
               "solo uno pasa del 50 %, sube únicamente ese y deja el otro en tierra.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=12), airborne_at(ev, "alpha", 12),
                                  never_armed(ev, "charlie"), never_armed(ev, "bravo")),
               [_battery("alpha"), _battery("charlie"), _takeoff("alpha", 12)],
               "Alpha tiene 67 % y charlie 44 %: solo alpha está a 12 m.", battery={"alpha": 67.0, "charlie": 44.0}),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("conditional", "dev", "cond12-ko-charlie-check-aloft", ("charlie",),
               "charlie를 15미터로 띄운 뒤 배터리를 확인해. 60% 이상이면 북쪽으로 30미터 가서 떠 있게 하고, 그보다 "
               "적으면 바로 제자리에 착륙시켜.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 30, 0), alt=15),
                                  airborne_at(ev, "charlie", 15)),
               [_takeoff("charlie", 15), _battery("charlie"), _move("charlie", 30, 0)],
               "charlie 배터리 71 %: 북쪽 30 m, 15 m 높이에 떠 있음.", battery={"charlie": 71.0}),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("conditional", "dev", "cond12-bravo-stands-in", three,
               "Charlie should go up to 16 m and fly 20 m north, unless its battery is under 35 %; in that case "
               "send bravo instead and leave charlie on the ground.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 20, 0), alt=16), airborne_at(ev, "bravo", 16),
                                  never_armed(ev, "charlie"), never_armed(ev, "alpha")),
               [_battery("charlie"), _takeoff("bravo", 16), _move("bravo", 20, 0)],
               "Charlie has 31 %, so bravo went instead: it hovers 20 m north at 16 m.",
               battery={"bravo": 82.0, "charlie": 31.0}),
        # formation
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("formation", "dev", "form12-fr-file-northeast-land", three,
               "Mettez alpha, bravo et charlie en file indienne, 10 m entre chacun, à 16 m d'altitude, 25 m au "
               "nord-est de leur position, puis posez-les tous les trois là-bas.",
               lambda c, ev: landed_formation_at(c, ev, three, 20, d25, d25),
               [_formation(three, "column", 16, 10, north=d25, east=d25), *(_land(d) for d in three)],
               "Les trois ont volé en file 25 m au nord-est et se sont posés, 10 m entre chacun."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("formation", "dev", "form12-hu-pair-abreast-west", three,
               "Állítsd egymás mellé alpha-t és charlie-t, egymástól 14 méterre, 18 méter magasan, a mostani "
               "helyüktől 30 méterrel nyugatra, és hagyd őket ott lebegni.",
               lambda c, ev: _all(formation_at(c, ev, ("alpha", "charlie"), 18, 14, 0, -30), never_armed(ev, "bravo")),
               [_formation(("alpha", "charlie"), "line", 18, 14, east=-30)],
               "Alpha és charlie egymás mellett lebeg 30 m-rel nyugatra, 18 m-en, 14 m-re egymástól."),
        # (the gateway's V has its arms 45 degrees off its axis: its two wings stand 2 x 12 x sin 45 = 16.97 m
        # apart, where three in a row 12 m apart have their ends 24 m apart)
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("formation", "dev", "form12-v-north", three,
               "Arrange the three in a V, 12 m between neighbours, at 15 m, centred 25 m north of where they sit "
               "now, and keep them there.",
               lambda c, ev: _all(formation_at(c, ev, three, 15, 12, 25, 0), farthest_apart(ev, three, 16.97)),
               [_formation(three, "wedge", 15, 12, north=25)], "The three hold a V 25 m north at 15 m."),
        # relative
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("relative", "dev", "rel12-it-bravo-northeast-climbing", ("bravo",),
               "Alza bravo a 10 metri, poi spostalo di 20 metri verso nord-est salendo di altri 6 metri, e "
               "tienilo lì.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", d20, d20), alt=16), airborne_at(ev, "bravo", 16)),
               [_takeoff("bravo", 10), _move("bravo", d20, d20, up=6)], "Bravo è 20 m a nord-est, a 16 m."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("relative", "dev", "rel12-fi-charlie-lower-south", ("charlie",),
               "Nosta charlie 24 metrin korkeuteen, laske sitä sitten 10 metriä alemmas ja siirrä se 15 metriä "
               "etelään; jätä se sinne leijumaan.",
               lambda c, ev: _all(rose_to(ev, "charlie", 24), at(ev, "charlie", *c.point("charlie", -15, 0), alt=14),
                                  airborne_at(ev, "charlie", 14)),
               [_takeoff("charlie", 24), _move("charlie", up=-10), _move("charlie", -15, 0)],
               "Charlie leijuu 15 m etelään, 14 m korkeudessa."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("relative", "dev", "rel12-alpha-offset-then-nudge-up", ("alpha",),
               "Alpha: go to a spot 16 m south and 12 m east of its pad at 10 m, then nudge it up another 5 m "
               "and hold.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -16, 12)], alt=10),
                                  at(ev, "alpha", *c.point("alpha", -16, 12), alt=15), airborne_at(ev, "alpha", 15)),
               [_move("alpha", -16, 12, alt=10), _move("alpha", up=5)],
               "Alpha holds 16 m south and 12 m east of its pad at 15 m."),
        # question
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("question", "dev", "ask12-ja-lower-of-pair", three,
               "alphaとcharlieのうち、バッテリーが少ないのはどっち？残量も教えて。どれも飛ばさないで。",
               lambda c, ev: _all(answer_says(ev, r"\balpha\b", "alpha"), answer_mentions_number(ev, 46, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "少ないのは alpha: 46 %。",
               battery={"alpha": 46.0, "bravo": 60.0, "charlie": 73.0}),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("question", "dev", "ask12-ar-too-low-to-launch", three,
               "هل توجد طائرة لا تكفي بطاريتها للإقلاع الآن؟ اذكر اسمها ونسبتها، ولا تُقلع أي طائرة.",
               lambda c, ev: _all(answer_says(ev, r"\bcharlie\b", "charlie"), answer_mentions_number(ev, 26, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "نعم، charlie: 26 %، أقل من 30 % اللازمة للإقلاع.",
               battery={"alpha": 77.0, "bravo": 65.0, "charlie": 26.0}),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("question", "dev", "ask12-needs-charge-for-job", three,
               "Which drone would I have to charge before it could fly a job that needs 70 %? Tell me its figure; "
               "keep everything on the ground.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 66, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Bravo: it has 66 %, under the 70 % the job needs.",
               battery={"alpha": 84.0, "bravo": 66.0, "charlie": 91.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("refusal", "dev", "refuse12-ru-bravo-half-metre", ("bravo",),
               "Подними bravo на 10 метров, а потом опусти его так, чтобы он висел в полуметре над землёй.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 10), refusal_seen(ev, "minimum", "at least"),
                                  answer_reports_refusal(ev)),
               [_takeoff("bravo", 10), _move("bravo", alt=0.5)],
               "Bravo is at 10 m; the descent was refused: 0.5 m is below the 2 m minimum altitude."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("refusal", "dev", "refuse12-id-alpha-miles-northwest", ("alpha",),
               "Terbangkan alpha sejauh 0,8 mil ke arah barat laut pada ketinggian 25 meter, lalu daratkan di sana.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "alpha", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("alpha", d08mi, -d08mi, alt=25)],
               "The gateway refused: 0.8 miles (1287 m) is beyond the 1000 m limit."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("refusal", "dev", "refuse12-stack-over-ceiling", three,
               "Stack them up over their own pads: alpha at 45 m, bravo 45 m higher than alpha, and charlie another "
               "45 m above bravo.",
               lambda c, ev: _all(airborne_at(ev, "alpha", 45), airborne_at(ev, "bravo", 90),
                                  refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "charlie", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("alpha", 45), _takeoff("bravo", 90), _takeoff("charlie", 135)],
               "Alpha hovers at 45 m and bravo at 90 m; charlie was refused: 135 m is above the 120 m altitude limit."),
        # units
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("units", "dev", "units12-pl-bravo-feet-yards-lower", ("bravo",),
               "Podnieś bravo na 60 stóp, przeleć nim 50 jardów na południowy wschód i obniż go o 20 stóp; niech "
               "tam wisi.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", -d50yd, d50yd), alt=40 * FT),
                                  airborne_at(ev, "bravo", 40 * FT)),
               [_takeoff("bravo", 60 * FT), _move("bravo", -d50yd, d50yd), _move("bravo", up=-20 * FT)],
               "Bravo wisi 50 jardów (46 m) na południowy wschód, na 40 stopach (12,2 m)."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("units", "dev", "units12-el-charlie-feet-km-land", ("charlie",),
               "Σήκωσε το charlie στα 35 πόδια, πέτα το 0,06 χιλιόμετρα βόρεια και προσγείωσέ το εκεί.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 35 * FT), at(ev, "charlie", *c.point("charlie", 60, 0)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 35 * FT), _move("charlie", 60, 0), _land("charlie")],
               "Το charlie πέταξε 60 m βόρεια στα 35 πόδια (10,7 m) και προσγειώθηκε."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("units", "dev", "units12-alpha-feet-miles-home", ("alpha",),
               "Alpha: up to 45 ft, then 0.03 miles east, then come home.",
               # the return home climbs to its own height: the leg east is checked at 45 ft instead
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 0.03 * MI)], alt=45 * FT),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 45 * FT), _move("alpha", 0, 0.03 * MI), _rtl("alpha")],
               "Alpha flew 0.03 miles (48 m) east at 45 ft (13.7 m) and came home."),
        # pattern
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("pattern", "dev", "pattern12-nl-alpha-square-south-left", ("alpha",),
               "Laat alpha op 14 meter hoogte een vierkant vliegen met zijden van 18 meter, eerste zijde naar "
               "het zuiden, linksom, en daarna boven het startpunt blijven hangen.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(square18)[:3]]),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=14), airborne_at(ev, "alpha", 14)),
               [_takeoff("alpha", 14), *_legs("alpha", square18)], "Alpha vloog het vierkant en hangt boven de start."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("pattern", "dev", "pattern12-hi-bravo-passes-north", ("bravo",),
               "bravo से 12 मीटर की ऊँचाई पर खेत का सर्वे करवाओ: 30 मीटर लंबी चार पट्टियाँ, पहली पूर्व की ओर, "
               "पट्टियों के बीच 8 मीटर का अंतर, हर अगली पट्टी पिछली के उत्तर में; फिर उसे घर वापस ले आओ।",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(passes)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), *_legs("bravo", passes), _rtl("bravo")],
               "bravo ने चारों पट्टियाँ उड़ीं और घर लौट आया।"),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("pattern", "dev", "pattern12-charlie-orbit-pad-from-east", ("charlie",),
               "Charlie at 16 m: go once round its own pad clockwise at a 20 m radius, starting from the east "
               "side, then land back on the pad.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e)
                                                          for n, e in ((0, 20), (-20, 0), (0, -20), (20, 0))]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 16), *_legs("charlie", orbit20), _land("charlie")],
               "Charlie circled its pad clockwise and landed on it."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # alpha from charlie or charlie from alpha, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("placement", "dev", "place12-uk-charlie-lands-sw-of-alpha", three,
               "Залиш alpha на місці, а charlie відправ у точку за 20 метрів на південний захід від alpha, на "
               "висоті 11 метрів, і посади його там.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 11), at(ev, "charlie", *c.point("alpha", -d20, -d20)),
                                  landed_disarmed(ev, "charlie"), never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               lambda c: [_go("charlie", c.point("alpha", -d20, -d20), 11), _land("charlie")],
               "charlie сів за 20 м на південний захід від alpha."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("placement", "dev", "place12-tr-alpha-south-of-moved-charlie", three,
               "charlie'yi 16 metreye kaldır ve 25 metre kuzeye götür. Sonra alpha'yı charlie'nin 10 metre "
               "güneyine, aynı yüksekliğe getir ve ikisini de orada beklet.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 25, 0), alt=16), airborne_at(ev, "charlie", 16),
                                  at(ev, "alpha", *c.point("charlie", 15, 0), alt=16), airborne_at(ev, "alpha", 16),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("charlie", 16), _move("charlie", 25, 0),
                          _go("alpha", c.point("charlie", 15, 0), 16)],
               "charlie 25 m kuzeyde 16 m'de; alpha onun 10 m güneyinde, aynı yükseklikte bekliyor."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("placement", "dev", "place12-charlie-alongside-alpha-west", three,
               "Put alpha at 14 m over its pad, then bring charlie alongside it: same height, 12 m to its west.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=14), airborne_at(ev, "alpha", 14),
                                  at(ev, "charlie", *c.point("alpha", 0, -12), alt=14), airborne_at(ev, "charlie", 14),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 14), _go("charlie", c.point("alpha", 0, -12), 14)],
               "Alpha hovers at 14 m over its pad; charlie 12 m west of it at 14 m."),
        # language
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("language", "dev", "lang12-ur-bravo-northeast-land", ("bravo",),
               "bravo کو 13 میٹر کی بلندی تک لے جاؤ، پھر اسے 25 میٹر شمال مشرق کی طرف اڑاؤ اور وہیں اتار دو۔",
               lambda c, ev: _all(reached_alt(ev, "bravo", 13), at(ev, "bravo", *c.point("bravo", d25, d25)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 13), _move("bravo", d25, d25), _land("bravo")],
               "bravo شمال مشرق میں 25 m اڑ کر اتر گیا۔"),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("language", "dev", "lang12-ta-alpha-west-hover", ("alpha",),
               "alpha-வை 15 மீட்டர் உயரத்துக்கு ஏற்றி, மேற்கு நோக்கி 20 மீட்டர் பறக்கவிட்டு, அங்கேயே வானில் "
               "நிறுத்தி வை.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, -20), alt=15), airborne_at(ev, "alpha", 15)),
               [_takeoff("alpha", 15), _move("alpha", 0, -20)], "alpha மேற்கே 20 m, 15 m உயரத்தில் நிற்கிறது."),
        # moved to dev on 2026-12-02, twelfth round: the test half had been measured
        _entry("language", "dev", "lang12-sr-charlie-south-home", ("charlie",),
               "Подигни charlie на 11 метара, одлети њиме 30 метара ка југу, па га врати кући да слети.",
               # the return home climbs to its own height: the leg south is checked at 11 m instead
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -30, 0)], alt=11),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 11), _move("charlie", -30, 0), _rtl("charlie")],
               "charlie је одлетео 30 m ка југу и вратио се кући."),
    ]  # fmt: skip


def _thirteenth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-02 (thirteenth round), before any model ran on it: 3 a class; 22 of
    the 33 outside ``language`` in other languages than English, one each (Afrikaans, Arabic, Azerbaijani,
    Chinese, Dutch, French, Galician, German, Hindi, Icelandic, Indonesian, Italian, Japanese, Kazakh,
    Korean, Polish, Portuguese, Russian, Spanish, Turkish, Ukrainian, Vietnamese; Afrikaans, Azerbaijani,
    Galician, Icelandic and Kazakh are new), the ``language`` class's 3 in Marathi, Georgian and Armenian
    (the three languages are new, and Georgian and Armenian script with them); all of it moved to dev on
    2026-12-03 (thirteenth round), once both models had been measured on it."""
    three = DRONES
    d20, d25, d35 = (x / math.sqrt(2) for x in (20, 25, 35))
    # 30 m on a bearing of 300 degrees (clockwise from north): 15 m north, 25.98 m west
    b300 = (30 * math.cos(math.radians(300)), 30 * math.sin(math.radians(300)))
    triangle20 = _polygon_legs(3, 20.0, 270.0, right=False)  # first side west, turning left
    diamond20 = _polygon_legs(4, 20.0, 45.0, right=True)  # a square on its corner: NE, SE, SW, NW
    # a 20 m square centred on the pad, clockwise from its north-east corner, then back to the centre
    round_pad = [(10.0, 10.0), (-20.0, 0.0), (0.0, -20.0), (20.0, 0.0), (0.0, 20.0), (-10.0, -10.0)]

    def north_south(ev: Evidence, drones: tuple[str, ...]) -> Check:
        """Every drone within 3 m east or west of the drones' centre: a row running north to south."""
        lat, lon = _centroid([ev.final[d] for d in drones])
        off = max(horizontal_distance_m(lat, ev.final[d].lon, lat, lon) for d in drones)
        return Check(off <= 3.0, f"drones up to {off:.1f} m east or west of their centre (want 3 at most)")

    def centred_on(c: MissionContext, d: str) -> dict[str, float]:
        lat, lon = _home(c, d)
        return {"center_lat_deg": lat, "center_lon_deg": lon}

    return [
        # single
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("single", "dev", "single13-bravo-radio-relay", ("bravo",),
               "Need bravo up as a radio relay: ten metres straight up off its pad, and it stays there till I say.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=10), airborne_at(ev, "bravo", 10)),
               [_takeoff("bravo", 10)], "Bravo is up at 10 m over its pad as the relay."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("single", "dev", "single13-af-alpha-motor-test", ("alpha",),
               "Kan jy alpha net vinnig tot 9 meter laat opstyg en dan dadelik weer laat land? Ek wil net die "
               "motors toets.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 9), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 9), _land("alpha")], "Alpha het tot 9 m opgestyg en weer geland."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("single", "dev", "single13-ko-charlie-hover-till-told", ("charlie",),
               "charlie를 26미터 높이까지 띄우고, 내가 다시 말할 때까지 그대로 떠 있게 해 줘.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=26), airborne_at(ev, "charlie", 26)),
               [_takeoff("charlie", 26)], "charlie가 26 m 높이에 떠 있어."),
        # multi
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("multi", "dev", "multi13-fan-out-bravo-climbs", three,
               "Everyone up to 12 m. Then alpha slides 20 m west, charlie 20 m east, and bravo climbs another "
               "10 m where it is. All three stay up.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, -20), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("charlie", 0, 20), alt=12), airborne_at(ev, "charlie", 12),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=22), airborne_at(ev, "bravo", 22)),
               [*(_takeoff(d, 12) for d in three), _move("alpha", 0, -20), _move("charlie", 0, 20),
                _move("bravo", up=10)],
               "Alpha hovers 20 m west and charlie 20 m east at 12 m; bravo is at 22 m over its pad."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("multi", "dev", "multi13-it-highest-lands", three,
               "Porta alpha a 10 metri, bravo a 15 e charlie a 20, sopra le loro piazzole; poi fai atterrare quello "
               "che sta più in alto e lascia gli altri due in volo.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=15), airborne_at(ev, "bravo", 15),
                                  reached_alt(ev, "charlie", 20), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("alpha", 10), _takeoff("bravo", 15), _takeoff("charlie", 20), _land("charlie")],
               "Alpha a 10 m e bravo a 15 m restano in volo; charlie, il più alto, è atterrato."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("multi", "dev", "multi13-kk-north-lands-south-hovers", three,
               "alpha-ны солтүстікке қарай 30 метр, charlie-ді оңтүстікке қарай 30 метр ұшыр, екеуі де 15 метр "
               "биіктікте болсын. Сосын alpha сол жерге қонсын, ал charlie ауада ілулі тұрсын. bravo орнынан "
               "қозғалмасын.",
               lambda c, ev: _all(rose_to(ev, "alpha", 15), at(ev, "alpha", *c.point("alpha", 30, 0)),
                                  landed_disarmed(ev, "alpha"), at(ev, "charlie", *c.point("charlie", -30, 0), alt=15),
                                  airborne_at(ev, "charlie", 15), never_armed(ev, "bravo")),
               [_move("alpha", 30, 0, alt=15), _move("charlie", -30, 0, alt=15), _land("alpha")],
               "alpha солтүстікте 30 м жерге қонды; charlie оңтүстікте 30 м, 15 м биіктікте тұр; bravo қозғалмады."),
        # compound
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("compound", "dev", "compound13-alpha-climb-leg-drop-leg", ("alpha",),
               "Alpha: take off to 8 m, fly 20 m north climbing to 14 m on the way, then 20 m east dropping back "
               "to 8 m, and land it there.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 20, 0)], alt=14),
                                  at(ev, "alpha", *c.point("alpha", 20, 20)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 8), _move("alpha", 20, 0, alt=14), _move("alpha", 0, 20, alt=8), _land("alpha")],
               "Alpha flew 20 m north up to 14 m, 20 m east back down to 8 m, and landed."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("compound", "dev", "compound13-ja-alpha-ne-then-nw", ("alpha",),
               "alphaを12メートルまで上げて、北東に20メートル、続けて北西に20メートル飛ばして、そこで12メートルの"
               "まま待機させて。",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", d20, d20)]),
                                  at(ev, "alpha", *c.point("alpha", 2 * d20, 0), alt=12), airborne_at(ev, "alpha", 12)),
               [_takeoff("alpha", 12), _move("alpha", d20, d20), _move("alpha", d20, -d20)],
               "alphaは北東、北西へ20 mずつ飛び、北へ28 mの地点、高度12 mで待機中。"),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("compound", "dev", "compound13-gl-bravo-east-low-back", ("bravo",),
               "Sube o bravo a 15 metros, lévao 30 metros cara ao leste, báixao alí ata 6 metros e tráeo a esa "
               "altura 30 metros de volta cara ao oeste; despois fai que aterre.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, 30)], alt=15),
                                  visited(ev, "bravo", [c.point("bravo", 0, 30)], alt=6),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 15), _move("bravo", 0, 30), _move("bravo", alt=6), _move("bravo", 0, -30),
                _land("bravo")],
               "O bravo foi 30 m cara ao leste, baixou a 6 m, volveu á súa base e aterrou."),
        # conditional
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("conditional", "dev", "cond13-charlie-short-of-job", ("charlie",),
               "Only launch charlie if it has enough for the job, which needs 55 %. If it does, take it 30 m east "
               "at 15 m and leave it there; if it doesn't, keep it down and tell me how far short it is.",
               # the typed plan reads, it does not compute: the shortfall, or the reading it comes from
               lambda c, ev: _all(never_armed(ev, "charlie"),
                                  _any(answer_mentions_number(ev, 6, 1), answer_mentions_number(ev, 49, 1))),
               [_battery("charlie")], "Charlie has 49 %, 6 points short of the 55 % the job needs, so it stays down.",
               battery={"charlie": 49.0}),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("conditional", "dev", "cond13-de-weakest-stays", three,
               "Lass die Drohne mit dem schwächsten Akku am Boden; die anderen beiden sollen auf 12 m steigen, "
               "20 m nach Norden fliegen und dort in der Luft bleiben.",
               lambda c, ev: _all(*(at(ev, d, *c.point(d, 20, 0), alt=12) for d in ("alpha", "charlie")),
                                  *(airborne_at(ev, d, 12) for d in ("alpha", "charlie")), never_armed(ev, "bravo")),
               [("fleet_status", {}), _move("alpha", 20, 0, alt=12), _move("charlie", 20, 0, alt=12)],
               "Bravo hat den schwächsten Akku (47 %) und bleibt am Boden; alpha und charlie schweben 20 m "
               "nördlich auf 12 m.", battery={"alpha": 81.0, "bravo": 47.0, "charlie": 66.0}),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("conditional", "dev", "cond13-vi-bravo-holds-if-low", ("bravo",),
               "Cho bravo cất cánh lên 10 mét rồi kiểm tra pin của nó. Nếu pin còn trên 70 %, cho nó bay tiếp 30 "
               "mét về phía tây và lơ lửng ở đó; nếu không thì cứ giữ nó lơ lửng ngay trên chỗ cất cánh, ở 10 mét.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=10), airborne_at(ev, "bravo", 10)),
               [_takeoff("bravo", 10), _battery("bravo")],
               "Pin của bravo là 58 %, nên nó lơ lửng ở 10 m ngay trên chỗ cất cánh.", battery={"bravo": 58.0}),
        # formation
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("formation", "dev", "form13-north-south-row-over-pads", three,
               "Line the three up north to south over their pads, 10 m between each, at 15 m, and hold them there.",
               lambda c, ev: _all(formation_at(c, ev, three, 15, 10, 0, 0), farthest_apart(ev, three, 20),
                                  north_south(ev, three)),
               [_formation(three, "column", 15, 10)], "The three hold a north-south row 10 m apart at 15 m."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("formation", "dev", "form13-pt-pair-either-side-of-bravo", three,
               "Põe o alpha e o charlie lado a lado, a 20 m um do outro e a 14 m de altura, de forma que o bravo, "
               "que fica no chão, fique exatamente a meio entre os dois.",
               lambda c, ev: _all(formation_around(ev, ("alpha", "charlie"), 14, 20, _home(c, "bravo")),
                                  never_armed(ev, "bravo")),
               lambda c: [("formation_goto", {"drone_ids": ["alpha", "charlie"], "formation": "line", "alt_m": 14,
                                              "spacing_m": 20, **centred_on(c, "bravo")})],
               "O alpha e o charlie pairam a 14 m, 20 m um do outro, com o bravo no chão a meio."),
        # (the gateway's V has its arms 45 degrees off its axis: its two wings stand 2 x 12 x sin 45 = 16.97 m
        # apart)
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("formation", "dev", "form13-ru-wedge-southeast-land", three,
               "Построй alpha, bravo и charlie клином — 12 метров между соседями, высота 15 метров — в 35 метрах "
               "к юго-востоку от того места, где они сейчас стоят, и посади их там.",
               lambda c, ev: landed_formation_at(c, ev, three, 16.97, -d35, d35),
               [_formation(three, "wedge", 15, 12, north=-d35, east=d35), *(_land(d) for d in three)],
               "Три дрона долетели клином на 35 м к юго-востоку и сели там."),
        # relative
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("relative", "dev", "rel13-alpha-climb-to-not-by", ("alpha",),
               "Take alpha up to 8 m, then move it 25 m north while it climbs to 20 m (20 above the ground, not 20 "
               "more) and let it hover there.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 25, 0), alt=20), airborne_at(ev, "alpha", 20)),
               [_takeoff("alpha", 8), _move("alpha", 25, 0, alt=20)], "Alpha hovers 25 m north at 20 m."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("relative", "dev", "rel13-is-charlie-west-lower-further", ("charlie",),
               "Færðu charlie 20 metra í vestur í 12 metra hæð. Lækkaðu hann síðan um 6 metra og færðu hann 10 "
               "metrum lengra í vestur, og láttu hann svo sveima þar.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, -20)], alt=12),
                                  at(ev, "charlie", *c.point("charlie", 0, -30), alt=6), airborne_at(ev, "charlie", 6)),
               [_move("charlie", 0, -20, alt=12), _move("charlie", 0, -10, up=-6)],
               "Charlie sveimar 30 m vestan við upphafsstaðinn, í 6 m hæð."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("relative", "dev", "rel13-ar-charlie-bearing-300", ("charlie",),
               "حرّك charlie مسافة 30 مترًا باتجاه 300 درجة (مقيسة من الشمال مع عقارب الساعة) على ارتفاع 15 مترًا، "
               "واتركه يحوم هناك.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", *b300), alt=15), airborne_at(ev, "charlie", 15)),
               [_move("charlie", *b300, alt=15)], "charlie يحوم على بعد 30 m باتجاه 300°، على ارتفاع 15 m."),
        # question
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("question", "dev", "ask13-longer-leg-of-pair", three,
               "Alpha and bravo are both going out on the next sortie. Which of the two should take the longer "
               "leg, going by battery? Give me both charges; nothing flies yet.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 88, 1),
                                  answer_mentions_number(ev, 63, 1), nobody_armed(ev)),
               [("fleet_status", {})], "Bravo, with 88 %; alpha has 63 %.",
               battery={"alpha": 63.0, "bravo": 88.0, "charlie": 41.0}),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("question", "dev", "ask13-zh-closest-pair", three,
               "三架无人机里，有没有两架的电量相差不到 5%？是哪两架，各剩多少？都别起飞。",
               lambda c, ev: _all(answer_says(ev, r"\balpha\b", "alpha"), answer_says(ev, r"\bcharlie\b", "charlie"),
                                  answer_mentions_number(ev, 72, 1), answer_mentions_number(ev, 70, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "有：alpha 72%，charlie 70%，只差 2%。",
               battery={"alpha": 72.0, "bravo": 45.0, "charlie": 70.0}),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("question", "dev", "ask13-tr-charlie-vs-bravo", three,
               "charlie'nin şarjı bravo'nunkinden fazla mı? İkisinin yüzdesini de söyle, hiçbirini havalandırma.",
               lambda c, ev: _all(answer_mentions_number(ev, 49, 1), answer_mentions_number(ev, 58, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Hayır: charlie %49, bravo %58.",
               battery={"alpha": 90.0, "bravo": 58.0, "charlie": 49.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse13-row-lifted-over-ceiling", three,
               "Put all three in a row at 40 m over where they are, 10 m apart, then lift the whole row another "
               "90 m.",
               lambda c, ev: _all(*(airborne_at(ev, d, 40) for d in three), refusal_seen(ev, "altitude", "120"),
                                  *(max_alt_at_most(ev, d, c.max_alt_m) for d in three), answer_reports_refusal(ev)),
               [_formation(three, "line", 40, 10), _formation(three, "line", 130, 10)],
               "The three hold a row at 40 m; lifting it to 130 m was refused: above the 120 m altitude limit."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse13-fr-bravo-north-east-too-far", ("bravo",),
               "Envoie bravo au point situé 800 m au nord et 800 m à l'est de son point de départ, à 30 m "
               "d'altitude.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "bravo", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("bravo", 800, 800, alt=30)],
               "La passerelle a refusé : ce point est à 1131 m du départ, au-delà de la limite de 1000 m."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse13-az-bravo-low-anyway", ("bravo",),
               "Bilirəm ki, bravo-nun batareyası azdır, amma onu sadəcə bir dəqiqəlik 8 metrə qaldır, sonra "
               "endirərik.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "bravo"), answer_reports_refusal(ev)),
               [_takeoff("bravo", 8)],
               "Şlüz imtina etdi: bravo-nun batareyası (21 %) qalxış üçün lazım olan minimum 30 %-dən aşağıdır.",
               battery={"bravo": 21.0}),
        # units
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("units", "dev", "units13-bravo-feet-drop-yards-south", ("bravo",),
               "Bravo: up to 75 ft, then down 50 ft, then 40 yards south at that height, and hold it there.",
               lambda c, ev: _all(rose_to(ev, "bravo", 75 * FT), at(ev, "bravo", *c.point("bravo", -40 * YD, 0), alt=25 * FT),
                                  airborne_at(ev, "bravo", 25 * FT)),
               [_takeoff("bravo", 75 * FT), _move("bravo", up=-50 * FT), _move("bravo", -40 * YD, 0)],
               "Bravo holds 40 yd (36.6 m) south at 25 ft (7.6 m)."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("units", "dev", "units13-es-charlie-yards-feet-land", ("charlie",),
               "Mueve a charlie 30 yardas al norte y 45 pies al este, a 40 pies de altura, y que aterrice allí.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 40 * FT),
                                  at(ev, "charlie", *c.point("charlie", 30 * YD, 45 * FT)), landed_disarmed(ev, "charlie")),
               [_move("charlie", 30 * YD, 45 * FT, alt=40 * FT), _land("charlie")],
               "Charlie voló 30 yardas (27 m) al norte y 45 pies (14 m) al este a 40 pies (12 m) y aterrizó."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("units", "dev", "units13-uk-alpha-yards-back", ("alpha",),
               "Підніми alpha на 40 футів, відведи його на 50 ярдів на захід, потім поверни на 20 ярдів назад на "
               "схід і посади там.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 40 * FT), visited(ev, "alpha", [c.point("alpha", 0, -50 * YD)]),
                                  at(ev, "alpha", *c.point("alpha", 0, -30 * YD)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 40 * FT), _move("alpha", 0, -50 * YD), _move("alpha", 0, 20 * YD), _land("alpha")],
               "alpha пролетів 50 ярдів на захід, повернувся на 20 ярдів і сів за 30 ярдів (27 м) на захід від старту."),
        # pattern
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern13-charlie-triangle-two-laps", ("charlie",),
               "Charlie at 14 m: two laps of a triangle with 20 m sides, first side heading west, turning left at "
               "each corner; then hover over where it started.",
               # the two far corners of each lap, in order (the home corner between laps is left out)
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e)
                                                          for n, e in 2 * _corners(triangle20)[:2]]),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=14), airborne_at(ev, "charlie", 14)),
               [_takeoff("charlie", 14), *_legs("charlie", triangle20 + triangle20)],
               "Charlie flew the triangle twice and hovers over its start at 14 m."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern13-pl-alpha-diamond", ("alpha",),
               "Niech alpha na wysokości 12 m przeleci kwadrat postawiony na rogu, o boku 20 m: pierwszy bok na "
               "północny wschód, potem za każdym razem skręt w prawo; na koniec ma wylądować tam, skąd wystartował.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(diamond20)[:3]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), *_legs("alpha", diamond20), _land("alpha")],
               "Alpha przeleciał kwadrat postawiony na rogu i wylądował w miejscu startu."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern13-hi-bravo-square-round-pad", ("bravo",),
               "bravo को 12 मीटर की ऊँचाई पर एक ऐसा वर्ग उड़वाओ जिसकी हर भुजा 20 मीटर हो और जिसका केंद्र उसका अपना "
               "पैड हो: उत्तर-पूर्वी कोने से शुरू करो, घड़ी की दिशा में पूरा चक्कर लगाओ, फिर केंद्र पर लौटकर वहीं उतार दो।",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(round_pad)[:5]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), *_legs("bravo", round_pad), _land("bravo")],
               "bravo ने पैड के चारों ओर वर्ग उड़ाया और केंद्र पर उतर गया।"),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places a
        # drone from alpha or charlie, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("placement", "dev", "place13-charlie-east-above-alpha", three,
               "Alpha flies 20 m north at 12 m. Then put charlie 15 m east of alpha and 5 m above it, and once "
               "charlie's there, land alpha where it is.",
               lambda c, ev: _all(rose_to(ev, "alpha", 12), at(ev, "alpha", *c.point("alpha", 20, 0)),
                                  landed_disarmed(ev, "alpha"), at(ev, "charlie", *c.point("alpha", 20, 15), alt=17),
                                  airborne_at(ev, "charlie", 17), never_armed(ev, "bravo")),
               lambda c: [_move("alpha", 20, 0, alt=12), _go("charlie", c.point("alpha", 20, 15), 17), _land("alpha")],
               "Charlie hovers 15 m east of alpha at 17 m; alpha landed 20 m north of its pad."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("placement", "dev", "place13-nl-charlie-over-landed-alpha", three,
               "Vlieg alpha op 12 meter hoogte 20 meter naar het noorden en laat hem daar landen. Zet daarna charlie "
               "recht boven de plek waar alpha staat, op 12 meter hoogte, en laat hem daar hangen.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 0)), landed_disarmed(ev, "alpha"),
                                  at(ev, "charlie", *c.point("alpha", 20, 0), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("alpha", 20, 0, alt=12), _land("alpha"), _go("charlie", c.point("alpha", 20, 0), 12)],
               "Alpha is 20 m noordelijk geland; charlie hangt er recht boven op 12 m."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("placement", "dev", "place13-id-flanking-charlie", three,
               "Terbangkan alpha ke titik 20 meter di selatan charlie dan bravo ke titik 20 meter di utara charlie, "
               "keduanya pada ketinggian 10 meter, lalu biarkan keduanya melayang di sana; charlie tetap di darat.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("charlie", -20, 0), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "bravo", *c.point("charlie", 20, 0), alt=10), airborne_at(ev, "bravo", 10),
                                  never_armed(ev, "charlie")),
               lambda c: [_go("alpha", c.point("charlie", -20, 0), 10), _go("bravo", c.point("charlie", 20, 0), 10)],
               "alpha melayang 20 m di selatan charlie dan bravo 20 m di utaranya, keduanya pada 10 m."),
        # language
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("language", "dev", "lang13-mr-charlie-west-land", ("charlie",),
               "charlie ला 14 मीटर उंचीवर ने, मग त्याला 30 मीटर पश्चिमेकडे उडव आणि तिथेच खाली उतरव.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 14), at(ev, "charlie", *c.point("charlie", 0, -30)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 14), _move("charlie", 0, -30), _land("charlie")],
               "charlie पश्चिमेकडे 30 m उडून तिथे उतरला."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("language", "dev", "lang13-ka-alpha-southeast-hover", ("alpha",),
               "აიყვანე alpha 16 მეტრის სიმაღლეზე, გადაიყვანე 25 მეტრით სამხრეთ-აღმოსავლეთით და იქ ჰაერში გააჩერე.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", -d25, d25), alt=16), airborne_at(ev, "alpha", 16)),
               [_takeoff("alpha", 16), _move("alpha", -d25, d25)],
               "alpha ჰაერშია 25 m-ით სამხრეთ-აღმოსავლეთით, 16 m სიმაღლეზე."),
        # moved to dev on 2026-12-03, thirteenth round: the test half had been measured
        _entry("language", "dev", "lang13-hy-bravo-north-home", ("bravo",),
               "Բարձրացրու bravo-ն 12 մետր, թռցրու այն 20 մետր դեպի հյուսիս, ապա հետ բեր տուն և իջեցրու։",
               # the return home climbs to its own height: the leg north is checked at 12 m instead
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 20, 0)], alt=12),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", 20, 0), _rtl("bravo")],
               "bravo-ն թռավ 20 m դեպի հյուսիս, վերադարձավ տուն և իջավ։"),
    ]  # fmt: skip


def _fourteenth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-03 (fourteenth round), before any model ran on it, by a writer who
    did not read the host's word lists or rules: 3 a class; 22 of the 33 outside ``language`` in other
    languages than English, one each (Albanian, Basque, Catalan, Chinese, Croatian, Czech, Esperanto,
    Finnish, French, German, Greek, Hebrew, Japanese, Korean, Malay, Persian, Romanian, Spanish, Swedish,
    Turkish, Uzbek, Welsh; Albanian, Basque, Esperanto, Uzbek and Welsh are new), the ``language`` class's
    3 in Nepali, Macedonian and Gujarati (the three languages are new, and Gujarati script with them); all of
    it moved to dev on 2026-12-03 (fourteenth round), once both models had been measured on it."""
    three = DRONES
    d15, d18, d20, d30 = (x / math.sqrt(2) for x in (15, 18, 20, 30))
    d40yd = 40 * YD / math.sqrt(2)
    inch = 0.0254
    d01mi = 0.1 * MI / math.sqrt(2)
    square20 = _polygon_legs(4, 20.0, 90.0, right=False)  # first side east, turning left
    # a figure of eight of two 15 m squares meeting at the pad: the north-east one clockwise from its north
    # side, then the south-west one anticlockwise from its north side (flown west first)
    eight = [(15.0, 0.0), (0.0, 15.0), (-15.0, 0.0), (0.0, -15.0),
             (0.0, -15.0), (-15.0, 0.0), (0.0, 15.0), (15.0, 0.0)]  # fmt: skip
    # a right-angled triangle: 30 m north, 40 m east, then the 50 m hypotenuse straight back
    right_triangle = [(30.0, 0.0), (0.0, 40.0), (-30.0, -40.0)]

    def centred(c: MissionContext, ev: Evidence, drones: tuple[str, ...], north: float, east: float) -> Check:
        """The drones' centre ``north``/``east`` metres from the centre of their homes, whether they are up
        or down (a row of which one drone landed where it stood)."""
        home_lat = sum(c.homes[d][0] for d in drones) / len(drones)
        home_lon = sum(c.homes[d][1] for d in drones) / len(drones)
        want = offset_position(home_lat, home_lon, north, east)
        off = horizontal_distance_m(*_centroid([ev.final[d] for d in drones]), *want)
        return Check(off <= HORIZONTAL_TOL_M, f"drones' centre {off:.1f} m from where it was asked")

    return [
        # single
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("single", "dev", "single14-cy-alpha-over-pad", ("alpha",),
               "Codwch alpha 16 metr yn syth i fyny uwchben ei bad, a gadewch iddo hofran yno nes i mi ddweud yn "
               "wahanol.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=16), airborne_at(ev, "alpha", 16)),
               [_takeoff("alpha", 16)], "Mae alpha yn hofran 16 m uwchben ei bad."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("single", "dev", "single14-ja-bravo-check-hop", ("bravo",),
               "bravoを7メートルの高さまで上げたら、その場ですぐに降ろして。離陸と着陸の確認だけでいいから。",
               lambda c, ev: _all(reached_alt(ev, "bravo", 7), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 7), _land("bravo")], "bravoは7 mまで上がって、同じ場所に着陸した。"),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("single", "dev", "single14-charlie-wanted-overhead", ("charlie",),
               "Charlie's wanted overhead: lift it to 21 metres off its pad and leave it hanging there.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=21), airborne_at(ev, "charlie", 21)),
               [_takeoff("charlie", 21)], "Charlie hangs at 21 m over its pad."),
        # multi
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("multi", "dev", "multi14-es-bravo-lands-south-charlie-higher", three,
               "Sube a bravo y a charlie a 10 metros. Luego manda a bravo 25 metros al sur y que aterrice allí, y "
               "sube a charlie 15 metros más, sin moverlo de encima de su base. Alpha se queda en tierra.",
               lambda c, ev: _all(rose_to(ev, "bravo", 10), at(ev, "bravo", *c.point("bravo", -25, 0)),
                                  landed_disarmed(ev, "bravo"), visited(ev, "charlie", [_home(c, "charlie")], alt=10),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=25), airborne_at(ev, "charlie", 25),
                                  never_armed(ev, "alpha")),
               [_takeoff("bravo", 10), _takeoff("charlie", 10), _move("bravo", -25, 0), _land("bravo"),
                _move("charlie", up=15)],
               "Bravo aterrizó 25 m al sur; charlie está a 25 m sobre su base; alpha no despegó."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("multi", "dev", "multi14-hr-pair-northeast-charlie-hop", three,
               "Neka alpha i bravo polete na 15 metara i odlete 30 metara prema sjeveroistoku te ondje ostanu "
               "lebdjeti; charlie samo podigni na 6 metara i odmah ga spusti natrag na isto mjesto.",
               lambda c, ev: _all(*(at(ev, d, *c.point(d, d30, d30), alt=15) for d in ("alpha", "bravo")),
                                  *(airborne_at(ev, d, 15) for d in ("alpha", "bravo")),
                                  reached_alt(ev, "charlie", 6), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie")),
               [_move("alpha", d30, d30, alt=15), _move("bravo", d30, d30, alt=15), _takeoff("charlie", 6),
                _land("charlie")],
               "alpha i bravo lebde 30 m sjeveroistočno na 15 m; charlie je poletio na 6 m i sletio."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("multi", "dev", "multi14-alpha-up-level-with-bravo", three,
               "Alpha up to 10 m and bravo up to 20 m, each over its own pad; then take alpha up level with bravo. "
               "Charlie stays put.",
               lambda c, ev: _all(visited(ev, "alpha", [_home(c, "alpha")], alt=10),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=20), airborne_at(ev, "alpha", 20),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=20), airborne_at(ev, "bravo", 20),
                                  never_armed(ev, "charlie")),
               [_takeoff("alpha", 10), _takeoff("bravo", 20), _move("alpha", up=10)],
               "Alpha and bravo both hover at 20 m over their pads; charlie stayed down."),
        # compound
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("compound", "dev", "compound14-eo-bravo-three-legs-land", ("bravo",),
               "Levu la dronon bravo ĝis 10 metroj, flugigu ĝin 25 metrojn norden, poste 25 metrojn okcidenten, "
               "poste 25 metrojn suden, kaj tie surterigu ĝin.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 10),
                                  visited(ev, "bravo", [c.point("bravo", 25, 0), c.point("bravo", 25, -25)]),
                                  at(ev, "bravo", *c.point("bravo", 0, -25)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), _move("bravo", 25, 0), _move("bravo", 0, -25), _move("bravo", -25, 0),
                _land("bravo")],
               "Bravo flugis norden, okcidenten kaj suden, kaj surteriĝis 25 m okcidente de sia starto."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("compound", "dev", "compound14-el-charlie-east-climb-back-over-pad", ("charlie",),
               "Σήκωσε το charlie στα 12 μέτρα, πήγαινέ το 20 μέτρα ανατολικά, ανέβασέ το εκεί στα 20 μέτρα και "
               "φέρε το πίσω 20 μέτρα δυτικά, πάνω από το σημείο απογείωσης, χωρίς να το προσγειώσεις.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 20)], alt=12),
                                  visited(ev, "charlie", [c.point("charlie", 0, 20)], alt=20),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=20), airborne_at(ev, "charlie", 20)),
               [_takeoff("charlie", 12), _move("charlie", 0, 20), _move("charlie", alt=20), _move("charlie", 0, -20)],
               "Το charlie αιωρείται στα 20 m πάνω από το σημείο απογείωσης."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("compound", "dev", "compound14-alpha-staircase-north-home", ("alpha",),
               "Alpha: take off to 9 m, fly 20 m north, climb 9 m, fly another 20 m north, then bring it home.",
               # the return home climbs to its own height: the two legs are checked at their own heights instead
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 20, 0)], alt=9),
                                  visited(ev, "alpha", [c.point("alpha", 40, 0)], alt=18),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 9), _move("alpha", 20, 0), _move("alpha", up=9), _move("alpha", 20, 0),
                _rtl("alpha")],
               "Alpha flew 20 m north at 9 m, climbed to 18 m, flew 20 m more and came home."),
        # conditional
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("conditional", "dev", "cond14-de-height-by-charge", three,
               "Lass alle drei über ihren Startplätzen aufsteigen: jede Drohne mit mehr als 60 % Akku auf 20 m, "
               "die übrigen nur auf 8 m.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=20), airborne_at(ev, "alpha", 20),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=8), airborne_at(ev, "bravo", 8),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=20), airborne_at(ev, "charlie", 20)),
               [("fleet_status", {}), _takeoff("alpha", 20), _takeoff("bravo", 8), _takeoff("charlie", 20)],
               "alpha (64 %) und charlie (83 %) schweben auf 20 m, bravo (59 %) auf 8 m.",
               battery={"alpha": 64.0, "bravo": 59.0, "charlie": 83.0}),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("conditional", "dev", "cond14-fa-fuller-lands-southwest", three,
               "از میان alpha و charlie، هر کدام که باتری بیشتری دارد تا ارتفاع 18 متری بالا برود، 15 متر به سمت "
               "جنوب غربی پرواز کند و همان‌جا فرود بیاید؛ دیگری روی زمین بماند.",
               lambda c, ev: _all(rose_to(ev, "charlie", 18), at(ev, "charlie", *c.point("charlie", -d15, -d15)),
                                  landed_disarmed(ev, "charlie"), never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               [("fleet_status", {}), _move("charlie", -d15, -d15, alt=18), _land("charlie")],
               "charlie (68 %) 15 m به سمت جنوب غربی پرواز کرد و فرود آمد؛ alpha (52 %) روی زمین ماند.",
               battery={"alpha": 52.0, "charlie": 68.0}),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("conditional", "dev", "cond14-within-ten-points", three,
               "If alpha and bravo are within 10 points of each other on battery, put both up at 10 m over their "
               "pads; if not, only the fuller of the two goes up.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=10), airborne_at(ev, "alpha", 10),
                                  never_armed(ev, "bravo"), never_armed(ev, "charlie")),
               [("fleet_status", {}), _takeoff("alpha", 10)],
               "Alpha has 75 % and bravo 58 %, 17 points apart: only alpha is up, at 10 m.",
               battery={"alpha": 75.0, "bravo": 58.0}),
        # formation
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("formation", "dev", "form14-fr-pair-column-west-land", three,
               "Mettez alpha et charlie l'un derrière l'autre, à 12 m d'écart, à 20 m d'altitude, 30 m à l'ouest "
               "de là où ils sont, puis faites-les atterrir là-bas. Bravo ne bouge pas.",
               lambda c, ev: _all(landed_formation_at(c, ev, ("alpha", "charlie"), 12, 0, -30), never_armed(ev, "bravo")),
               [_formation(("alpha", "charlie"), "column", 20, 12, east=-30), _land("alpha"), _land("charlie")],
               "Alpha et charlie se sont posés en colonne 30 m à l'ouest, à 12 m l'un de l'autre."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("formation", "dev", "form14-sq-triangle-south", three,
               "Vendosini të tre dronët në formë trekëndëshi me brinjë 15 metra, në lartësi 18 metra, 25 metra "
               "në jug të vendit ku ndodhen tani, dhe lërini të qëndrojnë pezull atje.",
               lambda c, ev: _all(formation_at(c, ev, three, 18, 15, -25, 0), farthest_apart(ev, three, 15)),
               [_formation(three, "circle", 18, 15, north=-25)],
               "Të tre dronët qëndrojnë pezull në trekëndësh 25 m në jug, në 18 m."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("formation", "dev", "form14-row-north-bravo-lands", three,
               "Line alpha, bravo and charlie up abreast, 11 m apart, at 16 m, 20 m north of where they are; then "
               "land bravo there and keep the other two up.",
               lambda c, ev: _all(*(airborne_at(ev, d, 16) for d in ("alpha", "charlie")), rose_to(ev, "bravo", 16),
                                  landed_disarmed(ev, "bravo"), farthest_apart(ev, three, 22),
                                  centred(c, ev, three, 20, 0)),
               [_formation(three, "line", 16, 11, north=20), _land("bravo")],
               "Bravo landed in the row 20 m north; alpha and charlie hover 22 m apart at 16 m."),
        # relative
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("relative", "dev", "rel14-eu-charlie-south-east-offset", ("charlie",),
               "Igo ezazu charlie 10 metroko altuerara; gero, eraman ezazu 20 metro ekialdera eta 15 metro "
               "hegoaldera, eta utz ezazu han airean geldirik.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -15, 20), alt=10), airborne_at(ev, "charlie", 10)),
               [_takeoff("charlie", 10), _move("charlie", -15, 20)],
               "Charlie airean dago, 15 m hegoaldera eta 20 m ekialdera, 10 m-ko altueran."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("relative", "dev", "rel14-ko-bravo-third-back-half-height", ("bravo",),
               "bravo를 20미터까지 올려서 동쪽으로 30미터 보낸 다음, 온 거리의 3분의 1만큼 되돌아오면서 고도를 "
               "절반으로 낮추고 거기서 떠 있게 해.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, 30)], alt=20),
                                  at(ev, "bravo", *c.point("bravo", 0, 20), alt=10), airborne_at(ev, "bravo", 10)),
               [_takeoff("bravo", 20), _move("bravo", 0, 30), _move("bravo", 0, -10, alt=10)],
               "bravo는 동쪽 20 m, 10 m 높이에 떠 있어."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("relative", "dev", "rel14-alpha-climb-by-the-legs", ("alpha",),
               "Take alpha up to 6 m. Move it 10 m west, then twice as far north, then raise it by as many metres "
               "as those two legs add up to, and hold it there.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, -10)], alt=6),
                                  at(ev, "alpha", *c.point("alpha", 20, -10), alt=36), airborne_at(ev, "alpha", 36)),
               [_takeoff("alpha", 6), _move("alpha", 0, -10), _move("alpha", 20, 0), _move("alpha", up=30)],
               "Alpha holds 20 m north and 10 m west of its pad at 36 m."),
        # question
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("question", "dev", "ask14-zh-average-charge", three,
               "三架无人机的平均电量是多少？告诉我就行，一架都不要起飞。",
               # the typed plan reads, it does not compute: the average, or the three readings it comes from
               lambda c, ev: _all(_any(answer_mentions_number(ev, 73, 1),
                                       _all(answer_mentions_number(ev, 60, 1), answer_mentions_number(ev, 75, 1),
                                            answer_mentions_number(ev, 84, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "平均电量 73 %（alpha 60 %，bravo 75 %，charlie 84 %）。",
               battery={"alpha": 60.0, "bravo": 75.0, "charlie": 84.0}),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("question", "dev", "ask14-he-alpha-or-bravo-by-how-much", three,
               "למי יש יותר סוללה, ל-alpha או ל-bravo, ובכמה אחוזים? אל תמריא אף רחפן.",
               # the typed plan reads, it does not compute: the gap, or the two readings it comes from
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"),
                                  _any(answer_mentions_number(ev, 26, 1),
                                       _all(answer_mentions_number(ev, 81, 1), answer_mentions_number(ev, 55, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "ל-bravo: 81 %, 26 נקודות יותר מ-alpha (55 %).",
               battery={"alpha": 55.0, "bravo": 81.0, "charlie": 67.0}),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("question", "dev", "ask14-under-a-third", three,
               "Is any drone below a third of a full charge? If so, which one and what does it read? Keep them all "
               "grounded.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 31, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Yes: bravo, at 31 %.", battery={"alpha": 36.0, "bravo": 31.0, "charlie": 70.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse14-uz-alpha-three-times-higher", ("alpha",),
               "alpha-ni 50 metr balandlikka koʻtar, soʻng uni hozirgi balandligidan uch baravar yuqoriroqqa olib "
               "chiq.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 50), refusal_seen(ev, "altitude", "120"),
                                  max_alt_at_most(ev, "alpha", c.max_alt_m), answer_reports_refusal(ev)),
               [_takeoff("alpha", 50), _move("alpha", alt=150)],
               "alpha 50 m da; 150 m ga koʻtarilish rad etildi: bu 120 m balandlik limitidan yuqori."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse14-cs-charlie-feet-west-too-far", ("charlie",),
               "Pošli dron charlie 3500 stop na západ ve výšce 20 metrů a nech ho tam viset.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "charlie", c.max_distance_m), answer_reports_refusal(ev)),
               [_move("charlie", 0, -3500 * FT, alt=20)],
               "Brána let zamítla: 3500 stop (1067 m) je za limitem 1000 m od domova."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse14-charlie-yards-over-ceiling", ("charlie",),
               "Charlie up to 30 m first, then another 100 yards straight up.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 30), refusal_seen(ev, "altitude", "120"),
                                  max_alt_at_most(ev, "charlie", c.max_alt_m), answer_reports_refusal(ev)),
               [_takeoff("charlie", 30), _move("charlie", up=100 * YD)],
               "Charlie is at 30 m; the climb of 100 yd (91 m) was refused: 121 m is above the 120 m altitude limit."),
        # units
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("units", "dev", "units14-sv-alpha-feet-km-yards-land", ("alpha",),
               "Lyft alpha till 50 fot, flyg den 0,05 km söderut och sedan 30 yard österut, och landa den där.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 50 * FT), visited(ev, "alpha", [c.point("alpha", -50, 0)]),
                                  at(ev, "alpha", *c.point("alpha", -50, 30 * YD)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 50 * FT), _move("alpha", -50, 0), _move("alpha", 0, 30 * YD), _land("alpha")],
               "Alpha flög 0,05 km (50 m) söderut och 30 yard (27 m) österut på 50 fot (15 m) och landade."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("units", "dev", "units14-ro-charlie-feet-down-metres-ne", ("charlie",),
               "Ridică-l pe charlie la 80 de picioare, coboară-l apoi cu 15 metri și du-l 40 de iarzi spre "
               "nord-est; lasă-l să plutească acolo.",
               lambda c, ev: _all(rose_to(ev, "charlie", 80 * FT),
                                  at(ev, "charlie", *c.point("charlie", d40yd, d40yd), alt=80 * FT - 15),
                                  airborne_at(ev, "charlie", 80 * FT - 15)),
               [_takeoff("charlie", 80 * FT), _move("charlie", up=-15), _move("charlie", d40yd, d40yd)],
               "Charlie plutește la 40 de iarzi (37 m) spre nord-est, la 9,4 m."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("units", "dev", "units14-bravo-inches-tenth-mile", ("bravo",),
               "Bravo: climb to 480 inches, fly a tenth of a mile north-west, and land there.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 480 * inch), at(ev, "bravo", *c.point("bravo", d01mi, -d01mi)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 480 * inch), _move("bravo", d01mi, -d01mi), _land("bravo")],
               "Bravo climbed to 480 in (12.2 m), flew 0.1 mi (161 m) north-west and landed."),
        # pattern
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern14-alpha-figure-eight-squares", ("alpha",),
               "Alpha at 10 m: fly a figure of eight made of two 15 m squares that meet at its pad. First the one "
               "to the north-east, clockwise, starting north; then the one to the south-west, anticlockwise, "
               "starting west. Land on the pad at the end.",
               # the corners of each square but the pad they share, in order
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e)
                                                        for n, e in _corners(eight)[:3] + _corners(eight)[4:7]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), *_legs("alpha", eight), _land("alpha")],
               "Alpha flew the figure of eight and landed on its pad."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern14-fi-bravo-square-two-heights", ("bravo",),
               "Lennätä bravo 10 metrin korkeudessa neliö, jonka sivu on 20 metriä: ensimmäinen sivu itään, "
               "käännökset vasemmalle. Nosta se sitten 20 metriin, lennä sama neliö uudelleen ja laske se lopuksi "
               "lähtöpaikalleen.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(square20)[:3]], alt=10),
                                  visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(square20)[:3]], alt=20),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), *_legs("bravo", square20), _move("bravo", alt=20), *_legs("bravo", square20),
                _land("bravo")],
               "Bravo lensi neliön 10 m:ssä ja 20 m:ssä ja laskeutui lähtöpaikalleen."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern14-ca-charlie-right-triangle", ("charlie",),
               "Fes volar el dron charlie a 12 metres d'altura en un triangle: 30 metres cap al nord, després 40 "
               "metres cap a l'est i, finalment, en línia recta de tornada al punt de sortida; deixa'l allà suspès "
               "en l'aire.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(right_triangle)[:2]]),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=12), airborne_at(ev, "charlie", 12)),
               [_takeoff("charlie", 12), *_legs("charlie", right_triangle)],
               "El charlie ha volat el triangle i és suspès a 12 m sobre el punt de sortida."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # alpha from charlie or charlie from alpha, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("placement", "dev", "place14-tr-alpha-northwest-of-charlie", three,
               "charlie'yi bulunduğu yerde 14 metreye kaldır; sonra alpha'yı charlie'nin 20 metre kuzeybatısına, "
               "aynı yüksekliğe getir ve ikisini de orada havada tut.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=14), airborne_at(ev, "charlie", 14),
                                  at(ev, "alpha", *c.point("charlie", d20, -d20), alt=14), airborne_at(ev, "alpha", 14),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("charlie", 14), _go("alpha", c.point("charlie", d20, -d20), 14)],
               "charlie pistinin üstünde 14 m'de; alpha onun 20 m kuzeybatısında, aynı yükseklikte."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("placement", "dev", "place14-ms-charlie-lands-north-of-moved-alpha", three,
               "Naikkan alpha ke 10 meter dan bawa ia 25 meter ke timur. Selepas itu, terbangkan charlie pada "
               "ketinggian 16 meter ke titik 10 meter di utara alpha, lalu daratkan ia di situ.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 25), alt=10), airborne_at(ev, "alpha", 10),
                                  reached_alt(ev, "charlie", 16), at(ev, "charlie", *c.point("alpha", 10, 25)),
                                  landed_disarmed(ev, "charlie"), never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 10), _move("alpha", 0, 25), _go("charlie", c.point("alpha", 10, 25), 16),
                          _land("charlie")],
               "alpha terapung 25 m ke timur pada 10 m; charlie mendarat 10 m di utaranya."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("placement", "dev", "place14-charlie-southeast-above-alpha", three,
               "Hover alpha at 9 m over its pad, then park charlie 18 m south-east of alpha and 6 m higher than it.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=9), airborne_at(ev, "alpha", 9),
                                  at(ev, "charlie", *c.point("alpha", -d18, d18), alt=15), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 9), _go("charlie", c.point("alpha", -d18, d18), 15)],
               "Alpha hovers at 9 m over its pad; charlie 18 m south-east of it at 15 m."),
        # language
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("language", "dev", "lang14-ne-charlie-northwest-land", ("charlie",),
               "charlie लाई 13 मिटर माथि उडाऊ, त्यसपछि उत्तर-पश्चिमतर्फ 20 मिटर लैजाऊ र त्यहीँ अवतरण गराऊ।",
               lambda c, ev: _all(reached_alt(ev, "charlie", 13), at(ev, "charlie", *c.point("charlie", d20, -d20)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 13), _move("charlie", d20, -d20), _land("charlie")],
               "charlie उत्तर-पश्चिमतर्फ 20 m उडेर त्यहीँ अवतरण गर्‍यो।"),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("language", "dev", "lang14-mk-alpha-south-hover", ("alpha",),
               "Подигни го alpha на 17 метри, однеси го 30 метри кон југ и остави го таму да лебди.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", -30, 0), alt=17), airborne_at(ev, "alpha", 17)),
               [_takeoff("alpha", 17), _move("alpha", -30, 0)], "alpha лебди 30 m јужно, на 17 m."),
        # moved to dev on 2026-12-03, fourteenth round: the test half had been measured
        _entry("language", "dev", "lang14-gu-bravo-east-home", ("bravo",),
               "bravo ને 11 મીટર ઊંચે ચઢાવો, પછી તેને 25 મીટર પૂર્વ દિશામાં ઉડાડો અને ત્યાર બાદ ઘરે પાછું લાવીને "
               "ઉતારો.",
               # the return home climbs to its own height: the leg east is checked at 11 m instead
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, 25)], alt=11),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 11), _move("bravo", 0, 25), _rtl("bravo")],
               "bravo પૂર્વમાં 25 m ઊડીને ઘરે પાછું આવ્યું અને ઊતર્યું."),
    ]  # fmt: skip


def _fifteenth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-03 (fifteenth round), before any model ran on it, by a writer who
    did not read the host's word lists or rules: 3 a class; 22 of the 33 outside ``language`` in other
    languages than English, one each (Arabic, Bengali, Bulgarian, Danish, Dutch, Estonian, Hindi,
    Hungarian, Icelandic, Indonesian, Irish, Italian, Latvian, Lithuanian, Norwegian, Polish, Portuguese,
    Serbian, Slovenian, Tagalog, Thai, Vietnamese; Irish is new, and Serbian in Latin script), the
    ``language`` class's 3 in Ukrainian, Swahili and Punjabi (the three languages are new to the class, and
    Gurmukhi script with Punjabi); all of it moved to dev on 2026-12-03 (fifteenth round), once both models
    had been measured on it."""
    three = DRONES
    d10, d15, d25, d30 = (x / math.sqrt(2) for x in (10, 15, 25, 30))
    # a staircase north-east: 15 m east, 15 m north, twice
    stairs = [(0.0, 15.0), (15.0, 0.0), (0.0, 15.0), (15.0, 0.0)]
    # an L (30 m north, 15 m east) flown out and retraced back to the pad
    l_retraced = [(30.0, 0.0), (0.0, 15.0), (0.0, -15.0), (-30.0, 0.0)]
    # a 30 m by 12 m rectangle: 30 m east first, turning right
    rectangle = [(0.0, 30.0), (-12.0, 0.0), (0.0, -30.0), (12.0, 0.0)]
    triangle25 = _polygon_legs(3, 25.0, 90.0, right=True)  # first side east, turning right

    return [
        # single
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("single", "dev", "single15-charlie-just-off-the-ground", ("charlie",),
               "Nudge charlie up to 4 m off the ground, no higher, and hold it there.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=4), airborne_at(ev, "charlie", 4)),
               [_takeoff("charlie", 4)], "Charlie hovers 4 m over its pad."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("single", "dev", "single15-lt-bravo-hold-till-told", ("bravo",),
               "Pakelk droną bravo į 14 metrų aukštį tiesiai virš jo aikštelės ir laikyk ore, kol pasakysiu "
               "kitaip.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=14), airborne_at(ev, "bravo", 14)),
               [_takeoff("bravo", 14)], "bravo kabo 14 m aukštyje virš savo aikštelės."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("single", "dev", "single15-ga-alpha-hop", ("alpha",),
               "Ardaigh alpha suas go 8 méadar, agus ansin lig dó tuirlingt arís láithreach san áit chéanna.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 8), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 8), _land("alpha")], "D'ardaigh alpha go 8 m agus thuirling sé arís san áit chéanna."),
        # multi
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("multi", "dev", "multi15-three-jobs", three,
               "Three separate jobs: alpha climbs to 18 m over its pad and stays there; bravo flies 20 m east at "
               "10 m and lands; charlie goes 25 m south at 14 m and then comes home.",
               # the return home climbs to its own height: charlie's leg south is checked at 14 m instead
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=18), airborne_at(ev, "alpha", 18),
                                  reached_alt(ev, "bravo", 10), at(ev, "bravo", *c.point("bravo", 0, 20)),
                                  landed_disarmed(ev, "bravo"),
                                  visited(ev, "charlie", [c.point("charlie", -25, 0)], alt=14),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("alpha", 18), _move("bravo", 0, 20, alt=10), _land("bravo"), _move("charlie", -25, 0, alt=14),
                _rtl("charlie")],
               "Alpha hovers at 18 m over its pad; bravo landed 20 m east; charlie went 25 m south and came home."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("multi", "dev", "multi15-no-pair-west-bravo-lands-charlie-home", three,
               "Send bravo og charlie 30 meter vestover i 12 meters høyde. Når de er framme, skal bravo lande der "
               "den er, mens charlie flyr tilbake og lander der den tok av. Alpha blir stående på bakken.",
               # the return home climbs to its own height: charlie's leg west is checked at 12 m instead
               lambda c, ev: _all(reached_alt(ev, "bravo", 12), at(ev, "bravo", *c.point("bravo", 0, -30)),
                                  landed_disarmed(ev, "bravo"),
                                  visited(ev, "charlie", [c.point("charlie", 0, -30)], alt=12),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie"),
                                  never_armed(ev, "alpha")),
               [_move("bravo", 0, -30, alt=12), _move("charlie", 0, -30, alt=12), _land("bravo"), _rtl("charlie")],
               "Bravo landet 30 m vest; charlie fløy tilbake og landet der den tok av; alpha ble stående."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("multi", "dev", "multi15-bn-alpha-north-charlie-down", three,
               "alpha আর charlie দুটোকেই 15 মিটার উচ্চতায় তোলো। তারপর alpha-কে 20 মিটার উত্তরে নিয়ে গিয়ে "
               "সেখানেই ভাসিয়ে রাখো, আর charlie-কে যেখানে আছে সেখানেই নামাও। bravo মাটিতেই থাকবে।",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 0), alt=15), airborne_at(ev, "alpha", 15),
                                  reached_alt(ev, "charlie", 15), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie"), never_armed(ev, "bravo")),
               [_takeoff("alpha", 15), _takeoff("charlie", 15), _move("alpha", 20, 0), _land("charlie")],
               "alpha 20 m উত্তরে 15 m উচ্চতায় ভাসছে; charlie নিজের জায়গায় নেমেছে; bravo মাটিতেই আছে।"),
        # compound
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("compound", "dev", "compound15-bravo-stairs-northeast", ("bravo",),
               "Bravo: up to 10 m, then zigzag north-east in steps (15 m east, 15 m north, 15 m east, 15 m north, "
               "all at 10 m) and land where that ends.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(stairs)[:3]], alt=10),
                                  at(ev, "bravo", *c.point("bravo", 30, 30)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), *_legs("bravo", stairs), _land("bravo")],
               "Bravo stepped 30 m east and 30 m north in four legs and landed."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("compound", "dev", "compound15-pl-alpha-south-half-back-climb", ("alpha",),
               "Podnieś alpha na 12 m i poleć nim 40 m na południe. Potem niech wróci połowę tej drogi na północ, "
               "wzniesie się tam o kolejne 10 m i zawiśnie w powietrzu.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -40, 0)], alt=12),
                                  at(ev, "alpha", *c.point("alpha", -20, 0), alt=22), airborne_at(ev, "alpha", 22)),
               [_takeoff("alpha", 12), _move("alpha", -40, 0), _move("alpha", 20, 0), _move("alpha", up=10)],
               "Alpha wisi 20 m na południe od startu, na wysokości 22 m."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("compound", "dev", "compound15-lv-charlie-east-climb-north", ("charlie",),
               "Pacel charlie 10 metru augstumā un aizsūti viņu 20 metrus uz austrumiem. Tur pacel viņu līdz 20 "
               "metriem, pēc tam aizsūti vēl 20 metrus uz ziemeļiem, un lai viņš tur paliek gaisā.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 20)], alt=10),
                                  visited(ev, "charlie", [c.point("charlie", 0, 20)], alt=20),
                                  at(ev, "charlie", *c.point("charlie", 20, 20), alt=20), airborne_at(ev, "charlie", 20)),
               [_takeoff("charlie", 10), _move("charlie", 0, 20), _move("charlie", alt=20), _move("charlie", 20, 0)],
               "charlie karājas 20 m uz ziemeļiem un 20 m uz austrumiem no starta, 20 m augstumā."),
        # conditional
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("conditional", "dev", "cond15-charlie-job-or-hop", ("charlie",),
               "Check charlie's battery first. At 50 % or more, send it 30 m north at 15 m and land it there; under "
               "50 %, just hop it up to 5 m and straight back down so I know it still flies.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 5), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie")),
               [_battery("charlie"), _takeoff("charlie", 5), _land("charlie")],
               "Charlie has 44 %, under 50: it hopped to 5 m and landed on its pad.", battery={"charlie": 44.0}),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("conditional", "dev", "cond15-it-charlie-west-or-alpha-east", three,
               "Se charlie ha più batteria di alpha, portalo a 12 m, mandalo 25 m a ovest e fallo atterrare lì; "
               "altrimenti fai la stessa cosa con alpha, ma 25 m verso est. Bravo resta a terra.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 12), at(ev, "alpha", *c.point("alpha", 0, 25)),
                                  landed_disarmed(ev, "alpha"), never_armed(ev, "charlie"), never_armed(ev, "bravo")),
               [("fleet_status", {}), _takeoff("alpha", 12), _move("alpha", 0, 25), _land("alpha")],
               "alpha (77 %) ha più batteria di charlie (62 %): è volato 25 m a est a 12 m ed è atterrato lì.",
               battery={"alpha": 77.0, "charlie": 62.0}),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("conditional", "dev", "cond15-sl-alpha-climb-or-land", ("alpha",),
               "Dvigni alpha na 10 metrov in nato preveri njegovo baterijo. Če ima več kot 50 %, naj se dvigne še "
               "za 15 metrov in ostane tam; če ne, naj takoj pristane.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=25), airborne_at(ev, "alpha", 25)),
               [_takeoff("alpha", 10), _battery("alpha"), _move("alpha", up=15)],
               "alpha ima 67 %, zato se je dvignil na 25 m in lebdi nad vzletiščem.", battery={"alpha": 67.0}),
        # formation
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("formation", "dev", "form15-pair-column-east-alpha-overhead", three,
               "Put bravo and charlie one behind the other, 15 m apart at 10 m, 20 m east of where they sit; alpha "
               "goes up to 25 m over its own pad to keep an eye on them.",
               lambda c, ev: _all(formation_at(c, ev, ("bravo", "charlie"), 10, 15, 0, 20),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=25), airborne_at(ev, "alpha", 25)),
               [_formation(("bravo", "charlie"), "column", 10, 15, east=20), _takeoff("alpha", 25)],
               "Bravo and charlie hold a column 20 m east at 10 m; alpha watches from 25 m over its pad."),
        # (the gateway's V has its arms 45 degrees off its axis: its two wings stand 2 x 14 x sin 45 = 19.80 m
        # apart)
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("formation", "dev", "form15-nl-v-northeast", three,
               "Zet de drie drones in een V, met 14 m tussen buren, op 20 m hoogte, 30 m ten noordoosten van waar "
               "ze nu staan, en laat ze daar hangen.",
               lambda c, ev: _all(formation_at(c, ev, three, 20, 14, d30, d30), farthest_apart(ev, three, 19.80)),
               [_formation(three, "wedge", 20, 14, north=d30, east=d30)],
               "De drie hangen in een V 30 m ten noordoosten, op 20 m."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("formation", "dev", "form15-sr-row-then-raise", three,
               "Poređaj sva tri drona u vrstu, jedan pored drugog, na razmaku od 8 metara i na visini od 12 "
               "metara, tačno iznad mesta gde sada stoje; zatim celu vrstu podigni na 22 metra i drži ih tamo.",
               # (the row's climb may overshoot 22 m on the way: only where it holds is checked)
               lambda c, ev: _all(formation_at(c, ev, three, 22, 8, 0, 0), farthest_apart(ev, three, 16)),
               [_formation(three, "line", 12, 8), _formation(three, "line", 22, 8)],
               "Sva tri drona drže vrstu na 22 m, na razmaku od 8 m, iznad svojih mesta."),
        # relative
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("relative", "dev", "rel15-bravo-north-east-dropping", ("bravo",),
               "Bravo up to 12 m, then shift it 18 m north and 8 m east in one go, losing 4 m of height on the way, "
               "and hold it there.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 12), at(ev, "bravo", *c.point("bravo", 18, 8), alt=8),
                                  airborne_at(ev, "bravo", 8)),
               [_takeoff("bravo", 12), _move("bravo", 18, 8, up=-4)],
               "Bravo holds 18 m north and 8 m east of its pad at 8 m."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("relative", "dev", "rel15-pt-charlie-southwest-then-higher", ("charlie",),
               "Leva o charlie até aos 15 m, afasta-o depois 25 m para sudoeste e, já lá, sobe-o mais 5 m; deixa-o "
               "a pairar aí.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -d25, -d25)], alt=15),
                                  at(ev, "charlie", *c.point("charlie", -d25, -d25), alt=20),
                                  airborne_at(ev, "charlie", 20)),
               [_takeoff("charlie", 15), _move("charlie", -d25, -d25), _move("charlie", up=5)],
               "O charlie está a pairar 25 m a sudoeste, a 20 m."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("relative", "dev", "rel15-et-alpha-east-then-lower", ("alpha",),
               "Tõsta alpha 20 meetri kõrgusele, lennuta ta 30 meetrit ida poole ja lase tal seal 12 meetri võrra "
               "laskuda; siis jäta ta õhku hõljuma.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 30)], alt=20),
                                  at(ev, "alpha", *c.point("alpha", 0, 30), alt=8), airborne_at(ev, "alpha", 8)),
               [_takeoff("alpha", 20), _move("alpha", 0, 30), _move("alpha", up=-12)],
               "alpha hõljub 30 m ida pool, 8 m kõrgusel."),
        # question
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("question", "dev", "ask15-sum-alpha-charlie", three,
               "What do alpha's and charlie's batteries come to if you add them together? Don't fly anything, just "
               "tell me.",
               # the typed plan reads, it does not compute: the sum, or the two readings it comes from
               lambda c, ev: _all(_any(answer_mentions_number(ev, 131, 1),
                                       _all(answer_mentions_number(ev, 58, 1), answer_mentions_number(ev, 73, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Together 131 % (alpha 58 %, charlie 73 %).",
               battery={"alpha": 58.0, "bravo": 80.0, "charlie": 73.0}),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("question", "dev", "ask15-vi-rank-by-charge", three,
               "Xếp ba chiếc drone theo mức pin từ cao xuống thấp giúp tôi, kèm phần trăm của từng chiếc. Không cho "
               "chiếc nào bay nhé.",
               lambda c, ev: _all(answer_mentions_number(ev, 90, 1), answer_mentions_number(ev, 66, 1),
                                  answer_mentions_number(ev, 47, 1), nobody_armed(ev)),
               [("fleet_status", {})], "bravo 90 %, charlie 66 %, alpha 47 %.",
               battery={"alpha": 47.0, "bravo": 90.0, "charlie": 66.0}),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("question", "dev", "ask15-th-bravo-short-of-full", three,
               "แบตเตอรี่ของ bravo ยังขาดอีกกี่เปอร์เซ็นต์ถึงจะเต็ม บอกอย่างเดียวพอ ไม่ต้องให้โดรนลำไหนขึ้นบิน",
               # the typed plan reads, it does not compute: the shortfall, or the reading it comes from
               lambda c, ev: _all(_any(answer_mentions_number(ev, 38, 1), answer_mentions_number(ev, 62, 1)),
                                  nobody_armed(ev)),
               [_battery("bravo")], "bravo มีแบต 62 % ยังขาดอีก 38 % ถึงจะเต็ม", battery={"bravo": 62.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse15-alpha-long-leg-south", ("alpha",),
               "Alpha: take off to 20 m and run a single survey leg 1200 m long, heading due south.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 20), refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "alpha", c.max_distance_m), answer_reports_refusal(ev)),
               [_takeoff("alpha", 20), _move("alpha", -1200, 0)],
               "Alpha is up at 20 m; the 1200 m leg south was refused: it is beyond the 1000 m distance limit."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse15-hu-charlie-climb-over-ceiling", ("charlie",),
               "Vidd fel charlie-t 60 méter magasra, aztán onnan emeld még 70 méterrel magasabbra.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 60), refusal_seen(ev, "altitude", "120"),
                                  max_alt_at_most(ev, "charlie", c.max_alt_m), answer_reports_refusal(ev)),
               [_takeoff("charlie", 60), _move("charlie", up=70)],
               "charlie 60 m-en van; a 130 m-re emelést a rendszer elutasította: a magassági korlát 120 m."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse15-tl-bravo-low-battery", ("bravo",),
               "Kailangan ko si bravo sa himpapawid: paakyatin mo siya sa 15 metro, saka mo siya ilipad nang 40 "
               "metro pahilaga.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "bravo"), answer_reports_refusal(ev)),
               [_takeoff("bravo", 15)],
               "Tinanggihan ng gateway: 18 % na lang ang baterya ni bravo, kulang sa 30 % na kailangan para lumipad.",
               battery={"bravo": 18.0}),
        # units
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("units", "dev", "units15-alpha-feet-west-south-land", ("alpha",),
               "Alpha: hover at 45 ft, then slide 60 ft west and 30 ft south, and put it down there.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 45 * FT), at(ev, "alpha", *c.point("alpha", -30 * FT, -60 * FT)),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 45 * FT), _move("alpha", -30 * FT, -60 * FT), _land("alpha")],
               "Alpha hovered at 45 ft (13.7 m), moved 60 ft (18.3 m) west and 30 ft (9.1 m) south, and landed."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("units", "dev", "units15-da-bravo-yards-south-feet-up", ("bravo",),
               "Send bravo 30 yards mod syd i 10 meters højde, løft den derefter 20 fod mere, og lad den blive "
               "hængende dér.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", -30 * YD, 0)], alt=10),
                                  at(ev, "bravo", *c.point("bravo", -30 * YD, 0), alt=10 + 20 * FT),
                                  airborne_at(ev, "bravo", 10 + 20 * FT)),
               [_move("bravo", -30 * YD, 0, alt=10), _move("bravo", up=20 * FT)],
               "Bravo hænger 30 yards (27 m) mod syd i 16 m højde."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("units", "dev", "units15-bg-charlie-feet-km-climb", ("charlie",),
               "Вдигни charlie на 30 фута, прати го 0,04 км на север, после го качи до 70 фута и го остави да виси "
               "там.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 40, 0)], alt=30 * FT),
                                  at(ev, "charlie", *c.point("charlie", 40, 0), alt=70 * FT),
                                  airborne_at(ev, "charlie", 70 * FT)),
               [_takeoff("charlie", 30 * FT), _move("charlie", 40, 0), _move("charlie", alt=70 * FT)],
               "charlie виси на 40 м на север, на 70 фута (21 м)."),
        # pattern
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern15-bravo-l-out-and-back", ("bravo",),
               "Bravo at 10 m: fly an L, 30 m north and then 15 m east, then retrace it exactly back to the pad and "
               "land.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(l_retraced)[:3]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), *_legs("bravo", l_retraced), _land("bravo")],
               "Bravo flew the L out and back and landed on its pad."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern15-ar-charlie-rectangle-east-first", ("charlie",),
               "حلّق بالدرون charlie على ارتفاع 15 مترًا في مسار مستطيل: 30 مترًا نحو الشرق، ثم 12 مترًا نحو "
               "الجنوب، ثم 30 مترًا نحو الغرب، ثم 12 مترًا نحو الشمال، وبعد ذلك أنزله في مكان انطلاقه.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(rectangle)[:3]]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), *_legs("charlie", rectangle), _land("charlie")],
               "أكمل charlie المستطيل وهبط في مكان انطلاقه."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern15-is-alpha-triangle-right", ("alpha",),
               "Láttu alpha fljúga þríhyrning í 10 metra hæð með 25 metra hliðum: fyrsta hliðin í austur, og hann "
               "beygir til hægri í hverju horni. Láttu hann svo lenda þar sem hann fór á loft.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(triangle25)[:2]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), *_legs("alpha", triangle25), _land("alpha")],
               "alpha flaug þríhyrninginn og lenti þar sem hann fór á loft."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # charlie from alpha, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("placement", "dev", "place15-charlie-lands-northwest-of-alpha", three,
               "Get alpha up to 14 m over its pad. Then fly charlie to the spot 10 m north-west of alpha, at 8 m, "
               "and land it there.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=14), airborne_at(ev, "alpha", 14),
                                  reached_alt(ev, "charlie", 8), at(ev, "charlie", *c.point("alpha", d10, -d10)),
                                  landed_disarmed(ev, "charlie"), never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 14), _go("charlie", c.point("alpha", d10, -d10), 8), _land("charlie")],
               "Alpha hovers at 14 m over its pad; charlie landed 10 m north-west of it."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("placement", "dev", "place15-id-charlie-northeast-then-alpha-lands", three,
               "Naikkan alpha ke 8 meter. Setelah itu, tempatkan charlie 15 meter di timur laut alpha pada "
               "ketinggian yang sama, lalu daratkan alpha kembali di tempatnya.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 8), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha"),
                                  at(ev, "charlie", *c.point("alpha", d15, d15), alt=8), airborne_at(ev, "charlie", 8),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 8), _go("charlie", c.point("alpha", d15, d15), 8), _land("alpha")],
               "charlie melayang 15 m di timur laut landasan alpha pada 8 m; alpha sudah mendarat lagi."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("placement", "dev", "place15-hi-charlie-south-above-moved-alpha", three,
               "alpha को 10 मीटर की ऊँचाई पर 20 मीटर पश्चिम ले जाओ और वहीं रोके रखो। फिर charlie को alpha से 10 "
               "मीटर दक्षिण में, उससे 5 मीटर ऊपर, हवा में रोक दो।",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, -20), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "charlie", *c.point("alpha", -10, -20), alt=15), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("alpha", 0, -20, alt=10), _go("charlie", c.point("alpha", -10, -20), 15)],
               "alpha 20 m पश्चिम में 10 m पर है; charlie उससे 10 m दक्षिण में 15 m पर है।"),
        # language
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("language", "dev", "lang15-uk-bravo-northeast-hover", ("bravo",),
               "Підніми bravo на 18 метрів, відправ його на 25 метрів на північний схід і залиш там висіти.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", d25, d25), alt=18), airborne_at(ev, "bravo", 18)),
               [_takeoff("bravo", 18), _move("bravo", d25, d25)], "bravo висить за 25 м на північний схід, на 18 м."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("language", "dev", "lang15-sw-charlie-southwest-land", ("charlie",),
               "Ipaishe charlie hadi mita 12 juu, kisha uipeleke mita 30 kuelekea kusini magharibi, halafu "
               "uiteremshe chini hapo hapo.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 12), at(ev, "charlie", *c.point("charlie", -d30, -d30)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), _move("charlie", -d30, -d30), _land("charlie")],
               "charlie imeruka mita 30 kusini magharibi na kutua hapo."),
        # moved to dev on 2026-12-03, fifteenth round: the test half had been measured
        _entry("language", "dev", "lang15-pa-alpha-west-home", ("alpha",),
               "alpha ਨੂੰ 10 ਮੀਟਰ ਦੀ ਉਚਾਈ ਤੱਕ ਉਡਾਓ, ਫਿਰ ਇਸਨੂੰ 20 ਮੀਟਰ ਪੱਛਮ ਵੱਲ ਲੈ ਜਾਓ, ਅਤੇ ਉਸ ਤੋਂ ਬਾਅਦ ਵਾਪਸ ਘਰ "
               "ਲਿਆ ਕੇ ਉਤਾਰੋ।",
               # the return home climbs to its own height: the leg west is checked at 10 m instead
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, -20)], alt=10),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", 0, -20), _rtl("alpha")],
               "alpha 20 m ਪੱਛਮ ਵੱਲ ਉੱਡ ਕੇ ਘਰ ਵਾਪਸ ਆਇਆ ਅਤੇ ਉਤਰ ਗਿਆ।"),
    ]  # fmt: skip


def _sixteenth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-03 (sixteenth round), before any model ran on it, by a writer who
    did not read the host's word lists or rules: 3 a class; 22 of the 33 outside ``language`` in other
    languages than English, one each (Afrikaans, Arabic, Bosnian, Catalan, Chinese, French, German, Haitian
    Creole, Hebrew, Hindi, Japanese, Korean, Luxembourgish, Malay, Persian, Portuguese, Romanian, Russian,
    Spanish, Swedish, Turkish, Urdu; Bosnian, Haitian Creole and Luxembourgish are new, Urdu is new outside
    ``language``), the ``language`` class's 3 in Greek, Belarusian and Malayalam (Greek is new to the class,
    Belarusian and Malayalam to the corpus, and Malayalam script with it); all of it moved to dev on
    2026-12-03 (sixteenth round), once both models had been measured on it."""
    three = DRONES
    d20, d25, d40 = (x / math.sqrt(2) for x in (20, 25, 40))
    inch = 0.0254
    # a five-pointed star of 30 m strokes: the first due north, a 144 degree turn to the right at each point
    star = [(round(30 * math.cos(math.radians(k * 144)), 2), round(30 * math.sin(math.radians(k * 144)), 2))
            for k in range(5)]  # fmt: skip
    # a half circle of 20 m radius round the pad, from its west point through north to its east point
    arc = [(0.0, -20.0), (20 / math.sqrt(2), -20 / math.sqrt(2)), (20.0, 0.0), (20 / math.sqrt(2), 20 / math.sqrt(2)),
           (0.0, 20.0)]  # fmt: skip
    # a Z of 20 m strokes: east along the top, diagonally to the point 20 m south of the start, east again
    zed = [(0.0, 20.0), (-20.0, -20.0), (0.0, 20.0)]

    def formation_seen(
        c: MissionContext, ev: Evidence, drones: tuple[str, ...], alt: float, spacing: float, north: float
    ) -> Check:
        """At some moment of the flight, every drone at ``alt``, the nearest neighbours ``spacing`` apart (±3 m)
        and the drones' centre ``north`` metres from the centre of their homes: a formation held before the
        drones left it."""
        home_lat = sum(c.homes[d][0] for d in drones) / len(drones)
        home_lon = sum(c.homes[d][1] for d in drones) / len(drones)
        want = offset_position(home_lat, home_lon, north, 0.0)
        samples = min(len(ev.track.get(d, [])) for d in drones)
        for i in range(samples):
            now = [ev.track[d][i] for d in drones]
            if any(abs(s.alt_rel_m - alt) > ALT_TOL_M for s in now):
                continue
            nearest = min(horizontal_distance_m(p.lat, p.lon, q.lat, q.lon)
                          for j, p in enumerate(now) for q in now[j + 1 :])  # fmt: skip
            off = horizontal_distance_m(*_centroid(now), *want)
            if abs(nearest - spacing) <= 3.0 and off <= HORIZONTAL_TOL_M:
                return Check(True, f"the formation was held ({nearest:.1f} m apart at sample {i})")
        return Check(False, "the formation was never held")

    return [
        # single
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("single", "dev", "single16-charlie-over-the-mast", ("charlie",),
               "There's a 12 m radio mast right beside charlie's pad. Take charlie straight up until it's 3 m clear "
               "of the top of the mast, and keep it there.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=15), airborne_at(ev, "charlie", 15)),
               [_takeoff("charlie", 15)], "Charlie hovers at 15 m over its pad, 3 m above the mast."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("single", "dev", "single16-ht-bravo-two-hops", ("bravo",),
               "Fè bravo monte 6 mèt epi ateri sou menm plas la, de fwa youn apre lòt. Apre dezyèm fwa a, kite l "
               "atè.",
               lambda c, ev: _all(takeoffs(ev, "bravo", 6, 2), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 6), _land("bravo"), _takeoff("bravo", 6), _land("bravo")],
               "bravo monte 6 m epi ateri de fwa; kounye a li atè sou plas li."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("single", "dev", "single16-ko-alpha-three-steps", ("alpha",),
               "alpha를 한 번에 5미터씩, 세 번에 나눠서 올려 줘. 다 올라가면 그 높이에서 그대로 떠 있게 해 줘.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=15), airborne_at(ev, "alpha", 15)),
               [_takeoff("alpha", 5), _move("alpha", up=5), _move("alpha", up=5)],
               "alpha는 5 m씩 세 번 올라가서 15 m에 떠 있어."),
        # multi
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("multi", "dev", "multi16-alpha-charlie-swap-heights", three,
               "Alpha up to 10 m and charlie up to 20 m, each over its own pad; then swap their heights. Bravo "
               "stays on the ground.",
               lambda c, ev: _all(rose_to(ev, "charlie", 20),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=20), airborne_at(ev, "alpha", 20),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=10), airborne_at(ev, "charlie", 10),
                                  never_armed(ev, "bravo")),
               [_takeoff("alpha", 10), _takeoff("charlie", 20), _move("alpha", alt=20), _move("charlie", alt=10)],
               "Alpha now hovers at 20 m and charlie at 10 m over their pads; bravo stayed down."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("multi", "dev", "multi16-de-pair-north-alpha-lands-charlie-on", three,
               "Schick alpha und charlie zusammen auf 15 m Höhe 30 m nach Norden. Dort landet alpha, und charlie "
               "fliegt noch 20 m weiter nach Norden und bleibt in der Luft. Bravo bleibt am Boden.",
               lambda c, ev: _all(rose_to(ev, "alpha", 15), at(ev, "alpha", *c.point("alpha", 30, 0)),
                                  landed_disarmed(ev, "alpha"),
                                  visited(ev, "charlie", [c.point("charlie", 30, 0)], alt=15),
                                  at(ev, "charlie", *c.point("charlie", 50, 0), alt=15), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "bravo")),
               [_move("alpha", 30, 0, alt=15), _move("charlie", 30, 0, alt=15), _land("alpha"), _move("charlie", 20, 0)],
               "alpha ist 30 m nördlich gelandet; charlie schwebt 50 m nördlich auf 15 m; bravo blieb am Boden."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("multi", "dev", "multi16-ur-all-up-bravo-higher-two-land", three,
               "alpha، bravo اور charlie تینوں کو 8 میٹر کی اونچائی تک اڑاؤ۔ پھر bravo کو وہیں سے مزید 20 میٹر "
               "اوپر لے جاؤ، اور alpha اور charlie کو ان کی اپنی جگہ پر واپس اتار دو۔",
               lambda c, ev: _all(reached_alt(ev, "alpha", 8), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha"),
                                  reached_alt(ev, "charlie", 8), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie"),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=28), airborne_at(ev, "bravo", 28)),
               [_takeoff("alpha", 8), _takeoff("bravo", 8), _takeoff("charlie", 8), _move("bravo", up=20),
                _land("alpha"), _land("charlie")],
               "bravo اپنے پیڈ کے اوپر 28 میٹر پر ہے؛ alpha اور charlie 8 میٹر تک جا کر اپنی جگہ اتر گئے۔"),
        # compound
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("compound", "dev", "compound16-alpha-north-then-fifty-from-pad", ("alpha",),
               "Alpha: up to 12 m and 40 m north; then turn east and keep going until it's 50 m from its pad in a "
               "straight line, and land it there.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 12), visited(ev, "alpha", [c.point("alpha", 40, 0)], alt=12),
                                  at(ev, "alpha", *c.point("alpha", 40, 30)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), _move("alpha", 40, 0), _move("alpha", 0, 30), _land("alpha")],
               "Alpha flew 40 m north and 30 m east, 50 m from its pad, and landed there."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("compound", "dev", "compound16-ja-charlie-legs-from-height", ("charlie",),
               "charlieを15メートルまで上げて、その高度と同じ距離だけ西へ、続けてその2倍の距離を南へ飛ばしたら、そこで"
               "着陸させて。",
               lambda c, ev: _all(reached_alt(ev, "charlie", 15),
                                  visited(ev, "charlie", [c.point("charlie", 0, -15)], alt=15),
                                  at(ev, "charlie", *c.point("charlie", -30, -15)), landed_disarmed(ev, "charlie")),
               # (the plan names the points: the host's reading of the request made the leg west a climb)
               lambda c: [_takeoff("charlie", 15), _go("charlie", c.point("charlie", 0, -15), 15),
                          _go("charlie", c.point("charlie", -30, -15), 15), _land("charlie")],
               "charlieは西へ15 m、南へ30 m飛んで、そこに着陸した。"),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("compound", "dev", "compound16-lb-bravo-low-leg-north", ("bravo",),
               "Looss bravo op 12 Meter klammen an dann 25 Meter no Osten fléien. Do soll en bis op 3 Meter iwwer "
               "dem Buedem erofgoen an op där Héicht nach 10 Meter no Norden fléien; duerno bleift en do an der Loft.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, 25)], alt=12),
                                  visited(ev, "bravo", [c.point("bravo", 0, 25)], alt=3),
                                  at(ev, "bravo", *c.point("bravo", 10, 25), alt=3), airborne_at(ev, "bravo", 3)),
               [_takeoff("bravo", 12), _move("bravo", 0, 25), _move("bravo", alt=3), _move("bravo", 10, 0)],
               "bravo hänkt 10 m nërdlech an 25 m ëstlech vu senger Startplaz, 3 m iwwer dem Buedem."),
        # conditional
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("conditional", "dev", "cond16-heights-by-rank", three,
               "Put all three up over their pads by charge: the fullest at 20 m, the next at 15 m, the emptiest at "
               "10 m.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=20), airborne_at(ev, "bravo", 20),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=15), airborne_at(ev, "charlie", 15),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=10), airborne_at(ev, "alpha", 10)),
               [("fleet_status", {}), _takeoff("bravo", 20), _takeoff("charlie", 15), _takeoff("alpha", 10)],
               "Bravo (90 %) is at 20 m, charlie (72 %) at 15 m and alpha (55 %) at 10 m.",
               battery={"alpha": 55.0, "bravo": 90.0, "charlie": 72.0}),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("conditional", "dev", "cond16-fr-pair-abreast-or-fuller", three,
               "Si bravo et charlie ont tous les deux au moins 60 % de batterie, mets-les côte à côte à 15 m "
               "d'altitude, à 10 m l'un de l'autre, juste au-dessus de l'endroit où ils sont ; sinon, fais décoller "
               "uniquement celui des deux qui en a le plus, à 15 m. Alpha ne bouge pas.",
               lambda c, ev: _all(formation_at(c, ev, ("bravo", "charlie"), 15, 10, 0, 0), never_armed(ev, "alpha")),
               [("fleet_status", {}), _formation(("bravo", "charlie"), "line", 15, 10)],
               "bravo (72 %) et charlie (65 %) ont tous les deux au moins 60 % : ils sont côte à côte à 15 m, à 10 m "
               "l'un de l'autre.",
               battery={"bravo": 72.0, "charlie": 65.0}),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("conditional", "dev", "cond16-he-all-or-none", three,
               "אם לכל שלושת הרחפנים יש לפחות 40% סוללה, הרם את כולם ל-10 מטר מעל המנחתים שלהם. אם אפילו לאחד מהם "
               "יש פחות מזה, אל תמריא אף אחד, ותגיד לי מי זה וכמה סוללה יש לו.",
               lambda c, ev: _all(answer_says(ev, r"charlie", "charlie"), answer_mentions_number(ev, 37, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "ל-charlie יש רק 37%, לכן אף רחפן לא המריא.",
               battery={"alpha": 66.0, "bravo": 81.0, "charlie": 37.0}),
        # formation
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("formation", "dev", "form16-diagonal-row-nw-se", three,
               "Line the three up in a diagonal row running from north-west to south-east, 10 m apart, at 14 m, "
               "right above where they stand, and hold them there.",
               lambda c, ev: _all(formation_at(c, ev, three, 14, 10, 0, 0), farthest_apart(ev, three, 20),
                                  row_along(ev, three, 135)),
               # (the typed plan has no heading for a formation: each drone flies to its slot of the row)
               lambda c: [_go(d, slot(c, three, n, e), 14)
                          for d, n, e in (("alpha", 10 / math.sqrt(2), -10 / math.sqrt(2)), ("bravo", 0.0, 0.0),
                                          ("charlie", -10 / math.sqrt(2), 10 / math.sqrt(2)))],
               "The three hold a north-west to south-east row 10 m apart at 14 m over where they stood."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("formation", "dev", "form16-ru-row-spread-wider", three,
               "Выстрой все три дрона в ряд прямо над их площадками на высоте 15 метров, с интервалом 8 метров, а "
               "потом раздвинь их, чтобы между соседями было 16 метров. Пусть так и висят.",
               lambda c, ev: _all(formation_at(c, ev, three, 15, 16, 0, 0), farthest_apart(ev, three, 32)),
               [_formation(three, "line", 15, 8), _formation(three, "line", 15, 16)],
               "Все три дрона висят в ряд на 15 м, по 16 м между соседями, над своими площадками."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("formation", "dev", "form16-ca-column-north-then-home", three,
               "Posa els tres drons en columna, l'un darrere l'altre, separats 10 metres, a 12 metres d'altura i 30 "
               "metres al nord d'on són ara. Quan hi hagin arribat, fes-los tornar tots tres a casa.",
               lambda c, ev: _all(formation_seen(c, ev, three, 12, 10, 30),
                                  *(at(ev, d, *_home(c, d)) for d in three), *(landed_disarmed(ev, d) for d in three)),
               [_formation(three, "column", 12, 10, north=30), _rtl("alpha"), _rtl("bravo"), _rtl("charlie")],
               "Els tres drons han fet la columna 30 m al nord i han tornat a casa."),
        # relative
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("relative", "dev", "rel16-alpha-east-corrected-to-west", ("alpha",),
               "Alpha up to 10 m, then 20 m north and 15 m east (sorry, west, not east) and hold it there.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, -15), alt=10), airborne_at(ev, "alpha", 10)),
               # (the plan names the point: the host's reading of the request flew the leg east)
               lambda c: [_takeoff("alpha", 10), _go("alpha", c.point("alpha", 20, -15), 10)],
               "Alpha holds 20 m north and 15 m west of its pad at 10 m."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("relative", "dev", "rel16-af-charlie-east-climbing-gradient", ("charlie",),
               "Lig charlie op tot 8 meter en skuif hom dan 30 meter oos. Op pad moet hy 1 meter klim vir elke 3 "
               "meter wat hy vorentoe vlieg; laat hom daar hang.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 30), alt=18), airborne_at(ev, "charlie", 18)),
               [_takeoff("charlie", 8), _move("charlie", 0, 30, up=10)],
               "charlie hang 30 m oos van sy beginpunt, op 18 m."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("relative", "dev", "rel16-zh-bravo-mirror-across-pad", ("bravo",),
               "让 bravo 升到 12 米，往西北方向飞 20 米；然后把它挪到起飞点另一侧、与现在的位置正好对称的地方，高度不变，"
               "在那里悬停。",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", d20, -d20)], alt=12),
                                  at(ev, "bravo", *c.point("bravo", -d20, d20), alt=12), airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 12), _move("bravo", d20, -d20), _move("bravo", -2 * d20, 2 * d20)],
               "bravo 在起飞点东南方向 20 米、12 米高处悬停。"),
        # question
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("question", "dev", "ask16-charlie-runs-left", three,
               "Each survey run uses about 15 % of a battery, and charlie must still have 30 % left when it lands "
               "from the last one. Going by its charge right now, how many full runs can it do? Just work it out; "
               "nothing flies.",
               # the typed plan reads, it does not compute: the number of runs, or the reading it comes from
               lambda c, ev: _all(_any(answer_mentions_number(ev, 3, 0.5), answer_mentions_number(ev, 78, 1)),
                                  nobody_armed(ev)),
               [_battery("charlie")], "Charlie has 78 %: three runs (45 %) leave it 33 %, a fourth would not.",
               battery={"alpha": 60.0, "bravo": 90.0, "charlie": 78.0}),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("question", "dev", "ask16-sv-second-most-charge", three,
               "Vilken drönare har näst mest batteri kvar, och hur många procent har den? Starta ingenting.",
               lambda c, ev: _all(answer_says(ev, r"\balpha\b", "alpha"), answer_mentions_number(ev, 71, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "alpha, med 71 % (charlie har mest, 86 %).",
               battery={"alpha": 71.0, "bravo": 58.0, "charlie": 86.0}),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("question", "dev", "ask16-ar-closest-to-bravo", three,
               "أيّ الطائرتين، alpha أم charlie، نسبة بطاريتها أقرب إلى نسبة بطارية bravo؟ اذكر لي النسب، ولا تُقلع أي "
               "طائرة.",
               lambda c, ev: _all(answer_says(ev, r"\balpha\b", "alpha"), answer_mentions_number(ev, 64, 1),
                                  answer_mentions_number(ev, 70, 1), nobody_armed(ev)),
               [("fleet_status", {})], "alpha: بطاريتها 64 %، أي 6 نقاط عن bravo (70 %)، أما charlie (81 %) فيبعد 11 نقطة.",
               battery={"alpha": 64.0, "bravo": 70.0, "charlie": 81.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse16-alpha-second-leg-too-far", ("alpha",),
               "Alpha at 20 m: 300 m north first, then a 1 km leg due east from there.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 300, 0)]),
                                  refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "alpha", c.max_distance_m), answer_reports_refusal(ev)),
               [_takeoff("alpha", 20), _move("alpha", 300, 0), _move("alpha", 0, 1000)],
               "Alpha is 300 m north at 20 m; the 1 km leg east was refused: it would end 1044 m from home, beyond "
               "the 1000 m limit."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse16-es-bravo-triple-height", ("alpha", "bravo"),
               "Sube a alpha a 45 metros y a bravo al triple de esa altura, cada uno sobre su base.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=45), airborne_at(ev, "alpha", 45),
                                  refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "bravo", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("alpha", 45), _takeoff("bravo", 135)],
               "alpha está a 45 m; subir bravo a 135 m fue rechazado: supera el límite de altitud de 120 m."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("refusal", "dev", "refuse16-bs-row-charlie-low", three,
               "Poredaj sva tri drona u red iznad mjesta gdje sada stoje, na visini od 15 metara i s razmakom od 10 "
               "metara.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "charlie"), answer_reports_refusal(ev)),
               [_formation(three, "line", 15, 10)],
               "Formacija je odbijena: charlie ima samo 22 % baterije, a za polijetanje treba najmanje 30 %.",
               battery={"charlie": 22.0}),
        # units
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("units", "dev", "units16-bravo-feet-and-inches", ("bravo",),
               "Bravo: climb to 26 ft 3 in, fly 100 ft east, then climb another 16 ft 5 in and hold it there.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, 100 * FT)], alt=26 * FT + 3 * inch),
                                  at(ev, "bravo", *c.point("bravo", 0, 100 * FT), alt=42 * FT + 8 * inch),
                                  airborne_at(ev, "bravo", 42 * FT + 8 * inch)),
               [_takeoff("bravo", 26 * FT + 3 * inch), _move("bravo", 0, 100 * FT), _move("bravo", up=16 * FT + 5 * inch)],
               "Bravo holds 100 ft (30.5 m) east of its pad at 42 ft 8 in (13.0 m)."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("units", "dev", "units16-pt-alpha-feet-miles-yards-land", ("alpha",),
               "Suba o alpha a 35 pés, leve-o 0,03 milha para o oeste e depois 20 jardas para o sul, e pouse-o ali.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 35 * FT), visited(ev, "alpha", [c.point("alpha", 0, -0.03 * MI)]),
                                  at(ev, "alpha", *c.point("alpha", -20 * YD, -0.03 * MI)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 35 * FT), _move("alpha", 0, -0.03 * MI), _move("alpha", -20 * YD, 0), _land("alpha")],
               "O alpha subiu a 35 pés (10,7 m), voou 0,03 milha (48 m) para o oeste e 20 jardas (18 m) para o sul "
               "e pousou."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("units", "dev", "units16-fa-charlie-feet-km-nw-down", ("charlie",),
               "charlie را تا ارتفاع 50 پا بالا ببر، بعد 0.04 کیلومتر به سمت شمال غربی ببرش، آنجا 15 پا پایین "
               "بیاورش و همان‌جا نگهش دار.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", d40, -d40)], alt=50 * FT),
                                  at(ev, "charlie", *c.point("charlie", d40, -d40), alt=35 * FT),
                                  airborne_at(ev, "charlie", 35 * FT)),
               [_takeoff("charlie", 50 * FT), _move("charlie", d40, -d40), _move("charlie", up=-15 * FT)],
               "charlie در 40 متری شمال غربی، در ارتفاع 35 پا (10.7 متر) معلق است."),
        # pattern
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern16-charlie-five-pointed-star", ("charlie",),
               "Charlie at 12 m: fly a five-pointed star with 30 m strokes, the first stroke due north, then a 144° "
               "turn to the right at each point until it's back where it started, and land it there.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(star)[:4]]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), *_legs("charlie", star), _land("charlie")],
               "Charlie flew the star and landed where it started."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern16-ro-alpha-semicircle-north", ("alpha",),
               "Fă-l pe alpha să zboare la 10 metri înălțime un semicerc cu raza de 20 de metri în jurul punctului "
               "de decolare: să pornească din punctul aflat la 20 de metri la vest de acesta, să treacă prin nord și "
               "să termine în punctul aflat la 20 de metri la est, iar acolo să aterizeze.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in arc[::2]]),
                                  at(ev, "alpha", *c.point("alpha", 0, 20)), landed_disarmed(ev, "alpha")),
               lambda c: [_takeoff("alpha", 10), *(_go("alpha", c.point("alpha", n, e), 10) for n, e in arc),
                          _land("alpha")],
               "alpha a zburat semicercul prin nord și a aterizat la 20 m est de punctul de decolare."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("pattern", "dev", "pattern16-hi-bravo-letter-z", ("bravo",),
               "bravo को 12 मीटर की ऊँचाई पर अंग्रेज़ी के Z अक्षर जैसे रास्ते पर उड़ाओ: पहले 20 मीटर पूर्व, फिर तिरछे "
               "दक्षिण-पश्चिम की ओर उस जगह तक जो शुरुआत से ठीक 20 मीटर दक्षिण में है, और फिर दोबारा 20 मीटर पूर्व। "
               "आख़िर में उसे वहीं उतार दो।",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(zed)[:2]]),
                                  at(ev, "bravo", *c.point("bravo", -20, 20)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), *_legs("bravo", zed), _land("bravo")],
               "bravo ने Z उड़ाया और शुरुआत से 20 m दक्षिण और 20 m पूर्व में उतर गया।"),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # charlie from alpha, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("placement", "dev", "place16-charlie-behind-alpha", three,
               "Alpha flies 30 m north at 12 m and stops there. Then charlie tucks in 10 m behind alpha, on the side "
               "it came from, 3 m higher than it.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 30, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", 20, 0), alt=15), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("alpha", 30, 0, alt=12), _go("charlie", c.point("alpha", 20, 0), 15)],
               "Alpha hovers 30 m north at 12 m; charlie is 10 m behind it, to the south, at 15 m."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("placement", "dev", "place16-tr-charlie-follows-alpha", three,
               "alpha'yı 12 metreye kaldır ve charlie'yi alpha'nın 15 metre güneyine, aynı yüksekliğe getir. Sonra "
               "alpha'yı 20 metre doğuya kaydır; charlie de aradaki mesafeyi bozmadan onunla birlikte kaysın.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("alpha", -15, 0)], alt=12),
                                  at(ev, "alpha", *c.point("alpha", 0, 20), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", -15, 20), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 12), _go("charlie", c.point("alpha", -15, 0), 12), _move("alpha", 0, 20),
                          _move("charlie", 0, 20)],
               "alpha 20 m doğuda 12 m'de; charlie onun 15 m güneyinde, aynı yükseklikte."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("placement", "dev", "place16-ms-charlie-north-of-alpha-pad-half-bravo", three,
               "Naikkan bravo ke 16 meter betul-betul di atas padnya. Kemudian bawa charlie ke titik 20 meter di "
               "utara pad alpha, pada separuh ketinggian bravo, dan biarkan kedua-duanya berlegar di situ.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=16), airborne_at(ev, "bravo", 16),
                                  at(ev, "charlie", *c.point("alpha", 20, 0), alt=8), airborne_at(ev, "charlie", 8),
                                  never_armed(ev, "alpha")),
               lambda c: [_takeoff("bravo", 16), _go("charlie", c.point("alpha", 20, 0), 8)],
               "bravo berlegar 16 m di atas padnya; charlie berlegar 20 m di utara pad alpha pada 8 m."),
        # language
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("language", "dev", "lang16-el-alpha-southeast-land", ("alpha",),
               "Σήκωσε το alpha στα 14 μέτρα, πήγαινέ το 25 μέτρα νοτιοανατολικά και προσγείωσέ το εκεί.",
               lambda c, ev: _all(reached_alt(ev, "alpha", 14), at(ev, "alpha", *c.point("alpha", -d25, d25)),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 14), _move("alpha", -d25, d25), _land("alpha")],
               "Το alpha πέταξε 25 m νοτιοανατολικά και προσγειώθηκε εκεί."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("language", "dev", "lang16-be-bravo-west-hover", ("bravo",),
               "Падымі bravo на 16 метраў, адвядзі яго на 30 метраў на захад і пакінь там вісець.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -30), alt=16), airborne_at(ev, "bravo", 16)),
               [_takeoff("bravo", 16), _move("bravo", 0, -30)], "bravo вісіць за 30 м на захад, на 16 м."),
        # moved to dev on 2026-12-03, sixteenth round: the test half had been measured
        _entry("language", "dev", "lang16-ml-charlie-northeast-home", ("charlie",),
               "charlie-യെ 12 മീറ്റർ ഉയരത്തിലേക്ക് പറത്തുക, പിന്നെ വടക്കുകിഴക്ക് ദിശയിൽ 20 മീറ്റർ കൊണ്ടുപോകുക, "
               "അതിനുശേഷം പറന്നുയർന്ന സ്ഥലത്തേക്ക് തിരികെ കൊണ്ടുവന്ന് ഇറക്കുക.",
               # the return home climbs to its own height: the leg north-east is checked at 12 m instead
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", d20, d20)], alt=12),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), _move("charlie", d20, d20), _rtl("charlie")],
               "charlie വടക്കുകിഴക്ക് 20 m പറന്ന് തിരികെ വന്ന് ഇറങ്ങി."),
    ]  # fmt: skip


def _seventeenth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-03 (seventeenth round), before any model ran on it, by a writer who
    did not read the host's word lists or rules: 3 a class; 22 of the 33 outside ``language`` in other
    languages than English, one each (Bulgarian, Croatian, Czech, Danish, Dutch, Estonian, Finnish, Greek,
    Hungarian, Icelandic, Indonesian, Italian, Maltese, Norwegian, Polish, Slovak, Swahili, Tagalog, Tamil,
    Thai, Ukrainian, Vietnamese; Maltese is new, Tamil is new outside ``language``), the ``language``
    class's 3 in Telugu, Kannada and Mongolian (all three new to the corpus, and Telugu and Kannada script
    with them); all of it moved to dev on 2026-12-04 (seventeenth round): the 1.5B model had run 89 of its
    108 runs on it (figures lost with the session that ran them) and its failures had informed changes to
    the host."""
    three = DRONES
    d15, d20 = (x / math.sqrt(2) for x in (15, 20))
    # two laps round the pad, clockwise from the north side: 10 m, then 20 m from it; its north, east, south
    # and west points, and the legs that fly them (out to the north point, four legs round, out to the next)
    inner, outer = ([(r, 0.0), (0.0, r), (-r, 0.0), (0.0, -r)] for r in (10.0, 20.0))
    rings = [(10.0, 0.0), (-10.0, 10.0), (-10.0, -10.0), (10.0, -10.0), (10.0, 10.0),
             (10.0, 0.0), (-20.0, 20.0), (-20.0, -20.0), (20.0, -20.0), (20.0, 20.0)]  # fmt: skip
    # a 20 m square north first turning right, then the same square the other way round
    square = [(20.0, 0.0), (0.0, 20.0), (-20.0, 0.0), (0.0, -20.0)]
    reverse = [(0.0, 20.0), (20.0, 0.0), (0.0, -20.0), (-20.0, 0.0)]
    # three drones evenly on a circle of 15 m radius are 15 * sqrt(3) m from their neighbours
    chord = 15 * math.sqrt(3)

    def farthest_bearing(now: list[DroneTruth]) -> float:
        a, b = max(((p, q) for i, p in enumerate(now) for q in now[i + 1 :]),
                   key=lambda pq: horizontal_distance_m(pq[0].lat, pq[0].lon, pq[1].lat, pq[1].lon))  # fmt: skip
        return bearing_deg(a.lat, a.lon, b.lat, b.lon)

    def off_line(now: list[DroneTruth], bearing: float) -> float:
        off = (farthest_bearing(now) - bearing) % 180.0
        return min(off, 180.0 - off)

    def row_along(ev: Evidence, drones: tuple[str, ...], bearing: float) -> Check:
        """The two drones farthest apart lie on a line running along ``bearing`` (either way round, ±15°)."""
        off = off_line([ev.final[d] for d in drones], bearing)
        return Check(off <= 15.0, f"the row runs {off:.0f} degrees off a {bearing:g} degree line")

    def row_seen(
        c: MissionContext, ev: Evidence, drones: tuple[str, ...], alt: float, spacing: float, bearing: float
    ) -> Check:
        """At some moment of the flight, every drone at ``alt``, the nearest neighbours ``spacing`` apart (±3 m),
        the drones' centre over the centre of their homes and the row along ``bearing`` (±15°): a row held
        before the drones left it."""
        want = slot(c, drones, 0.0, 0.0)
        samples = min(len(ev.track.get(d, [])) for d in drones)
        for i in range(samples):
            now = [ev.track[d][i] for d in drones]
            if any(abs(s.alt_rel_m - alt) > ALT_TOL_M for s in now):
                continue
            nearest = min(horizontal_distance_m(p.lat, p.lon, q.lat, q.lon)
                          for j, p in enumerate(now) for q in now[j + 1 :])  # fmt: skip
            off = horizontal_distance_m(*_centroid(now), *want)
            if abs(nearest - spacing) <= 3.0 and off <= HORIZONTAL_TOL_M and off_line(now, bearing) <= 15.0:
                return Check(True, f"the row was held ({nearest:.1f} m apart at sample {i})")
        return Check(False, f"no row along {bearing:g} degrees was held")

    def on_radius(c: MissionContext, ev: Evidence, drones: tuple[str, ...], radius: float) -> Check:
        """Every drone ``radius`` metres (±3 m) from the centre of the drones' homes."""
        centre = slot(c, drones, 0.0, 0.0)
        far = {d: horizontal_distance_m(ev.final[d].lat, ev.final[d].lon, *centre) for d in drones}
        ok = all(abs(r - radius) <= 3.0 for r in far.values())
        return Check(ok, "from the centre: " + ", ".join(f"{d} {r:.1f} m" for d, r in far.items())
                     + f" (want {radius:g})")  # fmt: skip

    return [
        # single
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("single", "dev", "single17-charlie-quarter-of-ceiling", ("charlie",),
               "Our ceiling on this field is 120 m. Take charlie up to a quarter of that, straight over its pad, "
               "and leave it there.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=30), airborne_at(ev, "charlie", 30)),
               [_takeoff("charlie", 30)], "Charlie hovers at 30 m over its pad, a quarter of the 120 m ceiling."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("single", "dev", "single17-it-bravo-roof-height", ("bravo",),
               "Porta bravo all'altezza del tetto del palazzo qui di fianco: sono quattro piani da tre metri e "
               "mezzo ciascuno. Poi tienilo lì in volo, sopra la sua piazzola.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=14), airborne_at(ev, "bravo", 14)),
               [_takeoff("bravo", 14)], "bravo è in volo a 14 m sopra la sua piazzola, all'altezza del tetto."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("single", "dev", "single17-mt-alpha-up-down-up", ("alpha",),
               "Tella' lil alpha sa 10 metri, niżżlu lura fuq il-post tiegħu, u mbagħad erġa' tellgħu sa 10 metri "
               "u ħallih hemm fl-arja.",
               lambda c, ev: _all(takeoffs(ev, "alpha", 10, 2), at(ev, "alpha", *_home(c, "alpha"), alt=10),
                                  airborne_at(ev, "alpha", 10)),
               [_takeoff("alpha", 10), _land("alpha"), _takeoff("alpha", 10)],
               "alpha tela' sa 10 m, niżel, u reġa' tela' sa 10 m: issa qiegħed fl-arja fuq il-post tiegħu."),
        # multi
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("multi", "dev", "multi17-bravo-same-as-alpha-higher", three,
               "Alpha: 20 m south at 10 m, then hover. Bravo does exactly the same from its own pad, only 10 m "
               "higher. Charlie stays where it is.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", -20, 0), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "bravo", *c.point("bravo", -20, 0), alt=20), airborne_at(ev, "bravo", 20),
                                  never_armed(ev, "charlie")),
               [_move("alpha", -20, 0, alt=10), _move("bravo", -20, 0, alt=20)],
               "Alpha hovers 20 m south of its pad at 10 m, bravo 20 m south of its own at 20 m; charlie stayed down."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("multi", "dev", "multi17-pl-north-by-multiples", three,
               "Wyślij wszystkie trzy drony na północ, na wysokości 10 m: alpha ma przelecieć 15 m, bravo dwa razy "
               "tyle, a charlie trzy razy tyle co alpha. Na końcu niech wszystkie wylądują tam, gdzie doleciały.",
               lambda c, ev: _all(*(_all(visited(ev, d, [c.point(d, n, 0)], alt=10), at(ev, d, *c.point(d, n, 0)),
                                         landed_disarmed(ev, d))
                                    for d, n in (("alpha", 15), ("bravo", 30), ("charlie", 45)))),
               [_move("alpha", 15, 0, alt=10), _move("bravo", 30, 0, alt=10), _move("charlie", 45, 0, alt=10),
                _land("alpha"), _land("bravo"), _land("charlie")],
               "alpha wylądował 15 m na północ, bravo 30 m, a charlie 45 m."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("multi", "dev", "multi17-cs-cross-at-two-heights", three,
               "Alpha a charlie si prohodí strany: alpha poletí 20 metrů na východ a charlie 20 metrů na západ, "
               "takže se cestou minou. Aby se nesrazily, alpha poletí ve výšce 10 metrů a charlie v 16 metrech. Pak "
               "ať oba zůstanou viset ve vzduchu; bravo zůstává na zemi.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 20), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "charlie", *c.point("charlie", 0, -20), alt=16),
                                  airborne_at(ev, "charlie", 16), never_armed(ev, "bravo")),
               [_move("alpha", 0, 20, alt=10), _move("charlie", 0, -20, alt=16)],
               "alpha visí 20 m východně od svého startu v 10 m, charlie 20 m západně od svého v 16 m; bravo "
               "zůstal na zemi."),
        # compound
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("compound", "dev", "compound17-charlie-three-hops-east", ("charlie",),
               "Move charlie east in hops: up to 5 m, 15 m east, back down onto the ground. Three hops like that, "
               "and leave it on the ground where the third one ends.",
               lambda c, ev: _all(takeoffs(ev, "charlie", 5, 3),
                                  visited(ev, "charlie", [c.point("charlie", 0, 15), c.point("charlie", 0, 30)]),
                                  at(ev, "charlie", *c.point("charlie", 0, 45)), landed_disarmed(ev, "charlie")),
               [*(call for _ in range(3) for call in (_takeoff("charlie", 5), _move("charlie", 0, 15), _land("charlie")))],
               "Charlie hopped 15 m east three times and sits on the ground 45 m east of its pad."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("compound", "dev", "compound17-hu-bravo-halving-legs", ("bravo",),
               "Emeld fel bravo-t 10 méterre, repülj vele 40 métert északra, aztán feleannyit keletre, majd annak "
               "is a felét délre, és ott tedd le.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 40, 0), c.point("bravo", 40, 20)], alt=10),
                                  at(ev, "bravo", *c.point("bravo", 30, 20)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), _move("bravo", 40, 0), _move("bravo", 0, 20), _move("bravo", -10, 0),
                _land("bravo")],
               "bravo 40 m-t repült északra, 20 m-t keletre, 10 m-t délre, és ott leszállt."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("compound", "dev", "compound17-sk-charlie-dip-then-home", ("charlie",),
               "Vznes charlie do 15 metrov a preleť s ním 20 metrov na západ. Tam ho spusti na 5 metrov, potom ho "
               "znova vytiahni na 15 metrov a nakoniec ho pošli domov.",
               lambda c, ev: _all(passed(ev, "charlie", [(c.point("charlie", 0, -20), 15), (c.point("charlie", 0, -20), 5)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 15), _move("charlie", 0, -20), _move("charlie", alt=5), _move("charlie", alt=15),
                _rtl("charlie")],
               "charlie klesol 20 m západne na 5 m, znova vystúpil na 15 m a vrátil sa domov."),
        # conditional
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("conditional", "dev", "cond17-charlie-three-laps-or-stay", three,
               "A lap of the field costs charlie about 10 % of its battery, and it has to land with at least 30 % "
               "left. If it has enough for three laps, send it 30 m east at 12 m and hold it there; if not, keep "
               "it on the ground and tell me what it has.",
               lambda c, ev: _all(answer_mentions_number(ev, 54, 1), nobody_armed(ev)),
               [_battery("charlie")], "Charlie has 54 %; three laps and the reserve need 60 %, so it stays down.",
               battery={"charlie": 54.0}),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("conditional", "dev", "cond17-fi-fuller-north-other-south", three,
               "Katso alphan ja bravon akut. Se, jonka akku on täydempi, lentää 12 metrin korkeudessa 30 metriä "
               "pohjoiseen, ja toinen samalla korkeudella 10 metriä etelään; molemmat jäävät sinne leijumaan. "
               "Charlie pysyy maassa.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 30, 0), alt=12), airborne_at(ev, "bravo", 12),
                                  at(ev, "alpha", *c.point("alpha", -10, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  never_armed(ev, "charlie")),
               [("fleet_status", {}), _move("bravo", 30, 0, alt=12), _move("alpha", -10, 0, alt=12)],
               "bravolla (83 %) on täydempi akku: se leijuu 30 m pohjoisessa, alpha (48 %) 10 m etelässä, "
               "molemmat 12 metrissä.",
               battery={"alpha": 48.0, "bravo": 83.0}),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("conditional", "dev", "cond17-id-sum-over-120", three,
               "Jumlahkan persentase baterai alpha dan charlie. Kalau totalnya lebih dari 120 %, naikkan keduanya "
               "ke 10 meter tepat di atas landasannya masing-masing; kalau tidak, naikkan hanya yang baterainya "
               "lebih banyak. Bravo tetap di darat.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=10), airborne_at(ev, "charlie", 10),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               [("fleet_status", {}), _takeoff("charlie", 10)],
               "alpha 52 % dan charlie 63 %, totalnya 115 %: hanya charlie yang naik ke 10 m.",
               battery={"alpha": 52.0, "charlie": 63.0}),
        # formation
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("formation", "dev", "form17-row-turned-into-column", three,
               "Line the three up abreast at 12 m over where they stand, 10 m apart. Once they're in line, turn "
               "the row into a column, one behind the other, with the same spacing and on the same spot, and hold "
               "them there.",
               lambda c, ev: _all(row_seen(c, ev, three, 12, 10, 90), formation_at(c, ev, three, 12, 10, 0, 0),
                                  farthest_apart(ev, three, 20), row_along(ev, three, 0)),
               [_formation(three, "line", 12, 10), _formation(three, "column", 12, 10)],
               "The three stood abreast at 12 m, then re-formed into a north-south column, 10 m apart, on the "
               "same spot."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("formation", "dev", "form17-nl-circle-by-radius", three,
               "Zet de drie drones gelijkmatig verdeeld op een cirkel met een straal van 15 meter rond het midden "
               "tussen hun startplekken, op 18 meter hoogte, en laat ze daar hangen.",
               lambda c, ev: _all(formation_at(c, ev, three, 18, chord, 0, 0), farthest_apart(ev, three, chord),
                                  on_radius(c, ev, three, 15)),
               [_formation(three, "circle", 18, chord)],
               "De drie drones hangen op 18 m op een cirkel van 15 m straal, 26 m van elkaar."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("formation", "dev", "form17-el-stepped-row", three,
               "Στοίχισε τα τρία drones σε μια σειρά από τα δυτικά προς τα ανατολικά (alpha, bravo, charlie) με 10 "
               "μέτρα απόσταση μεταξύ τους, ακριβώς πάνω από εκεί που βρίσκονται, αλλά κλιμακωτά στο ύψος: το "
               "alpha στα 10 μέτρα, το bravo στα 14 και το charlie στα 18. Άφησέ τα να αιωρούνται εκεί.",
               lambda c, ev: _all(*(_all(at(ev, d, *slot(c, three, 0, e), alt=h), airborne_at(ev, d, h))
                                    for d, e, h in (("alpha", -10, 10), ("bravo", 0, 14), ("charlie", 10, 18)))),
               lambda c: [_go(d, slot(c, three, 0, e), h)
                          for d, e, h in (("alpha", -10, 10), ("bravo", 0, 14), ("charlie", 10, 18))],
               "Τα τρία drones αιωρούνται σε σειρά ανά 10 m: το alpha στα 10 m, το bravo στα 14 m, το charlie στα 18 m."),
        # relative
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("relative", "dev", "rel17-charlie-nose-east-forward-left", ("charlie",),
               "Charlie's nose points east. Take it up to 10 m, then move it 20 m forward and 10 m to its left, "
               "and hold it there.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 10, 20), alt=10), airborne_at(ev, "charlie", 10)),
               [_takeoff("charlie", 10), _move("charlie", 10, 20)],
               "Charlie holds 20 m east and 10 m north of its pad at 10 m."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("relative", "dev", "rel17-hr-alpha-undo-last-two", ("alpha",),
               "Podigni alpha na 10 metara, odleti s njim 20 metara na sjever, zatim 15 metara na istok pa još 10 "
               "metara na sjever. Onda ga vrati tamo gdje je bio prije zadnja dva pomaka i neka ondje lebdi.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in ((20, 0), (20, 15), (30, 15))],
                                          alt=10),
                                  at(ev, "alpha", *c.point("alpha", 20, 0), alt=10), airborne_at(ev, "alpha", 10)),
               [_takeoff("alpha", 10), _move("alpha", 20, 0), _move("alpha", 0, 15), _move("alpha", 10, 0),
                _move("alpha", -10, -15)],
               "alpha lebdi 20 m sjeverno od mjesta polijetanja, na 10 m."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("relative", "dev", "rel17-uk-bravo-four-north-three-east", ("bravo",),
               "Підніми bravo на 12 метрів і відведи його на 50 метрів у такому напрямку, щоб на кожні 4 метри на "
               "північ припадало 3 метри на схід. Там нехай і висить.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 40, 30), alt=12), airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 12), _move("bravo", 40, 30)],
               "bravo висить за 40 м на північ і 30 м на схід від старту, на 12 м."),
        # question
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("question", "dev", "ask17-bravo-hover-minutes", three,
               "Bravo uses about 2 % of its battery a minute in a hover. How many minutes could it hover before "
               "it's down to 30 %? Work it out from what it has now; don't launch it.",
               # the typed plan reads, it does not compute: the minutes, or the reading they come from
               lambda c, ev: _all(_any(answer_mentions_number(ev, 22, 0.5), answer_mentions_number(ev, 74, 1)),
                                  nobody_armed(ev)),
               [_battery("bravo")], "Bravo has 74 %: 44 points above 30 % at 2 % a minute is about 22 minutes.",
               battery={"alpha": 61.0, "bravo": 74.0, "charlie": 88.0}),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("question", "dev", "ask17-vi-below-average", three,
               "Chiếc drone nào có mức pin thấp hơn mức trung bình của cả ba chiếc? Cho tôi biết nó còn bao nhiêu "
               "phần trăm. Đừng cho chiếc nào cất cánh.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 48, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "bravo, còn 48 % (trung bình của cả ba là khoảng 60 %).",
               battery={"alpha": 62.0, "bravo": 48.0, "charlie": 71.0}),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("question", "dev", "ask17-th-charlie-twice-alpha", three,
               "แบตของ charlie เหลือมากกว่าสองเท่าของ alpha หรือเปล่า ขอตัวเลขเปอร์เซ็นต์ของทั้งสองลำด้วย "
               "แต่ไม่ต้องให้ลำไหนขึ้นบินนะ",
               lambda c, ev: _all(answer_mentions_number(ev, 84, 1), answer_mentions_number(ev, 40, 1),
                                  nobody_armed(ev)),
               [_battery("alpha"), _battery("charlie")], "ใช่ charlie มี 84% ส่วน alpha มี 40% มากกว่าสองเท่า",
               battery={"alpha": 40.0, "bravo": 66.0, "charlie": 84.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("refusal", "dev", "refuse17-bravo-above-sea-level", ("bravo",),
               "The field sits at 490 m above sea level. Take bravo up to 620 m above sea level, over its pad, and "
               "hold it there.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "bravo", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("bravo", 130)],
               "Refused: 620 m above sea level is 130 m over the field, above the 120 m altitude limit."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("refusal", "dev", "refuse17-no-v-far-north", three,
               "Fly alle tre dronene i V-formasjon med 10 meter mellom naboene, i 20 meters høyde, og plasser "
               "formasjonen 1,2 km nord for der de står nå.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  *(stayed_within(ev, c, d, c.max_distance_m) for d in three),
                                  answer_reports_refusal(ev)),
               [_formation(three, "wedge", 20, 10, north=1200)],
               "Avvist: 1,2 km nord er utenfor grensen på 1000 m fra hjemmepunktet."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("refusal", "dev", "refuse17-da-row-lowered-too-low", three,
               "Stil de tre droner op på en række lige over der, hvor de står, i 8 meters højde og med 10 meter "
               "mellem hver. Sænk derefter hele rækken 7 meter.",
               lambda c, ev: _all(formation_at(c, ev, three, 8, 10, 0, 0), refusal_seen(ev, "minimum", "at least"),
                                  answer_reports_refusal(ev)),
               [_formation(three, "line", 8, 10), _formation(three, "line", 1, 10)],
               "Rækken står i 8 m; at sænke den til 1 m blev afvist: under minimumshøjden på 2 m."),
        # units
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("units", "dev", "units17-alpha-kmh-for-seconds", ("alpha",),
               "Alpha: up to 10 m, then head north at 18 km/h for 8 seconds and land wherever that leaves it.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 40, 0)], alt=10),
                                  at(ev, "alpha", *c.point("alpha", 40, 0)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", 40, 0), _land("alpha")],
               "Alpha flew 40 m north (18 km/h is 5 m/s, for 8 s) and landed there."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("units", "dev", "units17-bg-charlie-yards-and-feet", ("charlie",),
               "Издигни charlie на височина 12 ярда и 1 фут, после го премести с 33 ярда и 1 фут на запад и го "
               "остави да виси там.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, -100 * FT), alt=37 * FT),
                                  airborne_at(ev, "charlie", 37 * FT)),
               [_takeoff("charlie", 37 * FT), _move("charlie", 0, -100 * FT)],
               "charlie виси на 37 фута (11,3 м) височина, 100 фута (30,5 м) западно от старта си."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("units", "dev", "units17-et-bravo-feet-north-metres-east", ("bravo",),
               "Tõsta bravo 40 jala kõrgusele ja vii see ühe liigutusega 60 jalga põhja ja 15 meetrit itta; jäta "
               "see sinna õhku hõljuma.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 60 * FT, 15), alt=40 * FT),
                                  airborne_at(ev, "bravo", 40 * FT)),
               [_takeoff("bravo", 40 * FT), _move("bravo", 60 * FT, 15)],
               "bravo hõljub 60 jalga (18,3 m) põhja ja 15 m ida pool, 40 jala (12,2 m) kõrgusel."),
        # pattern
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("pattern", "dev", "pattern17-alpha-two-rings", ("alpha",),
               "Alpha at 10 m: one lap round its pad at a 10 m radius, then one at a 20 m radius, both clockwise "
               "starting from the north side; then bring it back over the pad and land it.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in (*inner, *outer)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               # (the plan flies each lap as four legs between those points: a plan naming a point every 45
               # degrees was too long to pass as a plan)
               [_takeoff("alpha", 10), *_legs("alpha", rings), _rtl("alpha")],
               "Alpha flew a lap at 10 m from its pad, then one at 20 m, and landed on the pad."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("pattern", "dev", "pattern17-sw-charlie-upright-square", ("charlie",),
               "Ipaishe charlie hadi mita 10, kisha iruke mraba uliosimama wima wenye pande za mita 10: ipande hadi "
               "mita 20, isogee mita 10 kuelekea mashariki, ishuke tena hadi mita 10, kisha irudi mita 10 kuelekea "
               "magharibi. Mwishoni iache ielee hapo.",
               lambda c, ev: _all(passed(ev, "charlie", [(_home(c, "charlie"), 20), (c.point("charlie", 0, 10), 20),
                                                         (c.point("charlie", 0, 10), 10)]),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=10), airborne_at(ev, "charlie", 10)),
               [_takeoff("charlie", 10), _move("charlie", up=10), _move("charlie", 0, 10), _move("charlie", up=-10),
                _move("charlie", 0, -10)],
               "charlie iliruka mraba wima na sasa inaelea mita 10 juu ya mahali ilipoanzia."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("pattern", "dev", "pattern17-is-bravo-square-and-back", ("bravo",),
               "Láttu bravo fljúga ferning í 12 metra hæð með 20 metra hliðum: fyrstu hliðina í norður og beygja "
               "til hægri. Þegar hann er kominn aftur að upphafsstaðnum á hann að fljúga sama ferninginn í hina "
               "áttina og lenda svo þar sem hann byrjaði.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e)
                                                        for n, e in ((20, 0), (20, 20), (0, 20), (20, 20), (20, 0))]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), *_legs("bravo", square), *_legs("bravo", reverse), _land("bravo")],
               "bravo flaug ferninginn réttsælis og svo rangsælis og lenti þar sem hann byrjaði."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # charlie from alpha, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("placement", "dev", "place17-charlie-on-alpha-line-twice-out", three,
               "Alpha goes 15 m north-east at 12 m and stops there. Put charlie on the same line out from alpha's "
               "pad, twice as far out, at the same height.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", d15, d15), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", 2 * d15, 2 * d15), alt=12),
                                  airborne_at(ev, "charlie", 12), never_armed(ev, "bravo")),
               lambda c: [_move("alpha", d15, d15, alt=12), _go("charlie", c.point("alpha", 2 * d15, 2 * d15), 12)],
               "Alpha hovers 15 m north-east of its pad at 12 m; charlie 30 m north-east of alpha's pad, at 12 m."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("placement", "dev", "place17-ta-charlie-stays-as-alpha-moves", three,
               "alpha-வை 12 மீட்டர் உயரத்துக்கு ஏற்றி, charlie-ஐ alpha-வுக்கு மேற்கே 15 மீட்டர் தொலைவில், அதே "
               "உயரத்தில் நிறுத்து. பிறகு alpha-வை மட்டும் வடக்கே 20 மீட்டர் நகர்த்து; charlie இருக்கும் இடத்திலேயே "
               "இருக்கட்டும்.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", 0, -15), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 12), _go("charlie", c.point("alpha", 0, -15), 12), _move("alpha", 20, 0)],
               "alpha வடக்கே 20 m தூரத்தில் 12 m உயரத்தில் உள்ளது; charlie, alpha-வின் தளத்துக்கு மேற்கே 15 m "
               "தொலைவில் அதே உயரத்தில் நிற்கிறது."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("placement", "dev", "place17-tl-charlie-relieves-alpha", three,
               "Paliparin mo si alpha nang 25 metro patimog sa taas na 10 metro, at doon mo muna siya palutangin. "
               "Pagkatapos, ipalit mo si charlie sa puwesto niya (parehong lugar, parehong taas) at pauwiin mo si "
               "alpha para lumapag sa pinanggalingan nito.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -25, 0)], alt=10),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha"),
                                  at(ev, "charlie", *c.point("alpha", -25, 0), alt=10), airborne_at(ev, "charlie", 10),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("alpha", -25, 0, alt=10), _go("charlie", c.point("alpha", -25, 0), 10), _rtl("alpha")],
               "Nasa puwesto na ni alpha si charlie, 25 m patimog sa taas na 10 m; nakauwi at nakalapag na si alpha."),
        # language
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("language", "dev", "lang17-te-bravo-northwest-land", ("bravo",),
               "bravo ని 15 మీటర్ల ఎత్తుకు ఎగరేసి, వాయువ్య దిశగా 20 మీటర్లు తీసుకెళ్ళి, అక్కడే దింపు.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 15), at(ev, "bravo", *c.point("bravo", d20, -d20)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 15), _move("bravo", d20, -d20), _land("bravo")],
               "bravo వాయువ్యంగా 20 m వెళ్ళి అక్కడ దిగింది."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("language", "dev", "lang17-kn-alpha-south-climb-hover", ("alpha",),
               "alpha ಅನ್ನು 12 ಮೀಟರ್ ಎತ್ತರಕ್ಕೆ ಏರಿಸಿ, ದಕ್ಷಿಣಕ್ಕೆ 30 ಮೀಟರ್ ಹಾರಿಸಿ, ಅಲ್ಲಿ ಇನ್ನೂ 6 ಮೀಟರ್ ಮೇಲಕ್ಕೆ ಏರಿಸಿ "
               "ಗಾಳಿಯಲ್ಲೇ ನಿಲ್ಲಿಸಿ.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -30, 0)], alt=12),
                                  at(ev, "alpha", *c.point("alpha", -30, 0), alt=18), airborne_at(ev, "alpha", 18)),
               [_takeoff("alpha", 12), _move("alpha", -30, 0), _move("alpha", up=6)],
               "alpha ದಕ್ಷಿಣಕ್ಕೆ 30 m ದೂರದಲ್ಲಿ 18 m ಎತ್ತರದಲ್ಲಿ ಗಾಳಿಯಲ್ಲಿ ನಿಂತಿದೆ."),
        # moved to dev on 2026-12-04, seventeenth round: its failures had informed changes to the host
        _entry("language", "dev", "lang17-mn-charlie-east-home", ("charlie",),
               "charlie-г 10 метрийн өндөрт хөөргөөд, зүүн зүг рүү 25 метр нисгэ. Дараа нь хөөрсөн газар руу нь "
               "буцааж авчраад буулга.",
               # the return home climbs to its own height: the leg east is checked at 10 m instead
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 25)], alt=10),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", 0, 25), _rtl("charlie")],
               "charlie зүүн зүг рүү 25 м нисээд, хөөрсөн газартаа буцаж ирж буулаа."),
    ]  # fmt: skip


def _eighteenth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-04 (eighteenth round), before any model ran on it, by a writer who
    did not read the host's word lists or rules: 3 a class; 22 of the 33 outside ``language`` in other
    languages than English, one each (Arabic, Chinese, Czech, Dutch, French, German, Hebrew, Hindi,
    Indonesian, Italian, Japanese, Korean, Persian, Polish, Portuguese, Romanian, Russian, Spanish, Swedish,
    Turkish, Ukrainian, Vietnamese), the ``language`` class's 3 in Amharic, Sinhala and Tajik (all three new
    to the corpus, and Ethiopic and Sinhala script with them); all of it moved to dev on 2026-12-04
    (eighteenth round), once both models had been measured on it (docs/benchmarks.md)."""
    three = DRONES
    d10, d20 = (x / math.sqrt(2) for x in (10, 20))
    knot = 1852 / 3600  # m/s
    # a bow tie centred on the pad: the east triangle, then the west one, each back through the pad
    bow_tie = [(10.0, 20.0), (-20.0, 0.0), (10.0, -20.0), (-10.0, -20.0), (20.0, 0.0), (-10.0, 20.0)]
    # nine 10 m sides, the first due east, a 40 degree turn to the right at the end of each
    nonagon = _polygon_legs(9, 10.0, 90.0, right=True)
    # a rectangle of 600 m2 whose north and south sides are 30 m: 20 m north, 30 m east, back round
    rectangle = [(20.0, 0.0), (0.0, 30.0), (-20.0, 0.0), (0.0, -30.0)]
    # 30 m toward the two o'clock of a drone facing north: 60 degrees east of north
    two_oclock = (30 * math.cos(math.radians(60)), 30 * math.sin(math.radians(60)))

    def touched_down(ev: Evidence, d: str, point: tuple[float, float]) -> Check:
        """The drone was on the ground at ``point`` at some time (a landing out there, not only at the end)."""
        ok = any(s.landed and horizontal_distance_m(s.lat, s.lon, *point) <= HORIZONTAL_TOL_M
                 for s in ev.track.get(d, []))  # fmt: skip
        return Check(ok, f"{d} {'touched down' if ok else 'never touched down'} there")

    def aloft_while(ev: Evidence, d: str, other: str, point: tuple[float, float], alt: float) -> Check:
        """Whenever ``other`` was over ``point``, ``d`` was up at ``alt`` (the tracks are sampled together)."""
        at_point = [i for i, s in enumerate(ev.track.get(other, []))
                    if horizontal_distance_m(s.lat, s.lon, *point) <= HORIZONTAL_TOL_M]  # fmt: skip
        mine = ev.track.get(d, [])
        ok = bool(at_point) and all(
            i < len(mine) and abs(mine[i].alt_rel_m - alt) <= ALT_TOL_M for i in at_point
        )
        return Check(ok, f"{d} {'was' if ok else 'was not'} at {alt:g} m while {other} was out there")

    def ring_held(
        c: MissionContext, ev: Evidence, drones: tuple[str, ...], alt: float, spacing: float
    ) -> Check:
        """At some moment of the flight, every drone at ``alt``, every two of them ``spacing`` apart (±3 m: a
        ring of three) and their centre over the centre of their homes: a ring held before it changed."""
        home_lat = sum(c.homes[d][0] for d in drones) / len(drones)
        home_lon = sum(c.homes[d][1] for d in drones) / len(drones)
        samples = min(len(ev.track.get(d, [])) for d in drones)
        for i in range(samples):
            now = [ev.track[d][i] for d in drones]
            if any(abs(s.alt_rel_m - alt) > ALT_TOL_M for s in now):
                continue
            gaps = [
                horizontal_distance_m(p.lat, p.lon, q.lat, q.lon)
                for j, p in enumerate(now)
                for q in now[j + 1 :]
            ]
            off = horizontal_distance_m(*_centroid(now), home_lat, home_lon)
            if all(abs(g - spacing) <= 3.0 for g in gaps) and off <= HORIZONTAL_TOL_M:
                return Check(True, f"the ring {spacing:g} m apart was held (sample {i})")
        return Check(False, f"no ring {spacing:g} m apart was held")

    def beyond(c: MissionContext, middle: tuple[float, float], d: str) -> tuple[float, float]:
        """The point with ``middle`` halfway between it and ``d``'s home."""
        lat, lon = _home(c, d)
        return 2 * middle[0] - lat, 2 * middle[1] - lon

    return [
        # single
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("single", "dev", "single18-alpha-between-trees-and-line", ("alpha",),
               "The trees along the fence top out at 8 m and the power line overhead runs at 20 m. Put alpha up "
               "halfway between the two, right above its pad, and leave it hovering there.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=14), airborne_at(ev, "alpha", 14)),
               [_takeoff("alpha", 14)], "Alpha hovers at 14 m over its pad, halfway between the treetops and the line."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("single", "dev", "single18-tr-bravo-height-corrected", ("bravo",),
               "bravo'yu 25 metreye çıkar... Dur, yanlış söyledim, 15 metre yeterli. Kalktığı yerin tam üstünde "
               "havada beklesin.",
               # the corrected height, and never the first one
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=15), airborne_at(ev, "bravo", 15),
                                  max_alt_at_most(ev, "bravo", 20)),
               [_takeoff("bravo", 15)], "bravo kalktığı yerin üstünde 15 m'de bekliyor; 25 m'ye hiç çıkmadı."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("single", "dev", "single18-he-charlie-halfway-down", ("charlie",),
               "תעלה את charlie לגובה 24 מטר, ואז תוריד אותו לחצי מהגובה הזה ותשאיר אותו לרחף שם, מעל נקודת "
               "ההמראה שלו.",
               lambda c, ev: _all(rose_to(ev, "charlie", 24), at(ev, "charlie", *_home(c, "charlie"), alt=12),
                                  airborne_at(ev, "charlie", 12)),
               [_takeoff("charlie", 24), _move("charlie", alt=12)],
               "charlie עלה ל-24 מ' וירד לחצי הגובה: הוא מרחף עכשיו ב-12 מ' מעל נקודת ההמראה."),
        # multi
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("multi", "dev", "multi18-alpha-bravo-leapfrog-north", three,
               "Leapfrog alpha and bravo northward at 10 m. Alpha goes 15 m north first; then bravo flies on to "
               "15 m past alpha; then alpha flies on to 15 m past bravo. Leave both hovering there; charlie stays "
               "on the ground.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 15, 0)], alt=10),
                                  # (where alpha ends is judged on its final state: the track may stop before it gets there)
                                  at(ev, "alpha", *c.point("alpha", 45, 0), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "bravo", *c.point("bravo", 30, 0), alt=10), airborne_at(ev, "bravo", 10),
                                  never_armed(ev, "charlie")),
               [_move("alpha", 15, 0, alt=10), _move("bravo", 30, 0, alt=10), _move("alpha", 30, 0)],
               "Alpha hovers 45 m north of its pad and bravo 30 m north of its own, both at 10 m; charlie stayed "
               "down."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("multi", "dev", "multi18-it-south-by-own-height", three,
               "Porta alpha a 10 metri, bravo a 15 e charlie a 20, ciascuno sopra la propria piazzola; poi spostali "
               "tutti verso sud di tanti metri quanti ne indica la loro quota, e lasciali lì in volo.",
               lambda c, ev: _all(*(_all(at(ev, d, *c.point(d, -h, 0), alt=h), airborne_at(ev, d, h))
                                    for d, h in (("alpha", 10), ("bravo", 15), ("charlie", 20)))),
               [_takeoff("alpha", 10), _takeoff("bravo", 15), _takeoff("charlie", 20), _move("alpha", -10, 0),
                _move("bravo", -15, 0), _move("charlie", -20, 0)],
               "alpha è 10 m a sud della sua piazzola a 10 m di quota, bravo 15 m a sud a 15 m, charlie 20 m a sud "
               "a 20 m."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("multi", "dev", "multi18-ja-charlie-watches-alpha-run", three,
               "charlieを20メートルまで上げて見張りをさせて。その間にalphaを高さ10メートルで東へ30メートル飛ばして、"
               "離陸した場所まで戻して着陸させて。alphaが降りたらcharlieも着陸させて。bravoは地上のままで。",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 30)], alt=10),
                                  aloft_while(ev, "charlie", "alpha", c.point("alpha", 0, 30), 20),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha"),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie"),
                                  never_armed(ev, "bravo")),
               [_takeoff("charlie", 20), _move("alpha", 0, 30, alt=10), _move("alpha", 0, -30), _land("alpha"),
                _land("charlie")],
               "alphaは東へ30 m飛んで戻って着陸し、その間charlieは20 mで見張ってから着陸した。bravoは地上のまま。"),
        # compound
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("compound", "dev", "compound18-charlie-detour-round-hangar", ("charlie",),
               "Charlie has to end up 50 m north of its pad, but there's a hangar in the way. At 10 m: 15 m north, "
               "10 m east to get round it, 20 m north past it, 10 m west back onto the line, then the last 15 m "
               "north, and land it there.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in ((15, 0), (15, 10), (35, 10), (35, 0))],
                                          alt=10),
                                  at(ev, "charlie", *c.point("charlie", 50, 0)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), *_legs("charlie", [(15, 0), (0, 10), (20, 0), (0, -10), (15, 0)]),
                _land("charlie")],
               "Charlie went round the hangar and landed 50 m north of its pad."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("compound", "dev", "compound18-de-bravo-out-low-back-high", ("bravo",),
               "Flieg bravo in 10 m Höhe 30 m nach Westen. Für den Rückweg soll er dort auf 20 m steigen, dann in "
               "dieser Höhe zurück über seinen Startplatz fliegen und da landen.",
               lambda c, ev: _all(passed(ev, "bravo", [(c.point("bravo", 0, -30), 10), (c.point("bravo", 0, -30), 20),
                                                       (_home(c, "bravo"), 20)]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), _move("bravo", 0, -30), _move("bravo", alt=20), _move("bravo", 0, 30),
                _land("bravo")],
               "bravo flog in 10 m 30 m nach Westen, stieg dort auf 20 m, kam in 20 m zurück und landete auf dem "
               "Startplatz."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("compound", "dev", "compound18-ko-alpha-lands-out-back-higher", ("alpha",),
               "alpha를 8미터 높이로 동쪽 25미터 지점까지 보내서 거기에 착륙시켜 줘. 그다음 다시 이륙시켜서 이번엔 "
               "15미터 높이로 원래 자리 위까지 돌아오게 하고, 착륙하지 말고 그 위에 떠 있게 해 줘.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 25)], alt=8),
                                  touched_down(ev, "alpha", c.point("alpha", 0, 25)),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=15), airborne_at(ev, "alpha", 15)),
               [_takeoff("alpha", 8), _move("alpha", 0, 25), _land("alpha"), _takeoff("alpha", 15),
                _move("alpha", 0, -25)],
               "alpha는 동쪽 25 m 지점에 착륙했다가 다시 떠서, 지금은 원래 자리 위 15 m에 떠 있어."),
        # conditional
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("conditional", "dev", "cond18-first-in-order-with-enough", three,
               "The job takes 25 % of a battery, and whoever does it has to keep 30 % in reserve. Go through alpha, "
               "bravo and charlie in that order and send the first one that has enough 20 m north at 12 m, to hover "
               "there. The others stay down.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 20, 0), alt=12), airborne_at(ev, "bravo", 12),
                                  never_armed(ev, "alpha"), never_armed(ev, "charlie")),
               [("fleet_status", {}), _move("bravo", 20, 0, alt=12)],
               "Alpha has 48 %, short of the 55 % the job needs; bravo (61 %) flew 20 m north and hovers at 12 m; "
               "charlie stayed down.",
               battery={"alpha": 48.0, "bravo": 61.0, "charlie": 90.0}),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("conditional", "dev", "cond18-fr-fullest-kept-in-reserve", three,
               "Garde en réserve au sol le drone qui a le plus de batterie ; les deux autres montent à 10 m et "
               "partent 15 m vers l'est, où ils restent en vol stationnaire.",
               lambda c, ev: _all(*(_all(at(ev, d, *c.point(d, 0, 15), alt=10), airborne_at(ev, d, 10))
                                    for d in ("bravo", "charlie")),
                                  never_armed(ev, "alpha")),
               [("fleet_status", {}), _move("bravo", 0, 15, alt=10), _move("charlie", 0, 15, alt=10)],
               "alpha (88 %) reste en réserve au sol ; bravo (64 %) et charlie (71 %) sont en vol stationnaire à "
               "10 m, 15 m à l'est.",
               battery={"alpha": 88.0, "bravo": 64.0, "charlie": 71.0}),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("conditional", "dev", "cond18-ar-fuller-then-distance-by-level", three,
               "انظر أيّ الطائرتين، alpha أم charlie، بطاريتها أعلى. إذا كانت نسبتها فوق 80 %، فأرسلها 40 مترًا "
               "غربًا على ارتفاع 12 مترًا، وإلا فأرسلها 20 مترًا فقط في الاتجاه نفسه وعلى الارتفاع نفسه، ودعها تحوم "
               "هناك. أمّا bravo فتبقى على الأرض.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, -20), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               [("fleet_status", {}), _move("charlie", 0, -20, alt=12)],
               "بطارية charlie أعلى (74 %) لكنها دون 80 %، فطارت 20 مترًا غربًا وتحوم على ارتفاع 12 مترًا؛ أمّا "
               "alpha (66 %) وbravo فبقيتا على الأرض.",
               battery={"alpha": 66.0, "charlie": 74.0}),
        # formation
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("formation", "dev", "form18-ring-drawn-in", three,
               "Put the three on a ring over the middle of their pads at 15 m, 20 m from each other. Then draw the "
               "ring in until they're 10 m apart, same spot, same height, and hold them there.",
               lambda c, ev: _all(ring_held(c, ev, three, 15, 20), formation_at(c, ev, three, 15, 10, 0, 0),
                                  farthest_apart(ev, three, 10)),
               [_formation(three, "circle", 15, 20), _formation(three, "circle", 15, 10)],
               "The three held a ring 20 m apart at 15 m, then closed it to 10 m apart over the same spot."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("formation", "dev", "form18-zh-pair-over-charlie-pad", three,
               "让alpha和bravo在charlie起飞点的正上方东西并排悬停，两机相距8米，高度20米。charlie留在地面不动。",
               lambda c, ev: _all(formation_around(ev, ("alpha", "bravo"), 20, 8, _home(c, "charlie")),
                                  row_along(ev, ("alpha", "bravo"), 90), never_armed(ev, "charlie")),
               lambda c: [_go("alpha", c.point("charlie", 0, -4), 20), _go("bravo", c.point("charlie", 0, 4), 20)],
               "alpha和bravo在charlie起飞点正上方20米高处东西并排悬停，相距8米；charlie留在地面。"),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("formation", "dev", "form18-pt-row-by-total-length", three,
               "Ponha os três drones numa fila de leste a oeste com 30 metros de ponta a ponta, igualmente "
               "espaçados, a 12 metros de altura e centrada sobre o lugar onde eles estão agora. Deixe-os pairando.",
               lambda c, ev: _all(formation_at(c, ev, three, 12, 15, 0, 0), farthest_apart(ev, three, 30),
                                  row_along(ev, three, 90)),
               [_formation(three, "line", 12, 15)],
               "Os três pairam a 12 m numa fila leste–oeste de 30 m de ponta a ponta, com 15 m entre vizinhos."),
        # relative
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("relative", "dev", "rel18-bravo-two-oclock", ("bravo",),
               "Bravo's nose is pointing north. Take it up to 10 m and move it 30 m toward its two o'clock, then "
               "hold it there.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", *two_oclock), alt=10), airborne_at(ev, "bravo", 10)),
               [_takeoff("bravo", 10), _move("bravo", *two_oclock)],
               "Bravo holds 15 m north and 26 m east of its pad (its two o'clock), at 10 m."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("relative", "dev", "rel18-hi-alpha-right-turn-from-northeast", ("alpha",),
               "alpha को 12 मीटर ऊपर ले जाओ और उत्तर-पूर्व की ओर 20 मीटर उड़ाओ। फिर वहाँ से अपनी उड़ान की दिशा से "
               "दाईं ओर मुड़कर 10 मीटर और ले जाओ, और उसे वहीं हवा में रोक दो।",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", d20, d20)], alt=12),
                                  at(ev, "alpha", *c.point("alpha", d20 - d10, d20 + d10), alt=12),
                                  airborne_at(ev, "alpha", 12)),
               [_takeoff("alpha", 12), _move("alpha", d20, d20), _move("alpha", -d10, d10)],
               "alpha उत्तर-पूर्व में 20 m गया, फिर दाएँ मुड़कर दक्षिण-पूर्व की ओर 10 m, और अब 12 m की ऊँचाई पर "
               "रुका है।"),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("relative", "dev", "rel18-fa-charlie-on-by-the-descent", ("charlie",),
               "charlie را تا ارتفاع 20 متر بالا ببر و 20 متر به سمت شمال ببرش. آنجا پایینش بیاور تا به ارتفاع 8 "
               "متر برسد، و بعد به همان اندازه‌ای که پایین آمد باز هم به سمت شمال جلو ببرش و همان‌جا نگهش دار.",
               lambda c, ev: _all(passed(ev, "charlie", [(c.point("charlie", 20, 0), 20), (c.point("charlie", 20, 0), 8)]),
                                  at(ev, "charlie", *c.point("charlie", 32, 0), alt=8), airborne_at(ev, "charlie", 8)),
               [_takeoff("charlie", 20), _move("charlie", 20, 0), _move("charlie", alt=8), _move("charlie", 12, 0)],
               "charlie در 32 متری شمال نقطهٔ پروازش، در ارتفاع 8 متر معلق است."),
        # question
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("question", "dev", "ask18-more-left-after-jobs", three,
               "If alpha flew a job that uses 25 % of its battery and bravo one that uses 40 %, which of the two "
               "would have more left afterwards, and how much? Don't fly anything.",
               # the typed plan reads, it does not compute: what is left, or the reading it comes from
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"),
                                  _any(answer_mentions_number(ev, 40, 0.5), answer_mentions_number(ev, 80, 1)),
                                  nobody_armed(ev)),
               [_battery("alpha"), _battery("bravo")],
               "Bravo: it has 80 % and would keep 40 %; alpha has 55 % and would keep 30 %.",
               battery={"alpha": 55.0, "bravo": 80.0, "charlie": 70.0}),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("question", "dev", "ask18-sv-charge-in-band", three,
               "Vilka drönare har minst 50 % men under 80 % batteri? Ge mig siffrorna, men låt allt stå kvar på "
               "marken.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 72, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Bara bravo, med 72 % (alpha har 45 % och charlie 85 %).",
               battery={"alpha": 45.0, "bravo": 72.0, "charlie": 85.0}),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("question", "dev", "ask18-id-alpha-against-other-two", three,
               "Apakah baterai alpha lebih banyak daripada baterai bravo dan charlie kalau dijumlahkan? Sebutkan "
               "angka-angkanya, tapi jangan terbangkan apa pun.",
               lambda c, ev: _all(answer_mentions_number(ev, 85, 1),
                                  _any(answer_mentions_number(ev, 71, 1),
                                       _all(answer_mentions_number(ev, 30, 1), answer_mentions_number(ev, 41, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Ya: alpha 85 %, sedangkan bravo 30 % dan charlie 41 %, jumlahnya 71 %.",
               battery={"alpha": 85.0, "bravo": 30.0, "charlie": 41.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude)
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("refusal", "dev", "refuse18-alpha-ten-percent-over-ceiling", ("alpha",),
               "Our ceiling is 120 m, but the survey wants alpha 10 % above it. Put it there, straight over its pad.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "alpha", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("alpha", 132)],
               "Refused: 10 % above the 120 m ceiling is 132 m, over the altitude limit."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("refusal", "dev", "refuse18-pl-charlie-into-the-pit", ("charlie",),
               "Charlie stoi na skraju wyrobiska, którego dno jest 8 m niżej niż jego lądowisko. Przeleć nim na "
               "wysokości 10 m 15 m na wschód, nad wyrobisko, a potem opuść go na 3 m nad dnem.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 15), alt=10), airborne_at(ev, "charlie", 10),
                                  refusal_seen(ev, "minimum", "at least", "below home"), answer_reports_refusal(ev)),
               # (a height below the pad is refused as "below home", not by the 2 m minimum; the plan goes down
               # 15 m from 10 m: as an altitude of -5 m the host sent 5 m, flown without a refusal)
               [_move("charlie", 0, 15, alt=10), _move("charlie", up=-15)],
               "charlie wisi 15 m na wschód na 10 m; zejścia na 3 m nad dnem (5 m poniżej lądowiska) odmówiono: to "
               "poniżej minimum 2 m wysokości."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("refusal", "dev", "refuse18-ro-bravo-speed-for-time-too-far", ("bravo",),
               "Ridică bravo la 20 de metri și trimite-l spre nord cu 12 m/s timp de un minut și jumătate.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "bravo", c.max_distance_m), answer_reports_refusal(ev)),
               [_takeoff("bravo", 20), _move("bravo", 1080, 0)],
               "bravo e la 20 m; zborul de 1080 m spre nord (12 m/s timp de 90 s) a fost refuzat: depășește limita "
               "de 1000 m de la punctul de decolare."),
        # units
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("units", "dev", "units18-alpha-knots-for-seconds", ("alpha",),
               "Alpha: climb to 40 ft, then fly north at 20 knots for 4 seconds and hold it wherever that leaves it.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 80 * knot, 0), alt=40 * FT),
                                  airborne_at(ev, "alpha", 40 * FT)),
               [_takeoff("alpha", 40 * FT), _move("alpha", 80 * knot, 0)],
               "Alpha holds 41 m north of its pad (20 kn for 4 s) at 40 ft (12.2 m)."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("units", "dev", "units18-nl-charlie-feet-over-mast", ("charlie",),
               "De zendmast naast het platform van charlie is 9 meter hoog. Laat charlie recht omhoog gaan tot 20 "
               "voet boven de top van die mast en laat hem daar hangen.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=9 + 20 * FT),
                                  airborne_at(ev, "charlie", 9 + 20 * FT)),
               [_takeoff("charlie", 9 + 20 * FT)],
               "charlie hangt op 15,1 m boven zijn platform: 20 voet (6,1 m) boven de top van de mast."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("units", "dev", "units18-es-bravo-feet-above-sea-level", ("bravo",),
               "La pista está a 1.600 pies sobre el nivel del mar. Sube a bravo hasta los 1.650 pies sobre el nivel "
               "del mar, justo encima de su base, y mantenlo ahí.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=50 * FT), airborne_at(ev, "bravo", 50 * FT)),
               [_takeoff("bravo", 50 * FT)],
               "bravo se mantiene a 50 pies (15,2 m) sobre su base, a 1.650 pies sobre el nivel del mar."),
        # pattern
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("pattern", "dev", "pattern18-bravo-bow-tie", ("bravo",),
               "Bravo at 10 m: fly a bow tie centred on its pad. From the pad out to the point 10 m north and 20 m "
               "east, then 20 m due south, then straight back to the pad; then out to 10 m south and 20 m west, "
               "20 m due north, and back to the pad again. Land it there.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(bow_tie)[:5]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), *_legs("bravo", bow_tie), _land("bravo")],
               "Bravo flew the bow tie, both triangles through its pad, and landed on the pad."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("pattern", "dev", "pattern18-ru-alpha-turns-of-forty", ("alpha",),
               "Подними alpha на 12 м и проведи его по фигуре со сторонами по 10 м: первая сторона на восток, в "
               "конце каждой стороны поворот направо на 40°, и так пока он не вернётся в точку, откуда начал. Там "
               "его и посади.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(nonagon)[:8]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), *_legs("alpha", nonagon), _land("alpha")],
               "alpha облетел девятиугольник со сторонами по 10 м и сел там, откуда начал."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("pattern", "dev", "pattern18-cs-charlie-rectangle-by-area", ("charlie",),
               "Ať charlie ve výšce 10 metrů obletí obdélník o ploše 600 m², jehož severní a jižní strana měří 30 "
               "metrů. Jeho stanoviště je jihozápadní roh: ať letí nejdřív na sever a nakonec přistane tam, kde "
               "začal.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(rectangle)[:3]]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), *_legs("charlie", rectangle), _land("charlie")],
               "charlie obletěl obdélník 20 × 30 m (600 m²) a přistál tam, kde začal."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # charlie from alpha, 10 m apart, so that a drone placed from itself misses)
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("placement", "dev", "place18-charlie-alpha-in-the-middle", three,
               "Bravo goes up to 12 m over its pad and alpha flies 15 m north at 12 m. Then put charlie at 12 m on "
               "the far side of alpha from bravo, so that alpha sits exactly halfway between bravo and charlie.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=12), airborne_at(ev, "bravo", 12),
                                  at(ev, "alpha", *c.point("alpha", 15, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *beyond(c, c.point("alpha", 15, 0), "bravo"), alt=12),
                                  airborne_at(ev, "charlie", 12)),
               lambda c: [_takeoff("bravo", 12), _move("alpha", 15, 0, alt=12),
                          _go("charlie", beyond(c, c.point("alpha", 15, 0), "bravo"), 12)],
               "Bravo hovers over its pad and alpha 15 m north of its own, both at 12 m; charlie is on the far side "
               "of alpha, as far from it as bravo, at 12 m."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("placement", "dev", "place18-uk-charlie-right-of-alpha-heading", three,
               "Підніми alpha на 12 метрів і відправ його на 20 метрів на схід. Коли він зупиниться, постав charlie "
               "за 10 метрів праворуч від нього, якщо дивитися туди, куди летів alpha, на тій самій висоті.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 20), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", -10, 20), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 12), _move("alpha", 0, 20), _go("charlie", c.point("alpha", -10, 20), 12)],
               "alpha висить за 20 м на схід на 12 м; charlie за 10 м праворуч від нього (на південь), на тій самій "
               "висоті."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("placement", "dev", "place18-vi-charlie-over-alpha-mid-height", three,
               "Cho bravo bay lên 18 mét ngay trên bệ của nó, và cho alpha bay 20 mét về phía nam ở độ cao 8 mét. "
               "Sau đó đưa charlie đến ngay phía trên alpha, ở độ cao nằm giữa độ cao của alpha và bravo.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=18), airborne_at(ev, "bravo", 18),
                                  at(ev, "alpha", *c.point("alpha", -20, 0), alt=8), airborne_at(ev, "alpha", 8),
                                  at(ev, "charlie", *c.point("alpha", -20, 0), alt=13), airborne_at(ev, "charlie", 13)),
               lambda c: [_takeoff("bravo", 18), _move("alpha", -20, 0, alt=8), _go("charlie", c.point("alpha", -20, 0), 13)],
               "bravo bay ở 18 m trên bệ; alpha ở 20 m về phía nam, cao 8 m; charlie ngay phía trên alpha, ở 13 m."),
        # language
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("language", "dev", "lang18-am-alpha-north-lower-hover", ("alpha",),
               "alpha ን 15 ሜትር ከፍ አድርገህ ወደ ሰሜን 30 ሜትር አብርረው። እዚያ ስትደርስ 5 ሜትር ዝቅ አድርገህ በአየር ላይ አቆየው።",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 30, 0)], alt=15),
                                  at(ev, "alpha", *c.point("alpha", 30, 0), alt=10), airborne_at(ev, "alpha", 10)),
               [_takeoff("alpha", 15), _move("alpha", 30, 0), _move("alpha", up=-5)],
               "alpha ወደ ሰሜን 30 ሜትር በርሮ አሁን በ10 ሜትር ከፍታ ላይ በአየር ላይ ነው።"),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("language", "dev", "lang18-si-bravo-west-land", ("bravo",),
               "bravo මීටර් 12ක් උසට ඔසවා, බටහිර දෙසට මීටර් 25ක් පියාසර කරවා, එතැනම බිමට බස්සන්න.",
               lambda c, ev: _all(reached_alt(ev, "bravo", 12), at(ev, "bravo", *c.point("bravo", 0, -25)),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", 0, -25), _land("bravo")],
               "bravo බටහිරට මීටර් 25ක් ගොස් එතැන බිමට බැස්සා."),
        # moved to dev on 2026-12-04, eighteenth round: measured on both models, its failures seen
        _entry("language", "dev", "lang18-tg-charlie-southeast-home", ("charlie",),
               "charlie-ро то баландии 10 метр бардоред, онро 20 метр ба самти ҷанубу шарқ баред, баъд ба ҷое, ки аз "
               "он парвоз карда буд, баргардонед ва фуроваред.",
               # the return home climbs to its own height: the leg south-east is checked at 10 m instead
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -d20, d20)], alt=10),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", -d20, d20), _rtl("charlie")],
               "charlie 20 м ба ҷанубу шарқ парид, баргашт ва дар ҷои худ фуруд омад."),
    ]  # fmt: skip


def _nineteenth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-04 (nineteenth round), before any model ran on it, by a writer who
    did not read the host's word lists or rules: 3 a class; 22 of the 33 outside ``language`` in other
    languages than English, one each (Afrikaans, Bengali, Bulgarian, Catalan, Cebuano, Danish, Estonian,
    Finnish, Greek, Hungarian, Javanese, Kyrgyz, Lithuanian, Malay, Norwegian, Serbian, Slovak, Slovenian,
    Swahili, Tagalog, Thai, Urdu; Cebuano, Javanese and Kyrgyz are new), the ``language`` class's 3 in Khmer,
    Lao and Zulu (all three new to the corpus, and Khmer and Lao script with them); all of it moved to dev on
    2026-12-05 (nineteenth round), once both models had been measured on it (docs/benchmarks.md)."""
    three = DRONES
    d15, d20, d25 = (x / math.sqrt(2) for x in (15, 20, 25))
    chain = 22 * YD
    # a sawtooth eastward: 10 m stretches, up to 16 m over one and back down to 10 m over the next, three times
    teeth = [(10.0 * k, 16.0 if k % 2 else 10.0) for k in range(1, 7)]
    # the rectangle whose opposite corners are the pad and the point 30 m north and 40 m east, north first
    rectangle = [(30.0, 0.0), (0.0, 40.0), (-30.0, 0.0), (0.0, -40.0)]
    # a regular hexagon 60 m round (10 m sides), the first side due east, turning right
    hexagon = _polygon_legs(6, 10.0, 90.0, right=True)
    # a V pointing north, 10 m arms at 45 degrees, centred over the centre of the pads: its tip, then the left
    # and the right wing (north, east from that centre)
    arm = 10 / math.sqrt(2)
    tip, left_wing, right_wing = (2 * arm / 3, 0.0), (-arm / 3, -arm), (-arm / 3, arm)

    def rises(ev: Evidence, d: str, alt: float) -> list[int]:
        """The samples at which the drone, coming from the ground, reached ``alt`` (less the tolerance)."""
        out, down = [], True
        for i, s in enumerate(ev.track.get(d, [])):
            if down and s.alt_rel_m >= alt - ALT_TOL_M:
                out.append(i)
                down = False
            elif s.landed:
                down = True
        return out

    def hops_in_turn(ev: Evidence, turns: list[str], alt: float) -> Check:
        """The drones rose from the ground to ``alt`` once each in the order of ``turns`` (a drone named twice
        rose twice), and no other time (the tracks are sampled together)."""
        seen = sorted((i, d) for d in set(turns) for i in rises(ev, d, alt))
        order = [d for _, d in seen]
        return Check(order == turns, f"the drones rose in the order {order} (want {turns})")

    def in_turn(ev: Evidence, drones: tuple[str, ...], alt: float) -> Check:
        """The drones first reached ``alt`` one after the other, in the order given."""
        first = [rises(ev, d, alt)[:1] for d in drones]
        ok = all(first) and all(a[0] < b[0] for a, b in itertools.pairwise(first))
        return Check(ok, f"{' then '.join(drones)} {'went' if ok else 'did not go'} up in turn")

    def together(ev: Evidence, a: str, b: str, alt: float) -> Check:
        """At some sample both drones were up at ``alt`` (less the tolerance): one handed over to the other."""
        ta, tb = ev.track.get(a, []), ev.track.get(b, [])
        ok = any(
            p.alt_rel_m >= alt - ALT_TOL_M and q.alt_rel_m >= alt - ALT_TOL_M
            for p, q in zip(ta, tb, strict=False)
        )
        return Check(ok, f"{a} and {b} {'were' if ok else 'were never'} up together")

    def apart_in_air(ev: Evidence, drones: tuple[str, ...], least: float) -> Check:
        """No two drones in the air came closer than ``least`` metres (the tracks are sampled together)."""
        tracks = [ev.track.get(d, []) for d in drones]
        near = min((horizontal_distance_m(p.lat, p.lon, q.lat, q.lon)
                    for samples in zip(*tracks, strict=False)
                    for j, p in enumerate(samples) for q in samples[j + 1 :]
                    if not p.landed and not q.landed), default=math.inf)  # fmt: skip
        return Check(near >= least, f"the drones in the air came {near:.1f} m close (at least {least:g})")

    def v_led_by(
        c: MissionContext, ev: Evidence, lead: str, left: str, right: str, alt: float, arm_m: float
    ) -> Check:
        """A V pointing north at ``alt``: ``lead`` at its tip, north of both wings; ``left`` on the west wing
        and ``right`` on the east one, level with each other and each ``arm_m`` from the tip (±3 m); the V
        over the centre of the three homes."""
        tip_at = ev.final[lead]
        wings = {
            d: ned_offset(tip_at.lat, tip_at.lon, ev.final[d].lat, ev.final[d].lon) for d in (left, right)
        }
        arms = [math.hypot(*wings[d]) for d in (left, right)]
        shape = (
            all(n <= -3.0 for n, _ in wings.values())
            and wings[left][1] <= -3.0
            and wings[right][1] >= 3.0
            and abs(wings[left][0] - wings[right][0]) <= 3.0
            and all(abs(a - arm_m) <= 3.0 for a in arms)
        )
        centre = slot(c, (lead, left, right), 0.0, 0.0)
        off = horizontal_distance_m(*_centroid([ev.final[d] for d in (lead, left, right)]), *centre)
        return _all(
            *(airborne_at(ev, d, alt) for d in (lead, left, right)),
            Check(shape, f"{lead} {'leads' if shape else 'does not lead'} a V ({left} west, {right} east)"),
            Check(off <= HORIZONTAL_TOL_M, f"the V's centre {off:.1f} m from the pads' centre"),
        )

    def charlie_between(c: MissionContext) -> tuple[float, float]:
        """10 m from alpha (10 m south of its pad) on the straight line to bravo (30 m north of its own)."""
        start = c.point("alpha", -10, 0)
        b = math.radians(bearing_deg(*start, *c.point("bravo", 30, 0)))
        return offset_position(*start, 10 * math.cos(b), 10 * math.sin(b))

    return [
        # single
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("single", "dev", "single19-alpha-under-crane-hook", ("alpha",),
               "The crane beside alpha's pad has its hook hanging at 18 m. Bring alpha up to 4 m below the hook, "
               "straight over its pad, and hold it there; never above the hook.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=14), airborne_at(ev, "alpha", 14),
                                  max_alt_at_most(ev, "alpha", 18)),
               [_takeoff("alpha", 14)], "Alpha hovers at 14 m over its pad, 4 m below the crane's hook."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("single", "dev", "single19-da-bravo-down-in-steps", ("bravo",),
               "Send bravo op i 24 meters højde, lige over sit startsted. Sænk den derefter i trin på 8 meter, 2 "
               "trin i alt, og lad den blive hængende i luften dér.",
               lambda c, ev: _all(rose_to(ev, "bravo", 24),
                                  passed(ev, "bravo", [(_home(c, "bravo"), 24), (_home(c, "bravo"), 16)]),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=8), airborne_at(ev, "bravo", 8)),
               [_takeoff("bravo", 24), _move("bravo", up=-8), _move("bravo", up=-8)],
               "bravo steg til 24 m og blev sænket 8 m ad gangen, 2 gange: den hænger nu i 8 m over sit startsted."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("single", "dev", "single19-el-charlie-tallest-tree", ("charlie",),
               "Γύρω από το σημείο απογείωσης του charlie υπάρχουν τρία δέντρα, ύψους 7, 16 και 10 μέτρων. Ανέβασε "
               "το charlie στο ύψος του ψηλότερου από αυτά, ακριβώς πάνω από το σημείο απογείωσης, και κράτησέ το "
               "εκεί στον αέρα.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=16), airborne_at(ev, "charlie", 16)),
               [_takeoff("charlie", 16)],
               "Το charlie αιωρείται στα 16 m πάνω από το σημείο απογείωσης, στο ύψος του ψηλότερου δέντρου."),
        # multi
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("multi", "dev", "multi19-hand-over-in-turn", three,
               "We need a drone over the pads at 15 m all the time, and only one at a time except while they hand "
               "over. Alpha goes up first. Then bravo takes over: once bravo is up at 15 m over its own pad, alpha "
               "lands. Charlie then takes over from bravo the same way, and stays up.",
               lambda c, ev: _all(in_turn(ev, three, 15), together(ev, "alpha", "bravo", 15),
                                  together(ev, "bravo", "charlie", 15),
                                  *(_all(at(ev, d, *_home(c, d)), landed_disarmed(ev, d)) for d in ("alpha", "bravo")),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=15), airborne_at(ev, "charlie", 15)),
               [_takeoff("alpha", 15), _takeoff("bravo", 15), _land("alpha"), _takeoff("charlie", 15), _land("bravo")],
               "Alpha, then bravo, then charlie kept watch at 15 m, each landing once the next was up; charlie is "
               "up now."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("multi", "dev", "multi19-no-charlie-mirrors-alpha", three,
               "Send alpha 15 meter mot nordvest i 10 meters høyde. Charlie skal fly den samme turen speilvendt fra "
               "sin egen plass, altså mot øst der alpha fløy mot vest, like langt og like høyt. La begge bli "
               "hengende der; bravo blir stående på bakken.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", d15, -d15), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "charlie", *c.point("charlie", d15, d15), alt=10),
                                  airborne_at(ev, "charlie", 10), never_armed(ev, "bravo")),
               [_move("alpha", d15, -d15, alt=10), _move("charlie", d15, d15, alt=10)],
               "alpha henger 15 m nordvest for sin plass og charlie 15 m nordøst for sin, begge i 10 m; bravo ble "
               "stående."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("multi", "dev", "multi19-fi-pair-takes-turns-hopping", three,
               "Alpha ja bravo tekevät vuorotellen pienen hypyn: nousu 6 metriin oman alustansa yläpuolelle ja "
               "heti takaisin alas samaan kohtaan. Ensin alpha, sitten bravo ja lopuksi vielä kerran alpha. "
               "Charlie jää maahan.",
               lambda c, ev: _all(hops_in_turn(ev, ["alpha", "bravo", "alpha"], 6),
                                  *(_all(at(ev, d, *_home(c, d)), landed_disarmed(ev, d)) for d in ("alpha", "bravo")),
                                  never_armed(ev, "charlie")),
               [_takeoff("alpha", 6), _land("alpha"), _takeoff("bravo", 6), _land("bravo"), _takeoff("alpha", 6),
                _land("alpha")],
               "alpha hyppäsi kahdesti ja bravo kerran niiden välissä; molemmat ovat maassa, charlie ei noussut."),
        # compound
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("compound", "dev", "compound19-bravo-route-told-backwards", ("bravo",),
               "I'll give you bravo's route backwards. It should end up on the ground 10 m west of its pad. Just "
               "before that, it passes over the point 20 m north of its pad at 12 m. And before that, it takes off "
               "from its pad straight up to 12 m.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 20, 0)], alt=12),
                                  at(ev, "bravo", *c.point("bravo", 0, -10)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", 20, 0), _move("bravo", -20, -10), _land("bravo")],
               "Bravo climbed to 12 m, passed over the point 20 m north of its pad and landed 10 m west of it."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("compound", "dev", "compound19-hu-alpha-marker-posts", ("alpha",),
               "Az alpha leszállóhelyétől északra egy sorban jelzőkarók állnak, 8 méterenként; az első 8 méterre "
               "van a leszállóhelytől. Emeld fel az alpha drónt 10 méterre, vidd a harmadik karó fölé, ott engedd "
               "le 5 méterre, majd ezen a magasságon repülj vele tovább az ötödik karóig, és ott tedd le.",
               lambda c, ev: _all(passed(ev, "alpha", [(c.point("alpha", 24, 0), 10), (c.point("alpha", 24, 0), 5),
                                                       (c.point("alpha", 32, 0), 5)]),
                                  at(ev, "alpha", *c.point("alpha", 40, 0)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", 24, 0), _move("alpha", alt=5), _move("alpha", 16, 0),
                _land("alpha")],
               "alpha a harmadik karó fölött (24 m) 5 méterre ereszkedett, és az ötödiknél (40 m) leszállt."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("compound", "dev", "compound19-bg-charlie-zigzag-straight-back", ("charlie",),
               "Издигни charlie на 12 метра, прелети с него 20 метра на североизток, после 20 метра на северозапад, "
               "а оттам го върни по най-краткия път, по права линия, над площадката му и го приземи там.",
               # straight back is due south: it passes the point halfway, which the zigzag's legs miss by 10 m
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", d20, d20), c.point("charlie", 2 * d20, 0),
                                                          c.point("charlie", d20, 0)]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), _move("charlie", d20, d20), _move("charlie", d20, -d20),
                _move("charlie", -2 * d20, 0), _land("charlie")],
               "charlie прелетя 20 м на североизток и 20 м на северозапад, върна се право на юг над площадката си и "
               "кацна."),
        # conditional
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("conditional", "dev", "cond19-charlie-north-by-its-lead", three,
               "Check bravo's and charlie's batteries. If charlie has more, fly it north at 10 m by as many metres "
               "as it is ahead of bravo in percentage points, and hold it there. If it isn't ahead, nothing flies.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 25, 0), alt=10), airborne_at(ev, "charlie", 10),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               [("fleet_status", {}), _move("charlie", 25, 0, alt=10)],
               "Charlie (78 %) is 25 points ahead of bravo (53 %): it hovers 25 m north of its pad at 10 m.",
               battery={"bravo": 53.0, "charlie": 78.0}),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("conditional", "dev", "cond19-sk-middle-charge-flies", three,
               "Pozri sa na batérie všetkých troch dronov. Ten, ktorého nabitie je medzi ostatnými dvoma (nie "
               "najvyššie ani najnižšie), nech vzlietne do 12 metrov, preletí 20 metrov na juh a zostane tam visieť. "
               "Ostatné dva zostanú na zemi.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", -20, 0), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               [("fleet_status", {}), _move("charlie", -20, 0, alt=12)],
               "Stredné nabitie má charlie (63 %): visí 20 m južne vo výške 12 m; alpha (81 %) a bravo (44 %) "
               "zostali na zemi.",
               battery={"alpha": 81.0, "bravo": 44.0, "charlie": 63.0}),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("conditional", "dev", "cond19-ca-all-up-low-ones-land", three,
               "Enlaira els tres drons a 10 metres, cadascun sobre la seva plataforma. Un cop a dalt, els que "
               "tinguin menys del 50 % de bateria han de tornar a aterrar al seu lloc; els altres volen 20 metres "
               "cap al nord i s'hi queden en vol estacionari.",
               lambda c, ev: _all(rose_to(ev, "bravo", 10), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo"),
                                  *(_all(at(ev, d, *c.point(d, 20, 0), alt=10), airborne_at(ev, d, 10))
                                    for d in ("alpha", "charlie"))),
               [("fleet_status", {}), _takeoff("alpha", 10), _takeoff("bravo", 10), _takeoff("charlie", 10),
                _land("bravo"), _move("alpha", 20, 0), _move("charlie", 20, 0)],
               "bravo (41 %) ha tornat a aterrar; alpha (72 %) i charlie (58 %) són a 20 m al nord, a 10 m d'alçada.",
               battery={"alpha": 72.0, "bravo": 41.0, "charlie": 58.0}),
        # formation
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("formation", "dev", "form19-row-spaced-by-height", three,
               "Line the three up abreast over where they stand, at 12 m, with as much room between neighbours as "
               "they are high, and hold them there.",
               lambda c, ev: _all(formation_at(c, ev, three, 12, 12, 0, 0), farthest_apart(ev, three, 24),
                                  row_along(ev, three, 90)),
               [_formation(three, "line", 12, 12)],
               "The three hover abreast at 12 m, 12 m apart, over where they stood."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("formation", "dev", "form19-th-row-in-reverse-order", three,
               "จัดโดรนทั้งสามลำเป็นแถวเดียวจากตะวันตกไปตะวันออก ให้ charlie อยู่ทางตะวันตกสุด ถัดมาเป็น bravo "
               "และ alpha อยู่ทางตะวันออกสุด แต่ละลำห่างกัน 10 เมตร ที่ความสูง 14 เมตร โดยให้กึ่งกลางแถวอยู่เหนือจุดที่"
               "พวกมันจอดอยู่ตอนนี้ แล้วให้ลอยค้างไว้ตรงนั้น",
               lambda c, ev: _all(*(_all(at(ev, d, *slot(c, three, 0, e), alt=14), airborne_at(ev, d, 14))
                                    for d, e in (("charlie", -10), ("bravo", 0), ("alpha", 10)))),
               # (alpha, whose pad is the westernmost, flies first, over the pads of the two still down)
               lambda c: [_go(d, slot(c, three, 0, e), 14) for d, e in (("alpha", 10), ("charlie", -10), ("bravo", 0))],
               "โดรนทั้งสามลอยอยู่ที่ 14 m เรียงจากตะวันตกไปตะวันออก: charlie, bravo, alpha ห่างกันลำละ 10 m"),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("formation", "dev", "form19-ms-v-with-bravo-leading", three,
               "Susun ketiga-tiga dron dalam bentuk V yang menghala ke utara pada ketinggian 15 meter: bravo di "
               "hujung hadapan, alpha di sayap kiri belakang dan charlie di sayap kanan belakang, masing-masing 10 "
               "meter dari bravo. Pusatkan formasi itu di atas tempat dron-dron itu berada sekarang dan biarkan "
               "semuanya berlegar di situ.",
               lambda c, ev: v_led_by(c, ev, "bravo", "alpha", "charlie", 15, 10),
               lambda c: [_go(d, slot(c, three, *p), 15) for d, p in (("bravo", tip), ("alpha", left_wing),
                                                                      ("charlie", right_wing))],
               "bravo di hujung V yang menghala ke utara; alpha dan charlie 10 m di belakangnya, di kiri dan di "
               "kanan, semuanya pada 15 m."),
        # relative
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("relative", "dev", "rel19-alpha-quarter-turn-round-pad", ("alpha",),
               "Take alpha up to 12 m and 20 m north of its pad. Then swing it a quarter turn clockwise round the "
               "pad, keeping the same distance from it, and hold it where it ends up.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 20, 0)], alt=12),
                                  at(ev, "alpha", *c.point("alpha", 0, 20), alt=12), airborne_at(ev, "alpha", 12)),
               [_takeoff("alpha", 12), _move("alpha", 20, 0), _move("alpha", -20, 20)],
               "Alpha swung from 20 m north of its pad to 20 m east of it and holds there at 12 m."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("relative", "dev", "rel19-tl-bravo-grid-squares", ("bravo",),
               "Hinati namin ang field sa mga parisukat na tig-10 metro ang gilid. Paliparin mo si bravo sa taas na "
               "12 metro, tapos ilipat mo siya nang 3 parisukat pahilaga, saka 2 parisukat pakanluran. Pagkatapos, "
               "hayaan mo siyang lumutang doon.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 30, -20), alt=12), airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 12), _move("bravo", 30, 0), _move("bravo", 0, -20)],
               "Lumulutang si bravo nang 30 m pahilaga at 20 m pakanluran mula sa pad niya, sa taas na 12 m."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("relative", "dev", "rel19-sw-charlie-pad-to-its-southwest", ("charlie",),
               "Ipaishe charlie hadi mita 12, kisha uisogeze hadi mahali ambapo kituo chake cha kurukia kitakuwa "
               "mita 25 upande wa kusini-magharibi yake. Iache ielee hapo.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", d25, d25), alt=12), airborne_at(ev, "charlie", 12)),
               [_takeoff("charlie", 12), _move("charlie", d25, d25)],
               "charlie inaelea mita 25 kaskazini-mashariki mwa kituo chake, kwenye mita 12: kituo kiko "
               "kusini-magharibi yake."),
        # question
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("question", "dev", "ask19-first-to-run-out", three,
               "In a hover alpha burns about 2 % of its battery a minute, bravo 1 % and charlie 3 %. If all three "
               "hovered from now until they were flat, which would run out first, and after how many minutes? "
               "Don't fly anything.",
               # the typed plan reads, it does not compute: the minutes, or the reading they come from
               lambda c, ev: _all(answer_says(ev, r"\bcharlie\b", "charlie"),
                                  _any(answer_mentions_number(ev, 22, 0.5), answer_mentions_number(ev, 66, 1)),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Charlie: 66 % at 3 % a minute lasts 22 minutes (alpha 40, bravo 50).",
               battery={"alpha": 80.0, "bravo": 50.0, "charlie": 66.0}),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("question", "dev", "ask19-ur-bravo-against-midpoint", three,
               "کیا bravo کی بیٹری alpha اور charlie کی بیٹریوں کے عین درمیانی عدد سے زیادہ ہے یا کم؟ تینوں کے فیصد "
               "بتاؤ، لیکن کسی ڈرون کو مت اڑاؤ۔",
               lambda c, ev: _all(answer_mentions_number(ev, 66, 1),
                                  _any(answer_mentions_number(ev, 60, 0.5),
                                       _all(answer_mentions_number(ev, 40, 1), answer_mentions_number(ev, 80, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})],
               "زیادہ: bravo کی بیٹری 66 % ہے، جبکہ alpha (40 %) اور charlie (80 %) کا درمیانی عدد 60 % ہے۔",
               battery={"alpha": 40.0, "bravo": 66.0, "charlie": 80.0}),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("question", "dev", "ask19-bn-total-above-reserve", three,
               "প্রতিটি ড্রোনকে নামার সময় অন্তত 30 % চার্জ রাখতে হবে। সেই 30 % বাদ দিলে তিনটি ড্রোন মিলিয়ে মোট কত "
               "শতাংশ চার্জ কাজে লাগানো যাবে? প্রত্যেকটির সংখ্যাও বলো, কিন্তু কোনো ড্রোন ওড়াবে না।",
               # the typed plan reads, it does not compute: the total, or the three readings it comes from
               lambda c, ev: _all(_any(answer_mentions_number(ev, 77, 1),
                                       _all(*(answer_mentions_number(ev, v, 1) for v in (70, 55, 42)))),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "মোট 77 %: alpha 70 % (40 কাজে লাগবে), bravo 55 % (25), charlie 42 % (12)।",
               battery={"alpha": 70.0, "bravo": 55.0, "charlie": 42.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude, 5 m the least separation a formation keeps)
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("refusal", "dev", "refuse19-row-too-tight", three,
               "Bunch the three drones up tight for the group photo: a row abreast at 15 m right over where they "
               "stand, only 3 m between neighbours.",
               lambda c, ev: _all(refusal_seen(ev, "separation"), apart_in_air(ev, three, 4),
                                  answer_reports_refusal(ev)),
               [_formation(three, "line", 15, 3)],
               "Refused: 3 m between neighbours is below the minimum separation of 5 m the gateway keeps."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("refusal", "dev", "refuse19-af-bravo-climb-rate-over-ceiling", ("bravo",),
               "Laat bravo reguit bo sy landingsplek opstyg teen 4 meter per sekonde, 40 sekondes lank, en hou hom "
               "dan daar.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "bravo", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("bravo", 160)],
               "Geweier: 4 m/s vir 40 s bring bravo op 160 m, bo die hoogtegrens van 120 m."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("refusal", "dev", "refuse19-et-alpha-diagonal-past-limit", ("alpha",),
               "Tõsta alpha 20 meetri kõrgusele ja vii see ühe sirge lennuga punkti, mis asub tema stardikohast 800 "
               "meetrit põhja ja 700 meetrit ida pool.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "alpha", c.max_distance_m), answer_reports_refusal(ev)),
               [_takeoff("alpha", 20), _move("alpha", 800, 700)],
               "alpha on 20 m kõrgusel; lennust punkti 800 m põhja ja 700 m ida pool keelduti: see on stardikohast "
               "1063 m kaugusel, üle 1000 m piiri."),
        # units
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("units", "dev", "units19-alpha-chains", ("alpha",),
               "On the rail survey the next peg is 5 chains east of alpha's pad, a chain being 22 yards. Take alpha "
               "up to 10 m, fly it to the spot straight above that peg and hold it there.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, 5 * chain), alt=10), airborne_at(ev, "alpha", 10)),
               [_takeoff("alpha", 10), _move("alpha", 0, 5 * chain)],
               "Alpha holds over the peg, 110 yd (100.6 m) east of its pad, at 10 m."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("units", "dev", "units19-lt-bravo-paces", ("bravo",),
               "Nuo bravo aikštelės iki vartų yra 40 žingsnių tiesiai į pietus, o mano žingsnis – maždaug 75 "
               "centimetrai. Pakelk bravo į 12 metrų aukštį, nuskraidink jį virš vartų ir ten nutupdyk.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", -30, 0)], alt=12),
                                  at(ev, "bravo", *c.point("bravo", -30, 0)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", -30, 0), _land("bravo")],
               "bravo nuskrido 30 m į pietus (40 žingsnių po 75 cm) ir nutūpė prie vartų."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("units", "dev", "units19-ky-charlie-millimetres", ("charlie",),
               "Чиймеде charlie турган аянтчадан антеннага чейинки аралык түз батышты карай 25 000 мм деп "
               "көрсөтүлгөн. charlie-ни 15 метр бийиктикке көтөрүп, антеннанын үстүнө алып бар да, ошол жерде абада "
               "кармап тур.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, -25), alt=15), airborne_at(ev, "charlie", 15)),
               [_takeoff("charlie", 15), _move("charlie", 0, -25)],
               "charlie антеннанын үстүндө, аянтчасынан 25 м батышта, 15 м бийиктикте турат."),
        # pattern
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("pattern", "dev", "pattern19-charlie-sawtooth-profile", ("charlie",),
               "Charlie at 10 m: fly a sawtooth profile eastward, climbing to 16 m over each 10 m stretch and "
               "dropping back to 10 m over the next. Three teeth, so 60 m in all, then land it where it ends.",
               lambda c, ev: _all(passed(ev, "charlie", [(c.point("charlie", 0, e), h) for e, h in teeth[:5]]),
                                  at(ev, "charlie", *c.point("charlie", 0, 60)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), *(_move("charlie", 0, 10, alt=h) for _, h in teeth), _land("charlie")],
               "Charlie flew three teeth between 10 and 16 m over 60 m east, and landed at the end."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("pattern", "dev", "pattern19-sr-bravo-rectangle-by-diagonal", ("bravo",),
               "Подигни bravo на 12 метара и нека облети правоугаоник чија су два наспрамна темена његово место "
               "полетања и тачка 30 метара северно и 40 метара источно од њега. Нека прво лети на север, а на крају "
               "нека слети тамо где је кренуо.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(rectangle)[:3]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), *_legs("bravo", rectangle), _land("bravo")],
               "bravo је облетео правоугаоник 30 × 40 m и слетео тамо где је кренуо."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("pattern", "dev", "pattern19-sl-alpha-hexagon-by-perimeter", ("alpha",),
               "Dvigni alpha na 10 metrov in z njim obleti pravilni šestkotnik z obsegom 60 metrov. Prva stranica "
               "naj gre proti vzhodu, na vsakem oglišču zavij v desno, in ko se vrne na začetek, naj tam pristane.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(hexagon)[:5]]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), *_legs("alpha", hexagon), _land("alpha")],
               "alpha je obletel šestkotnik s stranicami po 10 m in pristal na začetku."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # charlie from alpha, so that a drone placed from itself misses)
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("placement", "dev", "place19-charlie-between-ten-from-alpha", three,
               "Bravo climbs to 15 m and flies 30 m north; alpha flies 10 m south at 15 m. Then put charlie at 15 m "
               "on the straight line between the two, 10 m from alpha, and leave all three hovering.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 30, 0), alt=15), airborne_at(ev, "bravo", 15),
                                  at(ev, "alpha", *c.point("alpha", -10, 0), alt=15), airborne_at(ev, "alpha", 15),
                                  at(ev, "charlie", *charlie_between(c), alt=15), airborne_at(ev, "charlie", 15)),
               lambda c: [_takeoff("bravo", 15), _move("bravo", 30, 0), _move("alpha", -10, 0, alt=15),
                          _go("charlie", charlie_between(c), 15)],
               "Bravo hovers 30 m north of its pad and alpha 10 m south of its own; charlie is on the line between "
               "them, 10 m from alpha; all three at 15 m."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("placement", "dev", "place19-jv-charlie-where-alpha-was", three,
               "Munggahna alpha nganti dhuwuré 12 mèter, terus pindhahen ngalor 20 mèter, banjur ngétan 15 mèter. "
               "Sawisé iku, gawanen charlie menyang panggonané alpha sadurungé pindhah ngétan mau, ing dhuwur sing "
               "padha, lan jarna ngambang ing kono. bravo tetep ing lemah waé.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 15), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", 20, 0), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 12), _move("alpha", 20, 0), _move("alpha", 0, 15),
                          _go("charlie", c.point("alpha", 20, 0), 12)],
               "alpha ngambang 20 m ngalor lan 15 m ngétan saka papané; charlie ana ing panggonané alpha sadurungé "
               "ngétan, ing 12 m."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("placement", "dev", "place19-ceb-charlie-west-by-alpha-height", three,
               "Isaka ang alpha ngadto sa 12 ka metros ang gitas-on, unya ipalupad kini 25 ka metros paingon sa "
               "amihanan. Human niana, ibutang ang charlie sa kasadpan sa alpha, sa gilay-on nga sama sa gitas-on "
               "sa alpha, ug sa samang gitas-on. Pasagdi silang duha nga magpabilin sa hangin didto; ang bravo "
               "magpabilin sa yuta.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 25, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", 25, -12), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 12), _move("alpha", 25, 0), _go("charlie", c.point("alpha", 25, -12), 12)],
               "Ang alpha naa sa 25 m sa amihanan, 12 m ang gitas-on; ang charlie 12 m sa kasadpan niini, sa samang "
               "gitas-on."),
        # language
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("language", "dev", "lang19-km-alpha-east-land", ("alpha",),
               "ឲ្យ alpha ហោះឡើងដល់កម្ពស់ 15 ម៉ែត្រ បន្ទាប់មកហោះទៅទិសខាងកើត 20 ម៉ែត្រ ហើយចុះចតនៅទីនោះ។",
               lambda c, ev: _all(reached_alt(ev, "alpha", 15), at(ev, "alpha", *c.point("alpha", 0, 20)),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 15), _move("alpha", 0, 20), _land("alpha")],
               "alpha បានហោះទៅទិសខាងកើត 20 m ហើយចុះចតនៅទីនោះ។"),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("language", "dev", "lang19-lo-charlie-north-west-hover", ("charlie",),
               "ໃຫ້ charlie ບິນຂຶ້ນສູງ 12 ແມັດ, ບິນໄປທາງທິດເໜືອ 25 ແມັດ, ແລ້ວໄປທາງທິດຕາເວັນຕົກອີກ 10 ແມັດ, "
               "ແລ້ວໃຫ້ມັນລອຍຢູ່ກາງອາກາດບ່ອນນັ້ນ.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 25, 0)], alt=12),
                                  at(ev, "charlie", *c.point("charlie", 25, -10), alt=12), airborne_at(ev, "charlie", 12)),
               [_takeoff("charlie", 12), _move("charlie", 25, 0), _move("charlie", 0, -10)],
               "charlie ລອຍຢູ່ 25 m ທາງທິດເໜືອ ແລະ 10 m ທາງທິດຕາເວັນຕົກ, ສູງ 12 m."),
        # moved to dev on 2026-12-05, nineteenth round: measured on both models, its failures seen
        _entry("language", "dev", "lang19-zu-bravo-south-home", ("bravo",),
               "Khuphula i-bravo ifike emamitheni ayi-10, uyindizise amamitha angama-30 ubheke eningizimu, bese "
               "uyibuyisela lapho isuke khona uyehlise phansi.",
               # the return home climbs to its own height: the leg south is checked at 10 m instead
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", -30, 0)], alt=10),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 10), _move("bravo", -30, 0), _rtl("bravo")],
               "i-bravo indize amamitha angama-30 eningizimu, yabuya yehla lapho isuke khona."),
    ]  # fmt: skip


def _twentieth_round() -> list[CorpusEntry]:
    """The test half written on 2026-12-04 (twentieth round), before any model ran on it, by a writer who
    did not read the host's word lists or rules: 3 a class; 22 of the 33 outside ``language`` in other
    languages than English, one each (Afrikaans, Bengali, Bulgarian, Catalan, Cebuano, Danish, Estonian,
    Finnish, Greek, Hungarian, Javanese, Kyrgyz, Lithuanian, Malay, Norwegian, Serbian in Latin script,
    Slovak, Slovenian, Swahili, Tagalog, Thai, Urdu), the ``language`` class's 3 in Burmese, Yoruba and
    Somali (all three new to the corpus, and Myanmar script with them); all of it moved to dev on 2026-12-05
    (twentieth round), once both models had been measured on it (docs/benchmarks.md)."""
    three = DRONES
    d30 = 30 / math.sqrt(2)
    # three passes 40 m long northward, 10 m apart, stepping east between them
    mow = [(40.0, 0.0), (0.0, 10.0), (-40.0, 0.0), (0.0, 10.0), (40.0, 0.0)]
    # a 20 m square, the first side due west, turning left (south, east, north)
    square_left = [(0.0, -20.0), (-20.0, 0.0), (0.0, 20.0), (20.0, 0.0)]
    # an equilateral triangle of 20 m sides, the first due north, turning right
    triangle = _polygon_legs(3, 20.0, 0.0, right=True)

    def landed_before(ev: Evidence, d: str, stop: tuple[float, float], later: tuple[float, float]) -> Check:
        """The drone was on the ground at ``stop`` before it first came over ``later`` (a stop on the way
        out, not on the way back; where it ends counts as coming over ``later`` when the track stops short)."""
        track = ev.track.get(d, [])
        near = [
            i for i, s in enumerate(track) if horizontal_distance_m(s.lat, s.lon, *later) <= HORIZONTAL_TOL_M
        ]
        final = ev.final[d]
        if not near and horizontal_distance_m(final.lat, final.lon, *later) <= HORIZONTAL_TOL_M:
            near = [len(track)]
        down = [i for i, s in enumerate(track)
                if s.landed and horizontal_distance_m(s.lat, s.lon, *stop) <= HORIZONTAL_TOL_M]  # fmt: skip
        ok = bool(down) and bool(near) and down[0] < near[0]
        return Check(ok, f"{d} {'landed' if ok else 'did not land'} at the first stop before going on")

    return [
        # single
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("single", "dev", "single20-bravo-level-with-mast-light", ("bravo",),
               "The mast next to bravo's pad is 40 m tall and its warning light sits a quarter of the way down "
               "from the top. Put bravo level with that light, straight over its pad, and hold it there.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=30), airborne_at(ev, "bravo", 30)),
               [_takeoff("bravo", 30)], "Bravo hovers at 30 m over its pad, level with the mast's warning light."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("single", "dev", "single20-fi-alpha-twice-as-high", ("alpha",),
               "Nosta alpha suoraan lähtöpaikkansa yläpuolelle 7 metrin korkeuteen. Kun kamera on tarkistettu, "
               "nosta se kaksi kertaa niin korkealle ja jätä se leijumaan siihen.",
               lambda c, ev: _all(passed(ev, "alpha", [(_home(c, "alpha"), 7), (_home(c, "alpha"), 14)]),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=14), airborne_at(ev, "alpha", 14)),
               [_takeoff("alpha", 7), _move("alpha", alt=14)],
               "alpha leijuu 14 metrissä lähtöpaikkansa yläpuolella, kaksi kertaa 7 metrin korkeudella."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("single", "dev", "single20-ur-charlie-two-hops", ("charlie",),
               "موٹروں کی جانچ کے لیے charlie کو دو بار اڑاؤ: ہر بار اسے اس کے پیڈ سے سیدھا 10 میٹر اوپر لے جاؤ "
               "اور پھر واپس اسی جگہ اتار دو۔",
               lambda c, ev: _all(takeoffs(ev, "charlie", 10, 2), at(ev, "charlie", *_home(c, "charlie")),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _land("charlie"), _takeoff("charlie", 10), _land("charlie")],
               "charlie دو بار 10 میٹر تک اٹھا اور ہر بار اپنے پیڈ پر واپس اترا۔"),
        # multi
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("multi", "dev", "multi20-alpha-charlie-swap-pads", three,
               "Get alpha up to 10 m and charlie up to 15 m, each over its own pad, then have them swap places: "
               "alpha over charlie's pad and charlie over alpha's, each keeping its height so they pass without "
               "meeting. Bravo stays on the ground.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "charlie"), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "charlie", *_home(c, "alpha"), alt=15), airborne_at(ev, "charlie", 15),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 10), _takeoff("charlie", 15), _go("alpha", _home(c, "charlie"), 10),
                          _go("charlie", _home(c, "alpha"), 15)],
               "Alpha hovers over charlie's pad at 10 m and charlie over alpha's at 15 m; bravo stayed down."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("multi", "dev", "multi20-hu-spread-bravo-back-down", three,
               "Emeld fel mindhárom drónt 12 méterre, mindegyiket a saját leszállóhelye fölé. Ezután alpha "
               "repüljön 15 métert nyugatra, charlie ugyanennyit keletre, bravo pedig szálljon le oda, ahonnan "
               "felszállt.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, -15), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("charlie", 0, 15), alt=12), airborne_at(ev, "charlie", 12),
                                  rose_to(ev, "bravo", 12), at(ev, "bravo", *_home(c, "bravo")),
                                  landed_disarmed(ev, "bravo")),
               [_takeoff("alpha", 12), _takeoff("bravo", 12), _takeoff("charlie", 12), _move("alpha", 0, -15),
                _move("charlie", 0, 15), _land("bravo")],
               "alpha 15 m-re nyugatra, charlie 15 m-re keletre lebeg 12 m magasan; bravo visszaszállt a helyére."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("multi", "dev", "multi20-th-pair-north-one-returns", three,
               "ให้ alpha กับ bravo บินขึ้นไปที่ความสูง 10 เมตร แล้วบินไปทางทิศเหนือ 20 เมตรทั้งคู่ จากนั้นให้ alpha "
               "ลงจอดตรงนั้นเลย ส่วน bravo ให้บินกลับมาลงจอดที่จุดที่มันขึ้นบิน charlie ไม่ต้องบิน",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 20, 0)], alt=10),
                                  at(ev, "alpha", *c.point("alpha", 20, 0)), landed_disarmed(ev, "alpha"),
                                  visited(ev, "bravo", [c.point("bravo", 20, 0)], alt=10),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo"),
                                  never_armed(ev, "charlie")),
               [_move("alpha", 20, 0, alt=10), _move("bravo", 20, 0, alt=10), _land("alpha"), _rtl("bravo")],
               "alpha ลงจอดห่างไปทางเหนือ 20 m ส่วน bravo บินกลับมาลงจอดที่จุดขึ้นบิน charlie ไม่ได้บิน"),
        # compound
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("compound", "dev", "compound20-bravo-lands-at-first-sensor", ("bravo",),
               "Bravo has two fence sensors to service, 20 m and 40 m north of its pad. At 10 m, fly it to the "
               "first one and land there so the crew can swap the sensor's battery; then take it back up to 10 m, "
               "fly on to the second one and hold it over that.",
               lambda c, ev: _all(landed_before(ev, "bravo", c.point("bravo", 20, 0), c.point("bravo", 40, 0)),
                                  at(ev, "bravo", *c.point("bravo", 40, 0), alt=10), airborne_at(ev, "bravo", 10)),
               [_takeoff("bravo", 10), _move("bravo", 20, 0), _land("bravo"), _takeoff("bravo", 10),
                _move("bravo", 20, 0)],
               "Bravo landed at the first sensor, 20 m north, took off again and hovers over the second, 40 m "
               "north of its pad, at 10 m."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("compound", "dev", "compound20-sk-alpha-west-climb-south-land", ("alpha",),
               "Vzlietni s dronom alpha do výšky 10 metrov a preleť 20 metrov na západ. Tam vystúp na 25 metrov, "
               "potom preleť 20 metrov na juh a pristaň.",
               lambda c, ev: _all(passed(ev, "alpha", [(c.point("alpha", 0, -20), 10), (c.point("alpha", 0, -20), 25),
                                                       (c.point("alpha", -20, -20), 25)]),
                                  at(ev, "alpha", *c.point("alpha", -20, -20)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", 0, -20), _move("alpha", alt=25), _move("alpha", -20, 0),
                _land("alpha")],
               "alpha preletel 20 m na západ, vystúpil na 25 m, preletel 20 m na juh a pristál."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("compound", "dev", "compound20-sw-charlie-half-way-back", ("charlie",),
               "Paisha charlie hadi mita 12, uipeleke mita 30 upande wa kusini, kisha uirudishe nusu ya njia "
               "kuelekea kituo chake cha kurukia, na uitue hapo.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -30, 0)], alt=12),
                                  at(ev, "charlie", *c.point("charlie", -15, 0)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), _move("charlie", -30, 0), _move("charlie", 15, 0), _land("charlie")],
               "charlie ilienda mita 30 kusini, ikarudi mita 15 na kutua mita 15 kusini mwa kituo chake."),
        # conditional
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("conditional", "dev", "cond20-alpha-lead-of-twenty-or-charlie", three,
               "Compare alpha's and charlie's batteries. If alpha is ahead of charlie by at least 20 points, alpha "
               "flies 25 m east at 10 m and hovers there; otherwise charlie does that instead. Bravo stays down.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 0, 25), alt=10), airborne_at(ev, "charlie", 10),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               [("fleet_status", {}), _move("charlie", 0, 25, alt=10)],
               "Alpha (62 %) is only 14 points ahead of charlie (48 %), so charlie hovers 25 m east of its pad at "
               "10 m.",
               battery={"alpha": 62.0, "charlie": 48.0}),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("conditional", "dev", "cond20-da-sixty-percent-fly-north", three,
               "Tjek batterierne på alle tre droner først. De droner, der har mindst 60 %, skal lette til 15 meter "
               "og flyve 20 meter mod nord og blive hængende der; resten bliver på jorden.",
               lambda c, ev: _all(*(_all(at(ev, d, *c.point(d, 20, 0), alt=15), airborne_at(ev, d, 15))
                                    for d in ("alpha", "charlie")),
                                  never_armed(ev, "bravo")),
               [("fleet_status", {}), _move("alpha", 20, 0, alt=15), _move("charlie", 20, 0, alt=15)],
               "alpha (72 %) og charlie (66 %) hænger 20 m nord for deres pladser i 15 m; bravo (55 %) blev på "
               "jorden.",
               battery={"alpha": 72.0, "bravo": 55.0, "charlie": 66.0}),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("conditional", "dev", "cond20-ky-bravo-or-alpha-south-land", three,
               "Эгерде bravo дронунун батареясы 50 пайыздан көп болсо, аны 10 метр бийиктикке көтөрүп, 20 метр "
               "түштүккө учуруп, ошол жерге кондур. Андай болбосо, ошол эле тапшырманы alpha аткарсын. charlie "
               "жерде кала берсин.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -20, 0)], alt=10),
                                  at(ev, "alpha", *c.point("alpha", -20, 0)), landed_disarmed(ev, "alpha"),
                                  never_armed(ev, "bravo"), never_armed(ev, "charlie")),
               [("fleet_status", {}), _move("alpha", -20, 0, alt=10), _land("alpha")],
               "bravo'нун батареясы 46 %, 50 %дан аз: ошондуктан alpha 20 м түштүккө учуп, ошол жерге конду.",
               battery={"alpha": 77.0, "bravo": 46.0}),
        # formation
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("formation", "dev", "form20-column-west", three,
               "Put the three in single file, one behind the other on a north–south line, 8 m apart at 20 m, "
               "centred 30 m west of the middle of their pads, and hold them there.",
               lambda c, ev: _all(formation_at(c, ev, three, 20, 8, 0, -30), farthest_apart(ev, three, 16),
                                  row_along(ev, three, 0)),
               # (the typed plan has no heading for a formation, and the gateway faces one where it travels: a
               # column moved west would run east-west, so each drone flies to its slot)
               lambda c: [_go(d, slot(c, three, n, -30), 20) for d, n in (("alpha", 8), ("bravo", 0), ("charlie", -8))],
               "The three hover in single file north to south, 8 m apart at 20 m, 30 m west of their pads."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("formation", "dev", "form20-ca-triangle-south", three,
               "Posa els tres drons en un triangle equilàter de 12 metres de costat, a 15 metres d'alçada, "
               "centrat 20 metres al sud del punt mitjà de les seves plataformes, i deixa'ls allà en vol "
               "estacionari.",
               lambda c, ev: _all(formation_at(c, ev, three, 15, 12, -20, 0), farthest_apart(ev, three, 12)),
               [_formation(three, "circle", 15, 12, north=-20)],
               "Els tres drons són en un triangle de 12 m de costat a 15 m d'alçada, 20 m al sud de les "
               "plataformes."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("formation", "dev", "form20-sr-row-over-charlie-pad", three,
               "Poređaj sva tri drona u red od zapada prema istoku, na visini od 10 metara, sa razmakom od 6 "
               "metara između susednih, tako da sredina reda bude tačno iznad mesta poletanja drona charlie. Neka "
               "lebde tamo.",
               lambda c, ev: _all(formation_around(ev, three, 10, 6, _home(c, "charlie")),
                                  farthest_apart(ev, three, 12), row_along(ev, three, 90)),
               # (no heading in the typed plan, and the gateway faces a formation where it travels, here towards
               # charlie's pad: the row would run north-south, so each drone flies to its slot, charlie first)
               lambda c: [_go(d, offset_position(*_home(c, "charlie"), 0, e), 10)
                          for d, e in (("charlie", 6), ("bravo", 0), ("alpha", -6))],
               "Sva tri drona lebde na 10 m u redu zapad–istok, 6 m razmaka, sa sredinom iznad mesta poletanja "
               "drona charlie."),
        # relative
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("relative", "dev", "rel20-bravo-staircase-north", ("bravo",),
               "Walk bravo up a staircase: start it at 8 m over its pad, then two steps, each one 12 m north and "
               "5 m up, and hold it at the top.",
               lambda c, ev: _all(passed(ev, "bravo", [(c.point("bravo", 12, 0), 13)]),
                                  at(ev, "bravo", *c.point("bravo", 24, 0), alt=18), airborne_at(ev, "bravo", 18)),
               [_takeoff("bravo", 8), _move("bravo", 12, 0, up=5), _move("bravo", 12, 0, up=5)],
               "Bravo climbed two steps of 12 m north and 5 m up: it holds 24 m north of its pad at 18 m."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("relative", "dev", "rel20-el-alpha-quarter-back", ("alpha",),
               "Σήκωσε το alpha στα 12 μέτρα και πήγαινέ το 40 μέτρα νότια. Μετά γύρισέ το πίσω προς τα βόρεια "
               "κατά το ένα τέταρτο αυτής της απόστασης και κράτησέ το εκεί στον αέρα.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", -40, 0)], alt=12),
                                  at(ev, "alpha", *c.point("alpha", -30, 0), alt=12), airborne_at(ev, "alpha", 12)),
               [_takeoff("alpha", 12), _move("alpha", -40, 0), _move("alpha", 10, 0)],
               "Το alpha πήγε 40 m νότια, γύρισε 10 m πίσω και αιωρείται 30 m νότια του σημείου απογείωσης, στα "
               "12 m."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("relative", "dev", "rel20-lt-charlie-southeast-climb", ("charlie",),
               "Pakelk charlie į 10 metrų aukštį, nuskraidink jį 30 metrų į pietryčius ir ten pakelk dar 10 metrų "
               "aukščiau. Palik jį kaboti ore.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -d30, d30)], alt=10),
                                  at(ev, "charlie", *c.point("charlie", -d30, d30), alt=20),
                                  airborne_at(ev, "charlie", 20)),
               [_takeoff("charlie", 10), _move("charlie", -d30, d30), _move("charlie", up=10)],
               "charlie kabo 30 m į pietryčius nuo savo aikštelės, 20 m aukštyje."),
        # question
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("question", "dev", "ask20-spread-fullest-emptiest", three,
               "How many percentage points apart are the fullest and the emptiest battery in the fleet right now, "
               "and which drones are they? Keep everything on the ground.",
               # the typed plan reads, it does not compute: the gap, or the two readings it comes from
               lambda c, ev: _all(_any(answer_mentions_number(ev, 36, 0.5),
                                       _all(answer_mentions_number(ev, 83, 1), answer_mentions_number(ev, 47, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "36 points: alpha is fullest at 83 %, bravo emptiest at 47 % (charlie 65 %).",
               battery={"alpha": 83.0, "bravo": 47.0, "charlie": 65.0}),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("question", "dev", "ask20-bg-lead-over-second", three,
               "Кой дрон е с най-много заряд в момента и с колко процентни пункта изпреварва следващия по заряд? "
               "Нищо не излита.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"),
                                  _any(answer_mentions_number(ev, 14, 0.5),
                                       _all(answer_mentions_number(ev, 91, 1), answer_mentions_number(ev, 77, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "bravo: 91 %, с 14 пункта пред charlie (77 %); alpha има 58 %.",
               battery={"alpha": 58.0, "bravo": 91.0, "charlie": 77.0}),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("question", "dev", "ask20-jv-charlie-missions-left", three,
               "Saben misi butuh 15 % baterai, lan saben drone kudu isih nduwé paling ora 30 % sawisé misi "
               "pungkasan. Kaping pira charlie isih bisa nindakaké misi kaya ngono? Sebutna uga baterainé saiki, "
               "nanging aja ana sing mabur.",
               # the typed plan reads, it does not compute: the count, or the reading it comes from
               lambda c, ev: _all(_any(answer_mentions_number(ev, 3, 0.4), answer_mentions_number(ev, 78, 1)),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Ping 3: charlie saiki 78 %, saben misi 15 %, lan kudu isih 30 %.",
               battery={"alpha": 60.0, "bravo": 45.0, "charlie": 78.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude, 5 m the least separation a formation keeps)
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("refusal", "dev", "refuse20-charlie-low-battery", ("charlie",),
               "Charlie's just back from the last job, but it's the only one with the thermal camera. Send it up "
               "to 10 m and 50 m north to check the gate.",
               lambda c, ev: _all(refusal_seen(ev, "battery"), never_armed(ev, "charlie"), answer_reports_refusal(ev)),
               [_move("charlie", 50, 0, alt=10)],
               "Refused: charlie has 24 % battery, below the 30 % minimum to take off.",
               battery={"charlie": 24.0}),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("refusal", "dev", "refuse20-ms-bravo-second-leg-too-far", ("bravo",),
               "Naikkan bravo ke 30 meter dan terbangkan 600 meter ke barat untuk memeriksa pagar. Selepas itu, "
               "teruskan 600 meter lagi ke barat sampai ke tebing sungai.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -600), alt=30), airborne_at(ev, "bravo", 30),
                                  refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "bravo", c.max_distance_m), answer_reports_refusal(ev)),
               [_takeoff("bravo", 30), _move("bravo", 0, -600), _move("bravo", 0, -600)],
               "bravo berada 600 m ke barat pada 30 m; penerbangan 600 m lagi ditolak: 1200 m dari titik berlepas "
               "melebihi had 1000 m."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("refusal", "dev", "refuse20-ceb-alpha-down-to-one-metre", ("alpha",),
               "Ipalupad ang alpha sa 10 ka metros ibabaw sa iyang pad, unya ipaubos kini og 9 ka metros aron "
               "makita ang ilalom sa trak.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=10), airborne_at(ev, "alpha", 10),
                                  refusal_seen(ev, "minimum", "at least", "below"), answer_reports_refusal(ev)),
               [_takeoff("alpha", 10), _move("alpha", up=-9)],
               "Ang alpha anaa sa 10 m; gibalibaran ang pagpaubos og 9 m: 1 m ra kana, ubos sa minimum nga 2 m."),
        # units
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("units", "dev", "units20-alpha-feet-yards", ("alpha",),
               "Alpha: climb to 35 ft, fly 250 yards west, then drop to 20 ft there and hold it.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, -250 * YD)], alt=35 * FT),
                                  at(ev, "alpha", *c.point("alpha", 0, -250 * YD), alt=20 * FT),
                                  airborne_at(ev, "alpha", 20 * FT)),
               [_takeoff("alpha", 35 * FT), _move("alpha", 0, -250 * YD), _move("alpha", alt=20 * FT)],
               "Alpha holds 250 yd (229 m) west of its pad at 20 ft (6.1 m)."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("units", "dev", "units20-no-charlie-feet-km", ("charlie",),
               "Charlie skal opp i 40 fot og fly 0,2 km rett nordover, og så lande der.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 200, 0)], alt=40 * FT),
                                  at(ev, "charlie", *c.point("charlie", 200, 0)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 40 * FT), _move("charlie", 200, 0), _land("charlie")],
               "charlie fløy 200 m nordover i 40 fot (12,2 m) og landet der."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("units", "dev", "units20-et-bravo-cm-km", ("bravo",),
               "Tõsta bravo 1500 sentimeetri kõrgusele, lenda sellega 0,04 kilomeetrit läände ja jäta see sinna "
               "õhku hõljuma.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -40), alt=15), airborne_at(ev, "bravo", 15)),
               [_takeoff("bravo", 15), _move("bravo", 0, -40)],
               "bravo hõljub 40 m stardikohast läänes, 15 m kõrgusel."),
        # pattern
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("pattern", "dev", "pattern20-alpha-mow-north", ("alpha",),
               "Have alpha mow the field north of its pad at 15 m: three passes 40 m long running north, 10 m "
               "apart, the first straight out from the pad, stepping east between passes. Land it where the last "
               "pass ends.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", n, e) for n, e in _corners(mow)[:4]]),
                                  at(ev, "alpha", *c.point("alpha", 40, 20)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 15), *_legs("alpha", mow), _land("alpha")],
               "Alpha flew three 40 m passes north, 10 m apart, and landed 40 m north and 20 m east of its pad."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("pattern", "dev", "pattern20-bn-charlie-square-left", ("charlie",),
               "charlie-কে 10 মিটার উচ্চতায় তোলো, তারপর 20 মিটার বাহুর একটি বর্গক্ষেত্র ধরে ওড়াও: প্রথম বাহু পশ্চিম "
               "দিকে, আর প্রতিটি কোণে বাঁ দিকে ঘুরবে। যেখান থেকে শুরু করেছিল, শেষে সেখানেই নামিয়ে দাও।",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(square_left)[:3]]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), *_legs("charlie", square_left), _land("charlie")],
               "charlie পশ্চিম দিক থেকে শুরু করে বাঁ দিকে ঘুরে 20 m বাহুর বর্গক্ষেত্র উড়ে যেখান থেকে শুরু করেছিল "
               "সেখানে নেমেছে।"),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("pattern", "dev", "pattern20-tl-bravo-triangle-right", ("bravo",),
               "Paliparin mo si bravo sa taas na 12 metro, tapos paikutin mo siya sa isang tatsulok na pare-pareho "
               "ang haba ng mga gilid, 20 metro bawat isa. Pahilaga ang unang gilid, tapos kumanan siya sa bawat "
               "sulok. Pagbalik niya sa pinagsimulan, doon mo siya ilapag.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(triangle)[:2]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), *_legs("bravo", triangle), _land("bravo")],
               "Lumipad si bravo sa tatsulok na tig-20 m ang gilid, pahilaga muna, kumakanan sa bawat sulok, "
               "saka lumapag sa pinagsimulan."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # charlie from alpha, so that a drone placed from itself misses)
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("placement", "dev", "place20-charlie-north-lower-than-alpha", three,
               "Take alpha up to 20 m over its pad. Then put charlie 15 m north of alpha and 8 m lower than it, and "
               "leave both hovering; bravo stays on the ground.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=20), airborne_at(ev, "alpha", 20),
                                  at(ev, "charlie", *c.point("alpha", 15, 0), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 20), _go("charlie", c.point("alpha", 15, 0), 12)],
               "Alpha hovers over its pad at 20 m; charlie is 15 m north of it at 12 m; bravo stayed down."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("placement", "dev", "place20-af-charlie-east-of-alpha", three,
               "Laat alpha opstyg tot 12 meter en vlieg hom 20 meter suid. Stuur daarna charlie na 'n punt 10 "
               "meter oos van alpha, op dieselfde hoogte, en laat albei daar hang. bravo bly op die grond.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", -20, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", -20, 10), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 12), _move("alpha", -20, 0), _go("charlie", c.point("alpha", -20, 10), 12)],
               "alpha hang 20 m suid van sy plek op 12 m; charlie hang 10 m oos van alpha op dieselfde hoogte."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("placement", "dev", "place20-sl-charlie-over-alpha-pad-above-bravo", three,
               "Dvigni bravo na 15 metrov in ga premakni 20 metrov proti zahodu. Potem postavi charlie natanko nad "
               "vzletno mesto drona alpha, 5 metrov višje od bravo. alpha naj ostane na tleh.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 0, -20), alt=15), airborne_at(ev, "bravo", 15),
                                  at(ev, "charlie", *_home(c, "alpha"), alt=20), airborne_at(ev, "charlie", 20),
                                  never_armed(ev, "alpha")),
               lambda c: [_takeoff("bravo", 15), _move("bravo", 0, -20), _go("charlie", _home(c, "alpha"), 20)],
               "bravo lebdi 20 m zahodno na 15 m; charlie lebdi nad vzletnim mestom drona alpha na 20 m; alpha je "
               "ostal na tleh."),
        # language
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("language", "dev", "lang20-my-alpha-west-land", ("alpha",),
               "alpha ကို မီတာ 10 အမြင့်အထိ ပျံတက်စေပြီး အနောက်ဘက်သို့ မီတာ 25 ပျံသွားစေပါ။ ထို့နောက် "
               "အဲဒီနေရာမှာပဲ ဆင်းသက်စေပါ။",
               lambda c, ev: _all(reached_alt(ev, "alpha", 10), at(ev, "alpha", *c.point("alpha", 0, -25)),
                                  landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 10), _move("alpha", 0, -25), _land("alpha")],
               "alpha သည် အနောက်ဘက်သို့ မီတာ 25 ပျံသွားပြီး အဲဒီနေရာမှာ ဆင်းသက်ခဲ့သည်။"),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("language", "dev", "lang20-yo-bravo-north-east-hover", ("bravo",),
               "Gbé bravo sókè dé mítà 15, kí o fò ó lọ sí àríwá ní mítà 20, lẹ́yìn náà kí o tún fò ó lọ sí "
               "ìlà-oòrùn ní mítà 10, kí o sì jẹ́ kí ó dúró lójú òfuurufú níbẹ̀.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 20, 0)], alt=15),
                                  at(ev, "bravo", *c.point("bravo", 20, 10), alt=15), airborne_at(ev, "bravo", 15)),
               [_takeoff("bravo", 15), _move("bravo", 20, 0), _move("bravo", 0, 10)],
               "bravo wà lójú òfuurufú ní mítà 20 sí àríwá àti mítà 10 sí ìlà-oòrùn, ní gíga mítà 15."),
        # moved to dev on 2026-12-05, twentieth round: measured on both models, its failures seen
        _entry("language", "dev", "lang20-so-charlie-east-north-land", ("charlie",),
               "Kor u qaad charlie ilaa 12 mitir, u dir 20 mitir dhanka bari, kadibna 20 mitir dhanka waqooyi, "
               "halkaasna ku soo deji.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, 20)], alt=12),
                                  at(ev, "charlie", *c.point("charlie", 20, 20)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), _move("charlie", 0, 20), _move("charlie", 20, 0), _land("charlie")],
               "charlie wuxuu u duulay 20 mitir bari iyo 20 mitir waqooyi, halkaasna wuu ku degay."),
    ]  # fmt: skip


def _twenty_first_test_half() -> list[CorpusEntry]:
    """The test half written on 2026-12-05 (twenty-first round), before any model ran on it, by a writer who
    did not read the host's word lists, rules or prompts: 3 a class; 22 of the 33 outside ``language`` in
    other languages than English, one each (Arabic, Chinese, Czech, Dutch, French, German, Hebrew, Hindi,
    Indonesian, Italian, Japanese, Korean, Persian, Polish, Portuguese, Romanian, Russian, Spanish, Swedish,
    Turkish, Ukrainian, Vietnamese: none of them new), the ``language`` class's 3 in Hausa, Kurdish
    (Kurmanji) and Odia (all three new to the corpus, and Odia script with them)."""
    three = DRONES
    d10, d15, d30 = (x / math.sqrt(2) for x in (10, 15, 30))
    furlong = 220 * YD
    # a parallelogram: 20 m east, 15 m north-east, 20 m west, and back south-west to the start
    parallelogram = [(0.0, 20.0), (d15, d15), (0.0, -20.0), (-d15, -d15)]
    # a 15 m square, the first side due north, turning right, 3 m higher at the end of each side
    square = [(15.0, 0.0), (0.0, 15.0), (-15.0, 0.0), (0.0, -15.0)]
    # a regular hexagon whose corners lie 12 m from the pad: from the corner due north, clockwise
    hexagon = _polygon_legs(6, 12.0, 120.0, right=True)
    hex_corners = [(12.0, 0.0), *((12.0 + n, e) for n, e in _corners(hexagon)[:5])]
    # five passes 200 m long, 300 m apart eastward: the step to the fifth (1200 m east) is past the limit
    survey = [(200.0, 0.0), (0.0, 300.0), (-200.0, 0.0), (0.0, 300.0), (200.0, 0.0), (0.0, 300.0),
              (-200.0, 0.0), (0.0, 300.0)]  # fmt: skip

    def first_hop(ev: Evidence, d: str, alt: float, point: tuple[float, float]) -> Check:
        """The drone's first flight peaked at ``alt`` (±tolerance) and ended on the ground at ``point``: a
        touchdown before what came next (judged on the final state), not a climb straight on to the next
        height."""
        track = ev.track.get(d, [])
        off = next((i for i, s in enumerate(track) if not s.landed), None)
        down = None if off is None else next((i for i in range(off, len(track)) if track[i].landed), None)
        ok = False
        if off is not None and down is not None:
            peak = max(s.alt_rel_m for s in track[off:down])
            ok = abs(peak - alt) <= ALT_TOL_M and (
                horizontal_distance_m(track[down].lat, track[down].lon, *point) <= HORIZONTAL_TOL_M
            )
        return Check(ok, f"{d} {'touched down' if ok else 'did not touch down'} after climbing to {alt:g} m")

    def rose_after(ev: Evidence, d: str, others: tuple[str, ...], alt: float) -> Check:
        """``d`` first reached ``alt`` (less the tolerance) only after each of ``others`` was last off the
        ground (the tracks are sampled together)."""
        track = ev.track.get(d, [])
        rise = next((i for i, s in enumerate(track) if s.alt_rel_m >= alt - ALT_TOL_M), None)
        last_up = max(
            (i for o in others for i, s in enumerate(ev.track.get(o, [])) if not s.landed), default=-1
        )
        ok = rise is not None and rise > last_up
        return Check(ok, f"{d} {'rose' if ok else 'did not rise'} only once {' and '.join(others)} were down")

    def set_down_in_order(ev: Evidence, d: str, points: list[tuple[float, float]]) -> Check:
        """The drone was on the ground at each of ``points`` in turn: landings out there, in order."""
        i = 0
        for s in ev.track.get(d, []):
            if (
                i < len(points)
                and s.landed
                and (horizontal_distance_m(s.lat, s.lon, *points[i]) <= HORIZONTAL_TOL_M)
            ):
                i += 1
        return Check(i == len(points), f"{d} set down at {i}/{len(points)} stops in order")

    def kept_clear(ev: Evidence, d: str, point: tuple[float, float]) -> Check:
        """The drone never came over ``point``: a corner the straight way does not turn."""
        track = ev.track.get(d, [])
        near = any(horizontal_distance_m(s.lat, s.lon, *point) <= HORIZONTAL_TOL_M for s in track)
        return Check(not near, f"{d} {'turned a corner' if near else 'flew straight'}")

    def apart_in_air(ev: Evidence, drones: tuple[str, ...], least: float) -> Check:
        """No two drones in the air came closer than ``least`` metres (the tracks are sampled together)."""
        tracks = [ev.track.get(d, []) for d in drones]
        near = min((horizontal_distance_m(p.lat, p.lon, q.lat, q.lon)
                    for samples in zip(*tracks, strict=False)
                    for j, p in enumerate(samples) for q in samples[j + 1 :]
                    if not p.landed and not q.landed), default=math.inf)  # fmt: skip
        return Check(near >= least, f"the drones in the air came {near:.1f} m close (at least {least:g})")

    def east_of_alpha_north_of_bravo(c: MissionContext) -> tuple[float, float]:
        """Level with alpha (25 m north of its pad) and in line with bravo (20 m east of its own)."""
        return c.point("alpha", 25, 0)[0], c.point("bravo", 0, 20)[1]

    def tower(c: MissionContext) -> tuple[float, float]:
        """The water tower, 30 m north-west of alpha's pad."""
        return c.point("alpha", d30, -d30)

    return [
        # single
        _entry("single", "test", "single21-bravo-touch-and-go", ("bravo",),
               "Give bravo a touch-and-go on its own pad: up to 8 m, straight back down until it touches the "
               "pad, then straight back up to 12 m, and hold it there.",
               lambda c, ev: _all(first_hop(ev, "bravo", 8, _home(c, "bravo")),
                                  at(ev, "bravo", *_home(c, "bravo"), alt=12), airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 8), _land("bravo"), _takeoff("bravo", 12)],
               "Bravo went up to 8 m, touched down on its pad and now holds 12 m over it."),
        _entry("single", "test", "single21-de-charlie-climb-five-seconds", ("charlie",),
               "Lass charlie senkrecht über seinem Startplatz fünf Sekunden lang mit 3 Metern pro Sekunde "
               "steigen, dann soll er anhalten und dort in der Luft stehen bleiben.",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=15), airborne_at(ev, "charlie", 15)),
               [_takeoff("charlie", 15)],
               "charlie schwebt 15 m über seinem Startplatz: 5 s mit 3 m/s."),
        _entry("single", "test", "single21-ja-alpha-bump-and-back", ("alpha",),
               "alpha を離陸地点の真上で 12 メートルまで上げて、そこからさらに 6 メートル上昇させたあと、元の 12 "
               "メートルに戻してホバリングさせて。",
               lambda c, ev: _all(rose_to(ev, "alpha", 18), at(ev, "alpha", *_home(c, "alpha"), alt=12),
                                  airborne_at(ev, "alpha", 12)),
               [_takeoff("alpha", 12), _move("alpha", up=6), _move("alpha", up=-6)],
               "alpha は 18 m まで上がってから 12 m に戻り、離陸地点の真上でホバリングしています。"),
        # multi
        _entry("multi", "test", "multi21-rotate-pads-east", three,
               "Rotate the three drones one pad to the east: each goes over the pad of its eastern neighbour, and "
               "charlie, the easternmost, wraps round to alpha's. Keep them at different heights so they don't "
               "meet: alpha 10 m, bravo 14 m, charlie 18 m. Leave them hovering.",
               lambda c, ev: _all(*(_all(at(ev, d, *_home(c, pad), alt=h), airborne_at(ev, d, h))
                                    for d, pad, h in (("alpha", "bravo", 10), ("bravo", "charlie", 14),
                                                      ("charlie", "alpha", 18)))),
               # (each up over its own pad first: a drone climbing from a pad another hovers over would meet it)
               lambda c: [_takeoff("alpha", 10), _takeoff("bravo", 14), _takeoff("charlie", 18),
                          _go("alpha", _home(c, "bravo"), 10), _go("bravo", _home(c, "charlie"), 14),
                          _go("charlie", _home(c, "alpha"), 18)],
               "Alpha hovers over bravo's pad at 10 m, bravo over charlie's at 14 m, charlie over alpha's at 18 m."),
        _entry("multi", "test", "multi21-es-one-goes-on-two-come-back", three,
               "Sube los tres drones a 10 metros y llévalos 15 metros hacia el norte, cada uno desde su "
               "plataforma. Después, bravo sigue otros 15 metros hacia el norte y se queda allí en el aire; alpha "
               "y charlie vuelven a sus plataformas y aterrizan.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 30, 0), alt=10), airborne_at(ev, "bravo", 10),
                                  *(_all(visited(ev, d, [c.point(d, 15, 0)], alt=10), at(ev, d, *_home(c, d)),
                                         landed_disarmed(ev, d)) for d in ("alpha", "charlie"))),
               [*(_move(d, 15, 0, alt=10) for d in three), _move("bravo", 15, 0), _rtl("alpha"), _rtl("charlie")],
               "bravo está 30 m al norte de su plataforma a 10 m; alpha y charlie volvieron a las suyas y "
               "aterrizaron."),
        _entry("multi", "test", "multi21-pl-charlie-after-both-land", three,
               "Najpierw alpha i bravo: start na 10 metrów nad swoimi lądowiskami i od razu z powrotem na ziemię. "
               "Dopiero kiedy oba będą już na ziemi, charlie wznosi się na 15 metrów i zostaje w powietrzu.",
               lambda c, ev: _all(*(_all(reached_alt(ev, d, 10), at(ev, d, *_home(c, d)), landed_disarmed(ev, d))
                                    for d in ("alpha", "bravo")),
                                  rose_after(ev, "charlie", ("alpha", "bravo"), 15),
                                  at(ev, "charlie", *_home(c, "charlie"), alt=15), airborne_at(ev, "charlie", 15)),
               [_takeoff("alpha", 10), _takeoff("bravo", 10), _land("alpha"), _land("bravo"), _takeoff("charlie", 15)],
               "alpha i bravo wzniosły się na 10 m i wylądowały; dopiero potem charlie wzniósł się na 15 m i wisi "
               "nad swoim lądowiskiem."),
        # compound
        _entry("compound", "test", "compound21-alpha-courier-run", ("alpha",),
               "Courier run for alpha at 10 m: fly 20 m east and land there to pick up a parcel, take off again "
               "and fly to the spot 20 m north of its pad, land there to drop it off, then take off once more, "
               "come home and land on the pad.",
               lambda c, ev: _all(set_down_in_order(ev, "alpha", [c.point("alpha", 0, 20), c.point("alpha", 20, 0)]),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               # the pad by its position: the autopilot's home walks to where it last armed, so a return
               # to launch after the second takeoff would land at the drop
               lambda c: [_takeoff("alpha", 10), _move("alpha", 0, 20), _land("alpha"), _takeoff("alpha", 10),
                          _move("alpha", 20, -20), _land("alpha"), _takeoff("alpha", 10),
                          _go("alpha", _home(c, "alpha"), 10), _land("alpha")],
               "Alpha landed 20 m east for the pick-up, then 20 m north of its pad for the drop, and came home."),
        _entry("compound", "test", "compound21-it-legs-from-first", ("bravo",),
               "Porta bravo a 12 metri. Primo tratto: 15 metri verso est. Secondo tratto: verso nord, lungo il "
               "doppio del primo. Terzo tratto: verso ovest, lungo quanto il primo. Alla fine fallo atterrare lì.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, 15), c.point("bravo", 30, 15)], alt=12),
                                  at(ev, "bravo", *c.point("bravo", 30, 0)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", 0, 15), _move("bravo", 30, 0), _move("bravo", 0, -15),
                _land("bravo")],
               "bravo ha volato 15 m a est, 30 m a nord e 15 m a ovest, ed è atterrato 30 m a nord della sua "
               "piazzola."),
        _entry("compound", "test", "compound21-tr-charlie-back-to-first-point", ("charlie",),
               "charlie'yi kalkış yerinin 15 metre kuzeyine 8 metre yükseklikte götür, sonra 15 metre daha kuzeye "
               "git ve orada 16 metreye çık. Ardından ilk noktaya 8 metreye inerek geri dön ve oraya indir.",
               lambda c, ev: _all(passed(ev, "charlie", [(c.point("charlie", 15, 0), 8), (c.point("charlie", 30, 0), 16),
                                                         (c.point("charlie", 15, 0), 8)]),
                                  at(ev, "charlie", *c.point("charlie", 15, 0)), landed_disarmed(ev, "charlie")),
               [_move("charlie", 15, 0, alt=8), _move("charlie", 15, 0), _move("charlie", alt=16),
                _move("charlie", -15, 0, alt=8), _land("charlie")],
               "charlie 8 m'de 15 m kuzeye, oradan 30 m'ye gidip 16 m'ye çıktı, 8 m'ye inerek ilk noktaya döndü ve "
               "indi."),
        # conditional
        _entry("conditional", "test", "cond21-closest-pair-flies", three,
               "Read all three batteries. The two drones whose charges are closest to each other fly 15 m east of "
               "their own pads at 12 m and hover there; the odd one out stays on the ground.",
               lambda c, ev: _all(*(_all(at(ev, d, *c.point(d, 0, 15), alt=12), airborne_at(ev, d, 12))
                                    for d in ("bravo", "charlie")),
                                  never_armed(ev, "alpha")),
               [("fleet_status", {}), _move("charlie", 0, 15, alt=12), _move("bravo", 0, 15, alt=12)],
               "Bravo (48 %) and charlie (53 %) are the closest pair, 5 points apart: both hover 15 m east of their "
               "pads at 12 m; alpha (80 %) stayed down.",
               battery={"alpha": 80.0, "bravo": 48.0, "charlie": 53.0}),
        _entry("conditional", "test", "cond21-fr-bravo-ratio-to-charlie", three,
               "Compare la batterie de bravo à celle de charlie. Si bravo a au moins une fois et demie la charge "
               "de charlie, monte bravo à 20 mètres au-dessus de son aire ; sinon, monte-le seulement à 10 mètres. "
               "Dans les deux cas il reste en vol stationnaire, et les deux autres restent au sol.",
               lambda c, ev: _all(at(ev, "bravo", *_home(c, "bravo"), alt=20), airborne_at(ev, "bravo", 20),
                                  never_armed(ev, "alpha"), never_armed(ev, "charlie")),
               [("fleet_status", {}), _takeoff("bravo", 20)],
               "bravo (66 %) a plus d'une fois et demie la charge de charlie (40 %) : il est en vol stationnaire à "
               "20 m au-dessus de son aire.",
               battery={"bravo": 66.0, "charlie": 40.0}),
        _entry("conditional", "test", "cond21-zh-charlie-only-if-both", three,
               "只有当 charlie 的电量高于 55%，并且也高于 bravo 的时候，才让 charlie 升到 10 米、向西飞 20 米并在那里"
               "悬停；否则这件事由 alpha 来做。bravo 留在地面上。",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 0, -20), alt=10), airborne_at(ev, "alpha", 10),
                                  never_armed(ev, "bravo"), never_armed(ev, "charlie")),
               [("fleet_status", {}), _move("alpha", 0, -20, alt=10)],
               "charlie（60%）虽高于 55%，但低于 bravo（64%），所以由 alpha 升到 10 米，在起飞点以西 20 米悬停。",
               battery={"alpha": 70.0, "bravo": 64.0, "charlie": 60.0}),
        # formation
        _entry("formation", "test", "form21-column-from-north-end", three,
               "Put the three in a north–south column at 15 m, 8 m apart, starting from a point 10 m north of the "
               "middle of their pads: the first drone right over that point, the other two trailing south of it. "
               "Hold them there.",
               # the column's centre is 8 m south of its head: 2 m north of the pads' middle
               lambda c, ev: _all(formation_at(c, ev, three, 15, 8, 2, 0), farthest_apart(ev, three, 16),
                                  row_along(ev, three, 0)),
               # (no heading in the typed plan, and the gateway faces a formation where it travels: each drone
               # flies to its slot)
               lambda c: [_go(d, slot(c, three, n, 0), 15) for d, n in (("alpha", 10), ("bravo", 2), ("charlie", -6))],
               "The three hover in a column at 15 m, 8 m apart, its head 10 m north of the pads' middle."),
        _entry("formation", "test", "form21-nl-row-square-to-pads", three,
               "Zet de drie drones op een rij die haaks staat op de lijn van hun startplaatsen, met 7 meter tussen "
               "buren, op 10 meter hoogte, en met het midden van de rij 15 meter ten oosten van de middelste "
               "startplaats. Laat ze daar hangen.",
               lambda c, ev: _all(formation_at(c, ev, three, 10, 7, 0, 15), farthest_apart(ev, three, 14),
                                  row_along(ev, three, 0)),
               # (the pads run west to east: the row at right angles runs north-south; each drone to its slot)
               lambda c: [_go(d, slot(c, three, n, 15), 10) for d, n in (("charlie", 7), ("bravo", 0), ("alpha", -7))],
               "De drie hangen op 10 m in een rij van noord naar zuid, 7 m uit elkaar, 15 m ten oosten van de "
               "middelste startplaats."),
        _entry("formation", "test", "form21-ru-join-charlie-in-middle", three,
               "Подними charlie на 12 метров и отведи его на 25 метров к северу. Потом выстрой alpha и bravo в одну "
               "линию с ним с запада на восток, на той же высоте, по 9 метров между соседями, так чтобы charlie "
               "оказался посередине. Пусть все трое висят там.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 25, 0), alt=12),
                                  formation_around(ev, three, 12, 9, c.point("charlie", 25, 0)),
                                  farthest_apart(ev, three, 18), row_along(ev, three, 90)),
               lambda c: [_takeoff("charlie", 12), _move("charlie", 25, 0),
                          _go("bravo", offset_position(*c.point("charlie", 25, 0), 0, 9), 12),
                          _go("alpha", offset_position(*c.point("charlie", 25, 0), 0, -9), 12)],
               "charlie висит в 25 м к северу от своей площадки на 12 м, alpha и bravo по обе стороны от него, в 9 "
               "м, на одной линии с запада на восток."),
        # relative
        _entry("relative", "test", "rel21-alpha-one-straight-line", ("alpha",),
               "Take alpha up to 10 m. It has to end up 16 m north and 30 m east of where it is, but fly it there "
               "in one straight line, not east first and then north or the other way round, and hold it there.",
               lambda c, ev: _all(kept_clear(ev, "alpha", c.point("alpha", 0, 30)),
                                  kept_clear(ev, "alpha", c.point("alpha", 16, 0)),
                                  at(ev, "alpha", *c.point("alpha", 16, 30), alt=10), airborne_at(ev, "alpha", 10)),
               # one straight line to the point (a plan's two legs are two moves: a corner)
               lambda c: [_takeoff("alpha", 10), _go("alpha", c.point("alpha", 16, 30), 10)],
               "Alpha flew straight to the point 16 m north and 30 m east of its pad and holds there at 10 m."),
        _entry("relative", "test", "rel21-sv-bravo-lower-by-percent", ("bravo",),
               "Ta upp bravo till 20 meter. Flytta den sedan 15 meter västerut och sänk den samtidigt med 40 "
               "procent av höjden. Låt den sväva kvar där.",
               lambda c, ev: _all(rose_to(ev, "bravo", 20), at(ev, "bravo", *c.point("bravo", 0, -15), alt=12),
                                  airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 20), _move("bravo", 0, -15, up=-8)],
               "bravo svävar 15 m väster om sin startplats på 12 m: 20 m sänkt med 40 procent."),
        _entry("relative", "test", "rel21-vi-charlie-three-times-as-far", ("charlie",),
               "Đưa charlie lên độ cao 10 mét rồi bay 10 mét về hướng tây nam. Sau đó cho nó bay tiếp theo đúng "
               "hướng đó cho đến khi khoảng cách từ nó tới điểm cất cánh gấp ba lần bây giờ, rồi giữ nó lơ lửng ở "
               "đó.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -d10, -d10)], alt=10),
                                  at(ev, "charlie", *c.point("charlie", -3 * d10, -3 * d10), alt=10),
                                  airborne_at(ev, "charlie", 10)),
               [_takeoff("charlie", 10), _move("charlie", -d10, -d10), _move("charlie", -2 * d10, -2 * d10)],
               "charlie đang lơ lửng cách điểm cất cánh 30 m về phía tây nam, ở độ cao 10 m."),
        # question
        _entry("question", "test", "ask21-average-after-fresh-battery", three,
               "Charlie's battery is being swapped for a fully charged one before the next job. Once that's done, "
               "what will the fleet's average charge be? Just tell me; nothing takes off.",
               # the typed plan reads, it does not compute: the average, or the two readings it keeps
               lambda c, ev: _all(_any(answer_mentions_number(ev, 205 / 3, 0.5),
                                       _all(answer_mentions_number(ev, 61, 1), answer_mentions_number(ev, 44, 1))),
                                  nobody_armed(ev)),
               [("fleet_status", {})],
               "68.3 %: alpha 61 %, bravo 44 % and charlie's fresh 100 % (its old battery has 23 %).",
               battery={"alpha": 61.0, "bravo": 44.0, "charlie": 23.0}),
        _entry("question", "test", "ask21-hi-minutes-to-full", three,
               "अगर चार्जर पर हर ड्रोन 2 % प्रति मिनट की दर से चार्ज होता है, तो जिस ड्रोन की बैटरी सबसे कम है उसे "
               "100 % तक पहुँचने में कितने मिनट लगेंगे? वह कौन-सा ड्रोन है, यह भी बताओ, लेकिन किसी ड्रोन को मत उड़ाओ।",
               # the typed plan reads, it does not compute: the minutes, or the reading they come from
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"),
                                  _any(answer_mentions_number(ev, 27, 0.5), answer_mentions_number(ev, 46, 1)),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "bravo (46 %): 100 % तक 54 अंक, 2 % प्रति मिनट से 27 मिनट। alpha 72 %, charlie 58 %।",
               battery={"alpha": 72.0, "bravo": 46.0, "charlie": 58.0}),
        _entry("question", "test", "ask21-fa-pair-sums-to-hundred", three,
               "شارژ کدام دو پهپاد روی هم دقیقاً 100 درصد می‌شود؟ درصد هر سه را هم بگو، ولی هیچ پهپادی را پرواز نده.",
               lambda c, ev: _all(answer_says(ev, r"\balpha\b", "alpha"), answer_says(ev, r"\bcharlie\b", "charlie"),
                                  answer_mentions_number(ev, 37, 1), answer_mentions_number(ev, 63, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "alpha (37 %) و charlie (63 %) روی هم 100 % می‌شوند؛ bravo 55 % دارد.",
               battery={"alpha": 37.0, "bravo": 55.0, "charlie": 63.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude, 5 m the least separation a formation keeps)
        _entry("refusal", "test", "refuse21-bravo-tower-storeys", ("bravo",),
               "Bravo needs to look over the roof of the 40-storey tower next door, about 3.5 m a storey. Take it "
               "straight up over its pad to the height of that roof and hold it there.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "bravo", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("bravo", 140)],
               "Refused: 40 storeys of 3.5 m is 140 m, above the 120 m altitude limit."),
        _entry("refusal", "test", "refuse21-ro-charlie-survey-past-limit", ("charlie",),
               "Ridică charlie la 40 de metri și scanează câmpul: cinci treceri de câte 200 de metri, prima spre "
               "nord, următoarea înapoi spre sud și tot așa, la 300 de metri una de alta, mutându-te spre est între "
               "treceri.",
               lambda c, ev: _all(refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "charlie", c.max_distance_m), answer_reports_refusal(ev)),
               [_takeoff("charlie", 40), *_legs("charlie", survey)],
               "charlie a zburat primele patru treceri; mutarea la 1200 m spre est pentru a cincea a fost refuzată: "
               "depășește limita de 1000 m de la punctul de decolare."),
        _entry("refusal", "test", "refuse21-id-row-twelve-feet", three,
               "Jajarkan ketiga drone berdampingan dari barat ke timur pada ketinggian 15 meter, tepat di atas "
               "tempat mereka sekarang, dengan jarak 12 kaki antara drone yang bersebelahan.",
               lambda c, ev: _all(refusal_seen(ev, "separation"), apart_in_air(ev, three, 4),
                                  answer_reports_refusal(ev)),
               [_formation(three, "line", 15, 12 * FT)],
               "Ditolak: 12 kaki (3,7 m) di bawah jarak minimum 5 m antar drone."),
        # units
        _entry("units", "test", "units21-charlie-furlong", ("charlie",),
               "The far marker of the gallops is a furlong (220 yards) due north of charlie's pad. Fly charlie "
               "there at 50 ft and land it beside the marker.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", furlong, 0)], alt=50 * FT),
                                  at(ev, "charlie", *c.point("charlie", furlong, 0)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 50 * FT), _move("charlie", furlong, 0), _land("charlie")],
               "Charlie flew a furlong (201 m) north at 50 ft (15.2 m) and landed by the marker."),
        _entry("units", "test", "units21-cs-bravo-decimetres-km", ("bravo",),
               "Vzlétni s dronem bravo do výšky 120 decimetrů, přeleť s ním 0,035 kilometru na jih a tam přistaň.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", -35, 0)], alt=12),
                                  at(ev, "bravo", *c.point("bravo", -35, 0)), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), _move("bravo", -35, 0), _land("bravo")],
               "bravo přeletěl ve 12 m 35 m na jih a tam přistál."),
        _entry("units", "test", "units21-ko-alpha-feet-yards-climb", ("alpha",),
               "alpha를 45피트 높이로 띄운 다음 동쪽으로 100야드 이동시키고, 거기서 15피트 더 올려서 그 자리에 떠 있게 "
               "해 줘.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 100 * YD)], alt=45 * FT),
                                  at(ev, "alpha", *c.point("alpha", 0, 100 * YD), alt=60 * FT),
                                  airborne_at(ev, "alpha", 60 * FT)),
               [_takeoff("alpha", 45 * FT), _move("alpha", 0, 100 * YD), _move("alpha", alt=60 * FT)],
               "alpha는 이륙 지점에서 동쪽으로 100야드(91.4 m) 떨어진 곳, 60피트(18.3 m) 높이에 떠 있습니다."),
        # pattern
        _entry("pattern", "test", "pattern21-bravo-parallelogram", ("bravo",),
               "Fly bravo round a parallelogram at 12 m: 20 m east, then 15 m north-east, then 20 m west, then "
               "straight back to where it started, and land it there.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(parallelogram)[:3]]),
                                  at(ev, "bravo", *_home(c, "bravo")), landed_disarmed(ev, "bravo")),
               [_takeoff("bravo", 12), *_legs("bravo", parallelogram), _land("bravo")],
               "Bravo flew the parallelogram (20 m east, 15 m north-east, 20 m west, back) and landed on its pad."),
        _entry("pattern", "test", "pattern21-he-alpha-climbing-square", ("alpha",),
               "הטס את alpha בריבוע שאורך כל צלע שלו 15 מטר: הצלע הראשונה צפונה, ובכל פינה פנה ימינה. התחל בגובה 10 "
               "מטר ועלה 3 מטר לאורך כל צלע. בסוף הריבוע השאר אותו מרחף מעל נקודת ההמראה.",
               lambda c, ev: _all(passed(ev, "alpha", [(c.point("alpha", n, e), 10 + 3 * (i + 1))
                                                       for i, (n, e) in enumerate(_corners(square)[:3])]),
                                  at(ev, "alpha", *_home(c, "alpha"), alt=22), airborne_at(ev, "alpha", 22)),
               [_takeoff("alpha", 10), *(_move("alpha", n, e, up=3) for n, e in square)],
               "alpha טס ריבוע של 15 מ' ועלה 3 מ' בכל צלע: הוא מרחף עכשיו ב-22 מ' מעל נקודת ההמראה."),
        _entry("pattern", "test", "pattern21-ar-charlie-hexagon-round-pad", ("charlie",),
               "ارفع charlie إلى ارتفاع 12 مترًا، ثم طِر به في مسار سداسي منتظم تقع رؤوسه على دائرة نصف قطرها 12 "
               "مترًا حول منصة إقلاعه. ابدأ من الرأس الواقع شمال المنصة مباشرة وسِر في اتجاه عقارب الساعة، وبعد "
               "إكمال الدورة أعده إلى المنصة وأنزله عليها.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in hex_corners]),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 12), _move("charlie", 12, 0), *_legs("charlie", hexagon), _move("charlie", -12, 0),
                _land("charlie")],
               "طار charlie في مسار سداسي رؤوسه على بعد 12 m من منصته، بدءًا من الشمال وفي اتجاه عقارب الساعة، ثم "
               "هبط على المنصة."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # charlie from another drone or a place, so that a drone placed from itself misses)
        _entry("placement", "test", "place21-charlie-opposite-alpha-pad", three,
               "Alpha goes up to 12 m and 20 m north of its pad. Put charlie at the same height on the opposite "
               "side of alpha's pad, just as far from it, and leave both hovering; bravo stays on the ground.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 20, 0), alt=12), airborne_at(ev, "alpha", 12),
                                  at(ev, "charlie", *c.point("alpha", -20, 0), alt=12), airborne_at(ev, "charlie", 12),
                                  never_armed(ev, "bravo")),
               lambda c: [_move("alpha", 20, 0, alt=12), _go("charlie", c.point("alpha", -20, 0), 12)],
               "Alpha hovers 20 m north of its pad and charlie 20 m south of it, both at 12 m; bravo stayed down."),
        _entry("placement", "test", "place21-pt-charlie-east-of-alpha-north-of-bravo", three,
               "Sobe o alpha a 15 m e leva-o 25 m para norte; sobe o bravo a 15 m e leva-o 20 m para leste. Depois "
               "põe o charlie, à mesma altura, no ponto que fica exatamente a leste do alpha e a norte do bravo, e "
               "deixa os três a pairar.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 25, 0), alt=15), airborne_at(ev, "alpha", 15),
                                  at(ev, "bravo", *c.point("bravo", 0, 20), alt=15), airborne_at(ev, "bravo", 15),
                                  at(ev, "charlie", *east_of_alpha_north_of_bravo(c), alt=15),
                                  airborne_at(ev, "charlie", 15)),
               lambda c: [_move("alpha", 25, 0, alt=15), _move("bravo", 0, 20, alt=15),
                          _go("charlie", east_of_alpha_north_of_bravo(c), 15)],
               "O alpha paira 25 m a norte do seu ponto, o bravo 20 m a leste do seu, e o charlie a leste do alpha "
               "e a norte do bravo, todos a 15 m."),
        _entry("placement", "test", "place21-uk-charlie-lands-east-of-tower", three,
               "Водонапірна башта стоїть за 30 метрів на північний захід від майданчика alpha. Підніми charlie на "
               "20 метрів, проведи його над баштою, а потім посади за 8 метрів на схід від неї. alpha і bravo "
               "залишаються на землі.",
               lambda c, ev: _all(visited(ev, "charlie", [tower(c)], alt=20),
                                  at(ev, "charlie", *offset_position(*tower(c), 0, 8)), landed_disarmed(ev, "charlie"),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               lambda c: [_takeoff("charlie", 20), _go("charlie", tower(c), 20),
                          _go("charlie", offset_position(*tower(c), 0, 8), 20), _land("charlie")],
               "charlie пролетів над баштою на 20 м і сів за 8 м на схід від неї; alpha і bravo на землі."),
        # language
        _entry("language", "test", "lang21-ha-bravo-west-climb-hover", ("bravo",),
               "Ka tayar da bravo zuwa tsayin mita 12, ka kai shi mita 20 zuwa yamma, sannan ka ƙara masa tsayi "
               "zuwa mita 18 ka bar shi yana shawagi a can.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, -20)], alt=12),
                                  at(ev, "bravo", *c.point("bravo", 0, -20), alt=18), airborne_at(ev, "bravo", 18)),
               [_takeoff("bravo", 12), _move("bravo", 0, -20), _move("bravo", alt=18)],
               "bravo yana shawagi a mita 18, mita 20 yamma da inda ya tashi."),
        _entry("language", "test", "lang21-ku-charlie-south-east-land", ("charlie",),
               "Charlie 10 metreyan bilind bike, paşê 20 metreyan ber bi başûr ve bibe, dû re 15 metreyan ber bi "
               "rojhilat ve bifirîne û li wir deyne ser erdê.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -20, 0)], alt=10),
                                  at(ev, "charlie", *c.point("charlie", -20, 15)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", -20, 0), _move("charlie", 0, 15), _land("charlie")],
               "charlie 20 m ber bi başûr û 15 m ber bi rojhilat ve firiya û li wir daket."),
        _entry("language", "test", "lang21-or-alpha-north-home", ("alpha",),
               "alpha କୁ 15 ମିଟର ଉଚ୍ଚତାକୁ ଉଠାଅ, ଉତ୍ତର ଦିଗକୁ 30 ମିଟର ଉଡ଼ାଇ ନିଅ, ତା'ପରେ ଯେଉଁଠାରୁ ଉଡ଼ିଥିଲା ସେଠାକୁ ଫେରାଇ "
               "ଆଣି ଅବତରଣ କରାଅ।",
               # the return home climbs to its own height: the leg north is checked at 15 m instead
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 30, 0)], alt=15),
                                  at(ev, "alpha", *_home(c, "alpha")), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 15), _move("alpha", 30, 0), _rtl("alpha")],
               "alpha ଉତ୍ତରକୁ 30 m ଉଡ଼ି ଫେରି ଆସି ଯେଉଁଠାରୁ ଉଡ଼ିଥିଲା ସେଠାରେ ଅବତରଣ କଲା।"),
    ]  # fmt: skip


def _twenty_second_test_half() -> list[CorpusEntry]:
    """The test half written on 2026-12-06 (twenty-second round), before any model ran on it, by a session
    that did not read the host (its word lists, rules, prompts, examples or pool, nor docs/agent.md): 3 a
    class; 22 of the 33 outside ``language`` in other languages than English, one each (Armenian, Assamese,
    Asturian, Cantonese, Faroese, Georgian, Greek, Japanese, Kazakh, Korean, Low German, Malayalam, Maori,
    Occitan, Scottish Gaelic, Sundanese, Tatar, Turkmen, Uyghur, West Frisian, Xhosa, Yiddish; fifteen of
    them new to the corpus), the ``language`` class's 3 in Tibetan, Pashto and Malagasy (all three new to
    the corpus, and Tibetan script with them). Not wired into ``corpus()`` until the twenty-first half has
    been measured."""
    three = DRONES
    mile, inch = 1609.344, 0.0254
    d20, d40 = 20 / math.sqrt(2), 40 / math.sqrt(2)
    ring = 10 * math.sqrt(3)  # three drones evenly on a circle of radius 10 m stand this far apart
    # an expanding square: legs of 10, 10, 20, 20 and 30 m, the first north, turning right after each
    expanding = [(10.0, 0.0), (0.0, 10.0), (-20.0, 0.0), (0.0, -20.0), (30.0, 0.0)]
    # four passes 40 m long running east and west, 10 m apart, the first east from the pad, stepping north
    passes = [(0.0, 40.0), (10.0, 0.0), (0.0, -40.0), (10.0, 0.0), (0.0, 40.0), (10.0, 0.0), (0.0, -40.0)]

    def post(c: MissionContext) -> tuple[float, float]:
        """The lamp post 20 m north of alpha's pad."""
        return c.point("alpha", 20, 0)

    def round_post(c: MissionContext) -> list[tuple[float, float]]:
        """The points 10 m south, east, north and west of the post: anticlockwise from the south."""
        return [offset_position(*post(c), n, e) for n, e in ((-10, 0), (0, 10), (10, 0), (0, -10))]

    def v_slots(c: MissionContext) -> list[tuple[float, float]]:
        """The V's point 20 m north of bravo's pad, its wings 10 m behind it (south) and 10 m to each side."""
        apex = c.point("bravo", 20, 0)
        return [apex, offset_position(*apex, -10, -10), offset_position(*apex, -10, 10)]

    def l_slots(c: MissionContext) -> list[tuple[float, float]]:
        """The L's corner 15 m south of the middle of the pads, one arm 10 m north of it, one 10 m west."""
        corner = slot(c, three, -15, 0)
        return [corner, offset_position(*corner, 10, 0), offset_position(*corner, 0, -10)]

    def between(c: MissionContext) -> tuple[float, float]:
        """Halfway between alpha (30 m north of its pad) and bravo (30 m east of its own)."""
        a, b = c.point("alpha", 30, 0), c.point("bravo", 0, 30)
        return (a[0] + b[0]) / 2, (a[1] + b[1]) / 2

    def slots_filled(
        ev: Evidence, drones: tuple[str, ...], points: list[tuple[float, float]], alt: float
    ) -> Check:
        """Each drone airborne at ``alt`` over one of ``points`` (lat, lon), one a point, whichever drone
        takes whichever point."""
        final = [ev.final[d] for d in drones]
        ok = any(all(horizontal_distance_m(t.lat, t.lon, *p) <= HORIZONTAL_TOL_M for t, p in zip(final, perm, strict=True))
                 for perm in itertools.permutations(points))  # fmt: skip
        return _all(Check(ok, f"the drones {'fill' if ok else 'do not fill'} the shape's points"),
                    *(airborne_at(ev, d, alt) for d in drones))  # fmt: skip

    def reversed_landings(ev: Evidence, order: tuple[str, ...], alt: float) -> Check:
        """The drones first reached ``alt`` (less the tolerance) in ``order`` and last touched down in the
        reverse order (the tracks are sampled together)."""
        ups, downs = [], []
        for d in order:
            track = ev.track.get(d, [])
            ups.append(next((i for i, s in enumerate(track) if s.alt_rel_m >= alt - ALT_TOL_M), None))
            downs.append(1 + max((i for i, s in enumerate(track) if not s.landed), default=-2))
        ok = None not in ups and min(downs) > 0
        ok = (
            ok
            and all(a < b for a, b in itertools.pairwise(ups))
            and all(a > b for a, b in itertools.pairwise(downs))
        )
        return Check(bool(ok), f"took off in order and landed in reverse: {'yes' if ok else 'no'}")

    def down_before(ev: Evidence, d: str, stop: tuple[float, float], later: tuple[float, float]) -> Check:
        """The drone was on the ground at ``stop`` before it first came over ``later`` (where it ends
        counts as coming over ``later`` when the track stops short)."""
        track = ev.track.get(d, [])
        near = [
            i for i, s in enumerate(track) if horizontal_distance_m(s.lat, s.lon, *later) <= HORIZONTAL_TOL_M
        ]
        if not near and horizontal_distance_m(ev.final[d].lat, ev.final[d].lon, *later) <= HORIZONTAL_TOL_M:
            near = [len(track)]
        down = [i for i, s in enumerate(track)
                if s.landed and horizontal_distance_m(s.lat, s.lon, *stop) <= HORIZONTAL_TOL_M]  # fmt: skip
        ok = bool(down) and bool(near) and down[0] < near[0]
        return Check(ok, f"{d} {'landed' if ok else 'did not land'} at the stop before going on")

    return [
        # single
        _entry("single", "test", "single22-bravo-halfway-down", ("bravo",),
               "Bravo only: send it straight up to 25 m over its pad, then bring it halfway back down to the "
               "ground and keep it hovering there.",
               lambda c, ev: _all(rose_to(ev, "bravo", 25), at(ev, "bravo", *_home(c, "bravo"), alt=12.5),
                                  airborne_at(ev, "bravo", 12.5)),
               [_takeoff("bravo", 25), _move("bravo", alt=12.5)],
               "Bravo climbed to 25 m and came halfway down: it hovers at 12.5 m over its pad."),
        _entry("single", "test", "single22-yue-charlie-midway-ten-thirty", ("charlie",),
               "charlie 喺佢個起飛點原地升起，升到 10 米同 30 米正中間嘅高度，之後就喺起飛點正上面停喺半空。",
               lambda c, ev: _all(at(ev, "charlie", *_home(c, "charlie"), alt=20), airborne_at(ev, "charlie", 20)),
               [_takeoff("charlie", 20)],
               "charlie 喺起飛點正上面 20 米懸停，啱啱係 10 米同 30 米嘅正中間。"),
        _entry("single", "test", "single22-fy-alpha-sixteen-then-four", ("alpha",),
               "Lit alpha rjocht boppe syn startplak opstige nei 16 meter, lit him dan sakje oant 4 meter boppe "
               "de grûn en hâld him dêr yn 'e loft.",
               lambda c, ev: _all(rose_to(ev, "alpha", 16), at(ev, "alpha", *_home(c, "alpha"), alt=4),
                                  airborne_at(ev, "alpha", 4)),
               [_takeoff("alpha", 16), _move("alpha", alt=4)],
               "alpha gie omheech nei 16 meter en sakke dêrnei oant 4 meter; er hinget boppe syn startplak."),
        # multi
        _entry("multi", "test", "multi22-reverse-landing-order", three,
               "Take off alpha, then bravo, then charlie, one after the other, each to 10 m over its own pad. Then "
               "land them in the reverse order of their takeoffs, each back on its own pad.",
               lambda c, ev: _all(*(_all(reached_alt(ev, d, 10), at(ev, d, *_home(c, d)), landed_disarmed(ev, d))
                                    for d in three),
                                  reversed_landings(ev, three, 10)),
               [_takeoff("alpha", 10), _takeoff("bravo", 10), _takeoff("charlie", 10), _land("charlie"),
                _land("bravo"), _land("alpha")],
               "Alpha, bravo and charlie rose to 10 m in that order and landed in reverse: charlie, bravo, alpha."),
        _entry("multi", "test", "multi22-tk-staggered-north-two-land", three,
               "Üç dronuň hemmesini 12 metre galdyr. Soňra alpha 10 metr, bravo 20 metr, charlie bolsa 30 metr "
               "demirgazyga uçsun. Ondan soň alpha bilen charlie şol ýerde gonsun, bravo bolsa howada asylyp "
               "dursun.",
               lambda c, ev: _all(*(_all(visited(ev, d, [c.point(d, n, 0)], alt=12), at(ev, d, *c.point(d, n, 0)),
                                         landed_disarmed(ev, d)) for d, n in (("alpha", 10), ("charlie", 30))),
                                  at(ev, "bravo", *c.point("bravo", 20, 0), alt=12), airborne_at(ev, "bravo", 12)),
               [_move("alpha", 10, 0, alt=12), _move("bravo", 20, 0, alt=12), _move("charlie", 30, 0, alt=12),
                _land("alpha"), _land("charlie")],
               "alpha 10 m, charlie 30 m demirgazykda gondy; bravo 20 m demirgazykda, 12 m beýiklikde asylyp dur."),
        _entry("multi", "test", "multi22-oc-onto-each-others-pads", three,
               "Fai montar alpha a 10 mètres e bravo a 20 mètres. Alpha se'n va 30 mètres cap a l'oèst e bravo 30 "
               "mètres cap a l'èst. Puèi cadun torna, sens cambiar de nautor, e se pausa sus la plataforma de "
               "l'autre: alpha sus la de bravo, bravo sus la d'alpha. Charlie demòra al sòl.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, -30)], alt=10),
                                  at(ev, "alpha", *_home(c, "bravo")), landed_disarmed(ev, "alpha"),
                                  visited(ev, "bravo", [c.point("bravo", 0, 30)], alt=20),
                                  at(ev, "bravo", *_home(c, "alpha")), landed_disarmed(ev, "bravo"),
                                  never_armed(ev, "charlie")),
               lambda c: [_move("alpha", 0, -30, alt=10), _move("bravo", 0, 30, alt=20),
                          _go("alpha", _home(c, "bravo"), 10), _land("alpha"), _go("bravo", _home(c, "alpha"), 20),
                          _land("bravo")],
               "alpha s'es pausat sus la plataforma de bravo e bravo sus la d'alpha; charlie es demorat al sòl."),
        # compound
        _entry("compound", "test", "compound22-charlie-fence-runs-twice", ("charlie",),
               "Charlie walks the fence south of its pad: at 10 m, out 20 m south and straight back over the pad, "
               "then the same run once more. After the second run, set it down on its pad.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", -20, 0), _home(c, "charlie"),
                                                          c.point("charlie", -20, 0)], alt=10),
                                  at(ev, "charlie", *_home(c, "charlie")), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", -20, 0), _move("charlie", 20, 0), _move("charlie", -20, 0),
                _move("charlie", 20, 0), _land("charlie")],
               "Charlie flew the 20 m run south and back twice at 10 m and landed on its pad."),
        _entry("compound", "test", "compound22-ug-alpha-west-dip-north", ("alpha",),
               "alpha نى 12 مېتىر ئېگىزلىككە كۆتۈرۈپ، غەربكە 20 مېتىر ئۇچۇر. ئۇ يەردە يېقىندىن كۆزىتىش ئۈچۈن 6 "
               "مېتىرغا چۈشۈر، ئاندىن 18 مېتىرغا كۆتۈرۈپ، شىمالغا 20 مېتىر ئۇچۇر ۋە شۇ يەردە لەيلەپ تۇرسۇن.",
               lambda c, ev: _all(passed(ev, "alpha", [(c.point("alpha", 0, -20), 12), (c.point("alpha", 0, -20), 6)]),
                                  at(ev, "alpha", *c.point("alpha", 20, -20), alt=18), airborne_at(ev, "alpha", 18)),
               [_takeoff("alpha", 12), _move("alpha", 0, -20), _move("alpha", alt=6), _move("alpha", alt=18),
                _move("alpha", 20, 0)],
               "alpha غەربكە 20 m ئۇچۇپ 6 m گە چۈشتى، ئاندىن 18 m گە كۆتۈرۈلۈپ شىمالغا 20 m ئۇچتى ۋە لەيلەپ "
               "تۇرۇۋاتىدۇ."),
        _entry("compound", "test", "compound22-fo-bravo-land-east-then-west", ("bravo",),
               "Lyft bravo upp í 10 metrar og lat hann flúgva 15 metrar eystur. Lend hann har. Síðan skal hann upp "
               "aftur, hesaferð í 8 metrar, og flúgva 30 metrar vestur, framum startstaðin, og síðan sveima har.",
               lambda c, ev: _all(down_before(ev, "bravo", c.point("bravo", 0, 15), c.point("bravo", 0, -15)),
                                  at(ev, "bravo", *c.point("bravo", 0, -15), alt=8), airborne_at(ev, "bravo", 8)),
               [_takeoff("bravo", 10), _move("bravo", 0, 15), _land("bravo"), _takeoff("bravo", 8),
                _move("bravo", 0, -30)],
               "bravo lendi 15 m eystan fyri startstaðin, fór upp aftur í 8 m og sveimar nú 15 m vestan fyri hann."),
        # conditional
        _entry("conditional", "test", "cond22-middle-charge-flies", three,
               "Look at the three batteries. The drone whose charge sits in the middle, neither the fullest nor "
               "the emptiest, flies 20 m north of its pad at 10 m and hovers there; the other two stay on the "
               "ground.",
               lambda c, ev: _all(at(ev, "charlie", *c.point("charlie", 20, 0), alt=10), airborne_at(ev, "charlie", 10),
                                  never_armed(ev, "alpha"), never_armed(ev, "bravo")),
               [("fleet_status", {}), _move("charlie", 20, 0, alt=10)],
               "Charlie (63 %) sits between bravo (81 %) and alpha (45 %): it hovers 20 m north of its pad at "
               "10 m; the other two stayed down.",
               battery={"alpha": 45.0, "bravo": 81.0, "charlie": 63.0}),
        _entry("conditional", "test", "cond22-ast-sum-over-hundred-twenty", three,
               "Si la carga d'alpha y la de bravo, sumaes, pasen del 120 %, xubi los dos a 15 metros enriba de les "
               "sos plataformes y déxalos ellí. Si non, xubi namás el que tenga más carga. Charlie queda nel "
               "suelu.",
               lambda c, ev: _all(at(ev, "alpha", *_home(c, "alpha"), alt=15), airborne_at(ev, "alpha", 15),
                                  never_armed(ev, "bravo"), never_armed(ev, "charlie")),
               [("fleet_status", {}), _takeoff("alpha", 15)],
               "alpha (58 %) y bravo (55 %) sumen 113 %, menos de 120 %: namás xubió alpha, a 15 m enriba de la so "
               "plataforma.",
               battery={"alpha": 58.0, "bravo": 55.0, "charlie": 90.0}),
        _entry("conditional", "test", "cond22-tt-charlie-unless-below-bravo", three,
               "charlie-ны 12 метрга күтәреп, көнбатышка 30 метр очыр да шунда утырт. Ләкин charlie-ның батареясы "
               "bravo-ныкыннан азрак булса, бу эшне charlie урынына bravo башкарсын: үз мәйданчыгыннан көнбатышка "
               "30 метр очып, шунда утырсын. alpha җирдә кала.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", 0, -30)], alt=12),
                                  at(ev, "bravo", *c.point("bravo", 0, -30)), landed_disarmed(ev, "bravo"),
                                  never_armed(ev, "charlie"), never_armed(ev, "alpha")),
               [("fleet_status", {}), _move("bravo", 0, -30, alt=12), _land("bravo")],
               "charlie-да 52 %, bravo-да 67 %: шуңа күрә bravo көнбатышка 30 м очып, шунда утырды.",
               battery={"alpha": 80.0, "bravo": 67.0, "charlie": 52.0}),
        # formation
        _entry("formation", "test", "form22-v-pointing-north", three,
               "Form the three into a V pointing north at 15 m: the lead drone 20 m north of bravo's pad, the "
               "other two 10 m behind it (to the south) and 10 m out to either side. Hold them there.",
               lambda c, ev: slots_filled(ev, three, v_slots(c), 15),
               # (a wedge with 14.1 m arms would fit, but the typed plan has no heading for a formation and the
               # gateway faces one where it travels: each drone flies to its slot)
               lambda c: [_go(d, p, 15) for d, p in zip(("bravo", "alpha", "charlie"), v_slots(c), strict=True)],
               "The three hover at 15 m in a V pointing north, its point 20 m north of bravo's pad."),
        _entry("formation", "test", "form22-su-ring-east-of-charlie", three,
               "Susun tilu drone dina hiji bunderan anu jari-jarina 10 méter, jarak antarna sarua, dina jangkungna "
               "20 méter. Puseur bunderanana 25 méter ka beulah wétaneun tempat hiber charlie. Antepkeun ngambang "
               "di dinya.",
               lambda c, ev: _all(formation_around(ev, three, 20, ring, c.point("charlie", 0, 25)),
                                  farthest_apart(ev, three, ring)),
               lambda c: [("formation_goto", {"drone_ids": list(three), "formation": "circle", "alt_m": 20,
                                              "spacing_m": ring, "center_lat_deg": c.point("charlie", 0, 25)[0],
                                              "center_lon_deg": c.point("charlie", 0, 25)[1]})],
               "Tilu drone ngambang dina bunderan 10 m jari-jarina, 20 m luhurna, 25 m wétaneun tempat hiber "
               "charlie."),
        _entry("formation", "test", "form22-ja-l-shape-south", three,
               "3機を高度12メートルでL字形に並べて。角に来る1機は3機の離陸地点の真ん中から南へ15メートルの地点、もう1機"
               "はその角から北へ10メートル、残りの1機は角から西へ10メートル。そこでホバリングさせておいて。",
               lambda c, ev: slots_filled(ev, three, l_slots(c), 12),
               lambda c: [_go(d, p, 12) for d, p in zip(("charlie", "bravo", "alpha"), l_slots(c), strict=True)],
               "3機は高度12 mでL字形にホバリングしています。角は離陸地点の真ん中から南へ15 mです。"),
        # relative
        _entry("relative", "test", "rel22-bravo-bearing-120", ("bravo",),
               "Take bravo up to 12 m, then fly it 30 m along a compass bearing of 120 degrees and hold it there.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", -15, 15 * math.sqrt(3)), alt=12),
                                  airborne_at(ev, "bravo", 12)),
               lambda c: [_takeoff("bravo", 12), _go("bravo", c.point("bravo", -15, 15 * math.sqrt(3)), 12)],
               "Bravo holds 30 m from its pad on a bearing of 120 degrees (15 m south, 26 m east), at 12 m."),
        _entry("relative", "test", "rel22-kk-alpha-east-as-far-as-high", ("alpha",),
               "alpha-ны 18 метр биіктікке көтер. Содан кейін оны шығысқа қарай өз биіктігіне тең қашықтыққа ұшыр, "
               "сосын биіктігінің үштен біріне тең қашықтыққа төмен түсір. Сол жерде ілініп тұрсын.",
               # (the descent may come during the leg east: the request orders it, the end is the same)
               lambda c, ev: _all(rose_to(ev, "alpha", 18), at(ev, "alpha", *c.point("alpha", 0, 18), alt=12),
                                  airborne_at(ev, "alpha", 12)),
               [_takeoff("alpha", 18), _move("alpha", 0, 18), _move("alpha", up=-6)],
               "alpha шығысқа 18 м ұшып, 6 м төмен түсті: қазір 12 м биіктікте ілініп тұр."),
        _entry("relative", "test", "rel22-el-charlie-back-along-track", ("charlie",),
               "Σήκωσε το charlie στα 10 μέτρα και πέτα το 40 μέτρα βορειοανατολικά. Μετά γύρνα το 10 μέτρα πίσω, "
               "από τον ίδιο δρόμο που ήρθε, και ανέβασέ το 5 μέτρα ψηλότερα. Άφησέ το να αιωρείται εκεί.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", d40, d40)], alt=10),
                                  at(ev, "charlie", *c.point("charlie", 3 * d40 / 4, 3 * d40 / 4), alt=15),
                                  airborne_at(ev, "charlie", 15)),
               lambda c: [_takeoff("charlie", 10), _go("charlie", c.point("charlie", d40, d40), 10),
                          _go("charlie", c.point("charlie", 3 * d40 / 4, 3 * d40 / 4), 15)],
               "Το charlie αιωρείται 30 m βορειοανατολικά της βάσης του, στα 15 m."),
        # question
        _entry("question", "test", "ask22-closest-to-half", three,
               "Which drone's battery is closest to 50 % right now, and what does it read? Don't take anything off "
               "the ground.",
               lambda c, ev: _all(answer_says(ev, r"\bbravo\b", "bravo"), answer_mentions_number(ev, 57, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "Bravo, at 57 % (7 points above 50); alpha has 38 %, charlie 71 %.",
               battery={"alpha": 38.0, "bravo": 57.0, "charlie": 71.0}),
        _entry("question", "test", "ask22-as-bravo-times-charlie", three,
               "bravo-ৰ বেটাৰীত charlie-তকৈ কিমান গুণ বেছি চাৰ্জ আছে? দুয়োটাৰে শতাংশও কোৱা, কিন্তু কোনো ড্ৰ'ন "
               "নুৰুৱাবা।",
               # the typed plan reads, it does not compute: the two readings asked for (the ratio is optional)
               lambda c, ev: _all(answer_mentions_number(ev, 90, 1), answer_mentions_number(ev, 30, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "bravo-ৰ 90 %, charlie-ৰ 30 %: bravo-ৰ চাৰ্জ 3 গুণ।",
               battery={"alpha": 64.0, "bravo": 90.0, "charlie": 30.0}),
        _entry("question", "test", "ask22-ml-charlie-points-to-alpha", three,
               "alpha-യുടെ ചാർജിനൊപ്പം എത്താൻ charlie-ക്ക് ഇനി എത്ര ശതമാന പോയിന്റ് കൂടി വേണം? രണ്ടിന്റെയും ഇപ്പോഴത്തെ "
               "ചാർജും പറയൂ. ഒരു ഡ്രോണും പറത്തരുത്.",
               # the typed plan reads, it does not compute: the two readings asked for (the gap is optional)
               lambda c, ev: _all(answer_mentions_number(ev, 71, 1), answer_mentions_number(ev, 34, 1),
                                  nobody_armed(ev)),
               [("fleet_status", {})], "37 പോയിന്റ്: alpha 71 %, charlie 34 %.",
               battery={"alpha": 71.0, "bravo": 66.0, "charlie": 34.0}),
        # refusal (limits of the default configuration: 120 m altitude, 1000 m from home, 30 % to take off,
        # 2 m the lowest altitude, 5 m the least separation a formation keeps)
        _entry("refusal", "test", "refuse22-charlie-450-feet", ("charlie",),
               "Get charlie up to 450 ft straight over its pad for a wide shot of the whole site.",
               lambda c, ev: _all(refusal_seen(ev, "altitude", "120"), max_alt_at_most(ev, "charlie", c.max_alt_m),
                                  answer_reports_refusal(ev)),
               [_takeoff("charlie", 450 * FT)],
               "Refused: 450 ft is 137 m, above the 120 m altitude limit."),
        _entry("refusal", "test", "refuse22-yi-bravo-north-then-east-too-far", ("bravo",),
               "הייב אויף bravo ביז 30 מעטער און פֿלי אים 800 מעטער צו צפֿון. דערנאָך זאָל ער פֿליִען נאָך 700 "
               "מעטער צו מיזרח, ביז צום ראַדיאָ־טורעם.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 800, 0), alt=30), airborne_at(ev, "bravo", 30),
                                  refusal_seen(ev, "distance", "from home", "geofence"),
                                  stayed_within(ev, c, "bravo", c.max_distance_m), answer_reports_refusal(ev)),
               [_takeoff("bravo", 30), _move("bravo", 800, 0), _move("bravo", 0, 700)],
               "bravo הענגט 800 m צפֿון פֿון זײַן פּלאַץ אויף 30 m; די ווײַטערע 700 m צו מיזרח זענען אָפּגעזאָגט "
               "געוואָרן: 1063 m פֿון דער היים, מער ווי די 1000 m וואָס מע מעג."),
        _entry("refusal", "test", "refuse22-hy-all-three-charlie-flat", three,
               "Բարձրացրու երեք դրոններն էլ 10 մետրի վրա, յուրաքանչյուրը իր հարթակի վերևում, և թող օդում կախված "
               "մնան։",
               lambda c, ev: _all(*(_all(at(ev, d, *_home(c, d), alt=10), airborne_at(ev, d, 10))
                                    for d in ("alpha", "bravo")),
                                  never_armed(ev, "charlie"), refusal_seen(ev, "battery"), answer_reports_refusal(ev)),
               [_takeoff("alpha", 10), _takeoff("bravo", 10), _takeoff("charlie", 10)],
               "alpha-ն և bravo-ն կախված են 10 մ բարձրության վրա; charlie-ի թռիչքը մերժվեց. նրա մարտկոցը 22 % է, "
               "իսկ թռիչքի համար պետք է առնվազն 30 %։",
               battery={"charlie": 22.0}),
        # units
        _entry("units", "test", "units22-charlie-miles-west", ("charlie",),
               "Charlie: climb to 30 ft, fly 0.15 miles due west and land there.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 0, -0.15 * mile)], alt=30 * FT),
                                  at(ev, "charlie", *c.point("charlie", 0, -0.15 * mile)),
                                  landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 30 * FT), _move("charlie", 0, -0.15 * mile), _land("charlie")],
               "Charlie flew 0.15 mi (241 m) west at 30 ft (9.1 m) and landed there."),
        _entry("units", "test", "units22-gd-bravo-inches-feet", ("bravo",),
               "Tog bravo gu 600 òirleach os cionn a làraich, an uair sin cuir e 150 troighean gu tuath agus fàg e "
               "an sin san adhar.",
               lambda c, ev: _all(at(ev, "bravo", *c.point("bravo", 150 * FT, 0), alt=600 * inch),
                                  airborne_at(ev, "bravo", 600 * inch)),
               [_takeoff("bravo", 600 * inch), _move("bravo", 150 * FT, 0)],
               "Tha bravo 150 troighean (45.7 m) tuath air a làrach, aig 600 òirleach (15.2 m)."),
        _entry("units", "test", "units22-mi-alpha-feet-km-east", ("alpha",),
               "Whakarewahia a alpha kia 40 putu te teitei, kātahi ka rere ki te rāwhiti, 0.12 kiromita te "
               "tawhiti, ā, tukuna kia tau ki reira.",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 120)], alt=40 * FT),
                                  at(ev, "alpha", *c.point("alpha", 0, 120)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 40 * FT), _move("alpha", 0, 120), _land("alpha")],
               "I rere a alpha ki te rāwhiti 120 m (0.12 km) i te 40 putu (12.2 m), ā, kua tau ki reira."),
        # pattern
        _entry("pattern", "test", "pattern22-alpha-orbit-post-anticlockwise", ("alpha",),
               "Orbit alpha once round the lamp post 20 m north of its pad, keeping 10 m from the post, at 15 m, "
               "anticlockwise as seen from above, starting at the point due south of the post. Then bring it back "
               "to its pad and land.",
               lambda c, ev: _all(visited(ev, "alpha", round_post(c)), at(ev, "alpha", *_home(c, "alpha")),
                                  landed_disarmed(ev, "alpha")),
               # (a circle through the four points, flown as the square they make)
               lambda c: [_takeoff("alpha", 15), *(_go("alpha", p, 15) for p in round_post(c)),
                          _go("alpha", round_post(c)[0], 15), _rtl("alpha")],
               "Alpha circled the post once anticlockwise at 10 m from it, from its south side, and landed on its "
               "pad."),
        _entry("pattern", "test", "pattern22-xh-bravo-expanding-square", ("bravo",),
               "Nyusa i-bravo iye kwiimitha ezili-12, emva koko iphaphe ngendlela yesikwere esandayo: imilenze "
               "emihlanu yeemitha eziyi-10, 10, 20, 20 nama-30, owokuqala usiya emntla, ijike ngasekunene "
               "ekupheleni komlenze ngamnye. Ekugqibeleni mayijinge apho igqibele khona.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", n, e) for n, e in _corners(expanding)[:4]]),
                                  at(ev, "bravo", *c.point("bravo", 20, -10), alt=12), airborne_at(ev, "bravo", 12)),
               [_takeoff("bravo", 12), *_legs("bravo", expanding)],
               "I-bravo iphaphe isikwere esandayo (10, 10, 20, 20, 30 m, ijika ngasekunene) kwaye ijinga apho "
               "igqibele khona, kwiimitha ezili-12."),
        _entry("pattern", "test", "pattern22-ka-charlie-east-west-passes", ("charlie",),
               "აიყვანე charlie 10 მეტრზე და ოთხი 40-მეტრიანი გავლით დაათვალიერე მინდორი "
               "აღმოსავლეთ-დასავლეთის მიმართულებით: პირველი გავლა პირდაპირ ბაქნიდან აღმოსავლეთისკენ, გავლებს შორის "
               "10 მეტრით ჩრდილოეთისკენ გადაინაცვლე. ბოლო გავლის ბოლოს დასვი იქვე.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", n, e) for n, e in _corners(passes)[:6]]),
                                  at(ev, "charlie", *c.point("charlie", 30, 0)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), *_legs("charlie", passes), _land("charlie")],
               "charlie-მ ოთხი 40 მ-იანი გავლა შეასრულა და დაეშვა ბაქნიდან 30 მ-ით ჩრდილოეთით."),
        # placement (the sim's homes stand 5 m apart west to east, alpha, bravo, charlie: each entry places
        # charlie or bravo from alpha or from two drones, so that a drone placed from itself misses)
        _entry("placement", "test", "place22-charlie-midway-in-height-too", three,
               "Take alpha up to 10 m and 30 m north of its pad, and bravo up to 20 m and 30 m east of its pad. "
               "Then send charlie to the point exactly halfway between the two drones, halfway between their "
               "heights too, and leave all three hovering.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", 30, 0), alt=10), airborne_at(ev, "alpha", 10),
                                  at(ev, "bravo", *c.point("bravo", 0, 30), alt=20), airborne_at(ev, "bravo", 20),
                                  at(ev, "charlie", *between(c), alt=15), airborne_at(ev, "charlie", 15)),
               lambda c: [_move("alpha", 30, 0, alt=10), _move("bravo", 0, 30, alt=20), _go("charlie", between(c), 15)],
               "Alpha hovers 30 m north of its pad at 10 m, bravo 30 m east of its own at 20 m, and charlie halfway "
               "between them at 15 m."),
        _entry("placement", "test", "place22-ko-charlie-under-alpha", three,
               "alpha를 12미터로 띄워서 북동쪽으로 20미터 보내고, 거기서 10미터 더 올려. 그다음 charlie를 alpha 바로 "
               "아래, 지면에서 5미터 높이에 띄워 두고 둘 다 그대로 떠 있게 해 줘. bravo는 움직이지 마.",
               lambda c, ev: _all(at(ev, "alpha", *c.point("alpha", d20, d20), alt=22), airborne_at(ev, "alpha", 22),
                                  at(ev, "charlie", *c.point("alpha", d20, d20), alt=5), airborne_at(ev, "charlie", 5),
                                  never_armed(ev, "bravo")),
               lambda c: [_takeoff("alpha", 12), _go("alpha", c.point("alpha", d20, d20), 12), _move("alpha", up=10),
                          _go("charlie", c.point("alpha", d20, d20), 5)],
               "alpha는 이륙 지점에서 북동쪽으로 20 m, 22 m 높이에 떠 있고, charlie는 그 바로 아래 5 m에 떠 있습니다. "
               "bravo는 움직이지 않았습니다."),
        _entry("placement", "test", "place22-nds-charlie-south-of-alpha-pad-bravo-above", three,
               "Laat charlie op 10 Meter stiegen un 12 Meter süüdlich vun alpha sien Startplatz landen. Denn schall "
               "bravo 8 Meter över charlie in de Luft hangen blieven. alpha blifft op de Eer.",
               lambda c, ev: _all(reached_alt(ev, "charlie", 10), at(ev, "charlie", *c.point("alpha", -12, 0)),
                                  landed_disarmed(ev, "charlie"),
                                  at(ev, "bravo", *c.point("alpha", -12, 0), alt=8), airborne_at(ev, "bravo", 8),
                                  never_armed(ev, "alpha")),
               lambda c: [_takeoff("charlie", 10), _go("charlie", c.point("alpha", -12, 0), 10), _land("charlie"),
                          _go("bravo", c.point("alpha", -12, 0), 8)],
               "charlie is 12 m süüdlich vun alpha sien Startplatz landt; bravo hangt 8 m doröver. alpha is nich "
               "flagen."),
        # language
        _entry("language", "test", "lang22-bo-alpha-east-land", ("alpha",),
               "alpha མཐོ་ཚད་ མི་ཊར་ 12 བར་དུ་ ཡར་འཕུར་དུ་ཆུག། དེ་ནས་ ཤར་ཕྱོགས་སུ་ མི་ཊར་ 20 འཕུར་དུ་ཆུག་སྟེ། ས་ཆ་དེ་ཉིད་དུ་ "
               "ས་ལ་བབས་སུ་ཆུག།",
               lambda c, ev: _all(visited(ev, "alpha", [c.point("alpha", 0, 20)], alt=12),
                                  at(ev, "alpha", *c.point("alpha", 0, 20)), landed_disarmed(ev, "alpha")),
               [_takeoff("alpha", 12), _move("alpha", 0, 20), _land("alpha")],
               "alpha ཤར་ཕྱོགས་སུ་ མི་ཊར་ 20 འཕུར་ནས་ ས་ཆ་དེར་ བབས་སོང་།"),
        _entry("language", "test", "lang22-ps-bravo-south-west-hover", ("bravo",),
               "bravo تر 15 مترو لوړوالي پورې پورته کړه، بیا یې 20 متره سویل ته او وروسته 10 متره لوېدیځ ته "
               "والوزوه، او هلته یې په هوا کې ودروه.",
               lambda c, ev: _all(visited(ev, "bravo", [c.point("bravo", -20, 0)], alt=15),
                                  at(ev, "bravo", *c.point("bravo", -20, -10), alt=15), airborne_at(ev, "bravo", 15)),
               [_takeoff("bravo", 15), _move("bravo", -20, 0), _move("bravo", 0, -10)],
               "bravo د خپل ځای څخه 20 m سویل او 10 m لوېدیځ ته، په 15 m لوړوالي کې په هوا کې ولاړ دی."),
        _entry("language", "test", "lang22-mg-charlie-north-back-land", ("charlie",),
               "Ampiakaro hatramin'ny 10 metatra ny charlie, ampanidino 30 metatra mianavaratra, avy eo averino 10 "
               "metatra mianatsimo, ary apetraho eo amin'io toerana io.",
               lambda c, ev: _all(visited(ev, "charlie", [c.point("charlie", 30, 0)], alt=10),
                                  at(ev, "charlie", *c.point("charlie", 20, 0)), landed_disarmed(ev, "charlie")),
               [_takeoff("charlie", 10), _move("charlie", 30, 0), _move("charlie", -10, 0), _land("charlie")],
               "Nanidina 30 metatra mianavaratra ny charlie, niverina 10 metatra mianatsimo ary nipetraka teo, 20 "
               "metatra avaratry ny toerany."),
    ]  # fmt: skip


def corpus() -> list[CorpusEntry]:
    return [
        *_single(),
        *_multi(),
        *_compound(),
        *_conditional(),
        *_formations(),
        *_relative(),
        *_questions(),
        *_refusals(),
        *_units(),
        *_patterns(),
        *_placements(),
        *_languages(),
        *_second_round(),
        *_third_round(),
        *_fourth_round(),
        *_fifth_round(),
        *_sixth_round(),
        *_seventh_round(),
        *_eighth_round(),
        *_ninth_round(),
        *_tenth_round(),
        *_eleventh_round(),
        *_twelfth_round(),
        *_thirteenth_round(),
        *_fourteenth_round(),
        *_fifteenth_round(),
        *_sixteenth_round(),
        *_seventeenth_round(),
        *_eighteenth_round(),
        *_nineteenth_round(),
        *_twentieth_round(),
        *_twenty_first_test_half(),
    ]


def select(half: str) -> list[CorpusEntry]:
    """The entries of one half (``dev`` or ``test``), or of both (``all``)."""
    if half not in (*HALVES, "all"):
        raise ValueError(f"half must be one of {[*HALVES, 'all']}; got {half!r}")
    return [e for e in corpus() if half in ("all", e.half)]


__all__ = ["ALT_TOL_M", "CLASSES", "DRONES", "HALVES", "CorpusEntry", "corpus", "select"]
