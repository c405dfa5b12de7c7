"""A package registered as its directory only: importing its submodules runs no ``__init__``.

Used where a library's ``__init__`` imports much the gateway never uses (`gateway.link.mavsdk_system`,
`gateway.mcp.sdk_package`, `gateway.server_cli` for uvicorn, `gateway.registry.database` for
SQLAlchemy's asyncio extension). A name the bare package lacks is answered by ``missing(package,
name)``; ``own_init_when_missed()`` is the ``missing`` that runs the package's own ``__init__`` in it
then, so code that asks the package for a name it exports works as before, with all of it loaded."""

from __future__ import annotations

import importlib.util
import sys
import threading
import types
from collections.abc import Callable
from pathlib import Path


def register_bare_package(
    name: str, missing: Callable[[types.ModuleType, str], object], what: str
) -> types.ModuleType | None:
    """``name`` in ``sys.modules`` as a bare package; None when it is imported already (nothing done).
    ``what`` names the distribution in the ImportError raised when it is not installed."""
    if name in sys.modules:
        return None
    spec = importlib.util.find_spec(name)  # finds the package without running its __init__
    if spec is None or spec.origin is None or spec.submodule_search_locations is None:
        raise ImportError(f"{what} is not installed")
    package = types.ModuleType(name)
    package.__spec__ = spec
    package.__file__ = spec.origin
    package.__path__ = list(spec.submodule_search_locations)
    package.__package__ = name

    def missing_name(attribute: str) -> object:
        return missing(package, attribute)

    package.__getattr__ = missing_name  # type: ignore[method-assign]
    sys.modules[name] = package
    return package


def own_init_when_missed(name: str) -> Callable[[types.ModuleType, str], object]:
    """A ``missing`` for `register_bare_package`: a name that is one of the package's modules is that
    module, imported (``from . import exc`` in a module of the package asks the package first); the
    first other name missed runs the package's own ``__init__`` in the package (once), then the name
    is answered from it."""
    done: list[bool] = []
    lock = threading.RLock()  # the __init__ run asks the package for names itself

    def whole_package_name(package: types.ModuleType, attribute: str) -> object:
        if not attribute.startswith("__") and importlib.util.find_spec(f"{name}.{attribute}") is not None:
            return importlib.import_module(f"{name}.{attribute}")
        with lock:
            if not done:
                done.append(True)
                init_file = str(package.__file__)
                code = compile(Path(init_file).read_text(encoding="utf-8"), init_file, "exec")
                exec(code, package.__dict__)  # the package's own __init__, in the package
        try:
            return package.__dict__[attribute]
        except KeyError:
            raise AttributeError(f"module {name!r} has no attribute {attribute!r}") from None

    return whole_package_name
