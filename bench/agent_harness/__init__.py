"""The agent benchmark's harness (used by ``bench/nl_missions.py`` and the tests, never installed).

``missions`` (requests and their checks), ``stack`` (local sim + gateway and the drones' true state),
``scripted`` (a scripted OpenAI-compatible endpoint), ``pilot`` (the self-check's scripted pilot).
"""
