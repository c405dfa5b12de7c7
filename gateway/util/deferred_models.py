"""A library's pydantic models imported with their validators and serializers built at first use.

pydantic builds a model's validator and serializer (pydantic-core's compiled schema, outside Python's
heap) when its class is defined, and a ``TypeAdapter``'s when it is made. Two libraries the gateway
imports define hundreds of models a serving gateway mostly never validates or dumps:

- the MCP SDK's wire types (``mcp_types``): the version-free models, both protocol eras' wire
  shapes (``mcp_types._v2025_11_25``, ``mcp_types._v2026_07_28``: about 300 models, of which a server
  validates the requests and notifications its clients send, in the era they speak) and six
  ``TypeAdapter`` unions of every request, notification and result;
- FastAPI's OpenAPI document models (``fastapi.openapi.models``, imported by ``fastapi.params``), used
  when ``/openapi.json`` is first built and for the few security schemes a route declares.

``import_with_models_deferred(name)`` imports such a module with pydantic's ``defer_build`` in force for
every model class defined and every ``TypeAdapter`` made meanwhile: each is complete, with its fields,
but builds its validator and serializer the first time it is used (pydantic's own mechanism, as for a
model declared ``defer_build=True``). Nothing is done for a module imported already.

pydantic has no public switch for the default of models it does not declare, so this sets its private
default (``pydantic._internal._config.config_defaults``) and ``TypeAdapter._defer_build`` for the time
of the import, and restores both. Where either is missing (another pydantic), the module is imported
as it is (`deferral_available`); tests/test_lean_libraries_unit.py fails then.
"""

from __future__ import annotations

import contextlib
import importlib
import sys
from collections.abc import Iterator
from types import ModuleType


def _pydantic_internals() -> tuple[dict[str, object], type] | None:
    """pydantic's config defaults and ``TypeAdapter``, where they are as this module expects."""
    try:
        from pydantic import TypeAdapter
        from pydantic._internal._config import config_defaults
    except ImportError:
        return None
    if "defer_build" not in config_defaults:
        return None
    if not isinstance(vars(TypeAdapter).get("_defer_build"), property):
        return None
    return config_defaults, TypeAdapter  # type: ignore[return-value]  # config_defaults is a ConfigDict


def deferral_available() -> bool:
    """True when the installed pydantic has the internals this module sets."""
    return _pydantic_internals() is not None


@contextlib.contextmanager
def models_built_when_used() -> Iterator[None]:
    """Within: models defined and TypeAdapters made build their validator and serializer at first use."""
    internals = _pydantic_internals()
    if internals is None:
        yield
        return
    defaults, adapter = internals
    before, adapter_property = defaults["defer_build"], vars(adapter)["_defer_build"]
    defaults["defer_build"] = True
    adapter._defer_build = property(lambda _self: True)  # type: ignore[attr-defined]
    try:
        yield
    finally:
        defaults["defer_build"] = before
        adapter._defer_build = adapter_property  # type: ignore[attr-defined]


def import_with_models_deferred(*names: str) -> list[ModuleType]:
    """Import ``names`` (in order) with their models built at first use; a module imported already is
    returned as it is."""
    modules = []
    for name in names:
        module = sys.modules.get(name)
        if module is None:
            with models_built_when_used():
                module = importlib.import_module(name)
        modules.append(module)
    return modules
