"""Giving the memory the start left free back to the system.

Importing and building the app (pydantic schemas, the tool list, the OpenAPI document) leaves freed
blocks in the C heap that glibc keeps for reuse; once the gateway has started, ``malloc_trim`` returns
the free pages to the system (about 1 MiB of RSS with one drone, bench/memory.py). Elsewhere than
glibc (musl, macOS) there is no such call and nothing is done.
"""

from __future__ import annotations

import ctypes
import gc


def release_free_memory() -> bool:
    """Collect the garbage, then hand the heap's free pages back (glibc ``malloc_trim``); True when done."""
    gc.collect()
    try:
        trim = ctypes.CDLL(None).malloc_trim  # the process's own symbols: glibc's, where it is the libc
    except (OSError, AttributeError):  # no glibc
        return False
    trim.argtypes = [ctypes.c_size_t]
    trim.restype = ctypes.c_int
    trim(0)
    return True
