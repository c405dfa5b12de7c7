"""Text from outside (ids, client names) made safe to echo in messages, logs and stored rows."""

from __future__ import annotations


def printable(text: str, limit: int | None = None) -> str:
    """``text`` with each control or otherwise unprintable character written as its escape (``\\n``,
    ``\\x1b``): a drone id or client name cannot forge log lines or terminal colours where it is echoed.
    Cut to ``limit`` characters first, when given."""
    cut = text if limit is None else text[:limit]
    if cut.isprintable():
        return cut
    return "".join(c if c.isprintable() else c.encode("unicode_escape").decode("ascii") for c in cut)
