"""FastAPI's checks for pydantic v1 models, answered without importing ``pydantic.v1``.

FastAPI refuses pydantic v1 models (``fastapi._compat.shared``): to tell one, it imports ``pydantic.v1``
(26 modules, 1.7 MiB of a serving gateway's RSS) at the first route it builds and at the first value it
encodes, and asks ``isinstance``/``issubclass`` of ``pydantic.v1.BaseModel``. No v1 model exists in a
process that has not imported ``pydantic.v1``, so while it is not imported the answer is False without
importing it; once something has imported it, FastAPI's own checks answer. Importing this module puts
the checks in place (`gateway.api` imports it before any of its routes).
"""

from __future__ import annotations

import sys
from collections.abc import Callable

V1_MODULE = "pydantic.v1"


def answer_without_v1(check: Callable[[object], bool]) -> Callable[[object], bool]:
    """``check`` (one of FastAPI's), asked only once ``pydantic.v1`` is imported; False before."""

    def without_v1(value: object) -> bool:
        return V1_MODULE in sys.modules and check(value)

    without_v1.__wrapped__ = check  # type: ignore[attr-defined]
    return without_v1


def install() -> None:
    """Put the checks in FastAPI's modules, where its code looks them up (idempotent)."""
    import fastapi._compat as compat
    import fastapi._compat.shared as shared
    import fastapi.encoders as encoders

    if hasattr(shared.is_pydantic_v1_model_class, "__wrapped__"):
        return
    by_class = answer_without_v1(shared.is_pydantic_v1_model_class)
    by_instance = answer_without_v1(shared.is_pydantic_v1_model_instance)
    places = (
        (shared, "is_pydantic_v1_model_class", by_class),  # annotation_is_pydantic_v1 calls it from here
        (shared, "is_pydantic_v1_model_instance", by_instance),
        (compat, "is_pydantic_v1_model_instance", by_instance),
        (encoders, "is_pydantic_v1_model_instance", by_instance),  # imported there by name
    )
    for module, name, check in places:
        setattr(module, name, check)


install()
