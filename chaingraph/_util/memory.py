"""The C library's allocator told to keep freed memory for the next arrays.

A sweep of a few thousand steps makes and frees hundreds of arrays of tens of kilobytes.
glibc's ``malloc`` gives the top of its heap back to the system whenever more than
``M_TRIM_THRESHOLD`` of it is free (128 kB by default), so every solve took its memory
back page by page: about 430 page faults a call, a third of a four-bar's 3,600-step sweep
(``benchmarks/solve.py`` counts them). Raised once, when chaingraph is imported, the
heap keeps up to :data:`KEPT` of freed memory for the next call. A process that sets
glibc's own ``MALLOC_TRIM_THRESHOLD_`` keeps its choice; other C libraries are left as
they are.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import sys

__all__ = ["KEPT", "keep_freed_memory"]

#: the freed memory the heap keeps before giving it back (bytes)
KEPT = 64 * 1024 * 1024

_M_TRIM_THRESHOLD = -1          # mallopt's parameter number (malloc.h)


def keep_freed_memory(kept: int = KEPT) -> bool:
    """Tell glibc's allocator to keep up to ``kept`` bytes of freed memory at the top of
    its heap instead of giving it back to the system at once; True when it was told (on
    Linux with glibc, unless ``MALLOC_TRIM_THRESHOLD_`` is set), False otherwise.

    A process that chose its own threshold keeps it:

    >>> import os
    >>> os.environ["MALLOC_TRIM_THRESHOLD_"] = "131072"
    >>> keep_freed_memory()
    False
    >>> del os.environ["MALLOC_TRIM_THRESHOLD_"]
    """
    if not sys.platform.startswith("linux") or "MALLOC_TRIM_THRESHOLD_" in os.environ:
        return False
    name = ctypes.util.find_library("c")
    try:
        libc = ctypes.CDLL(name)
        mallopt = libc.mallopt
    except (OSError, AttributeError, TypeError):     # not glibc: no such knob
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    return bool(mallopt(_M_TRIM_THRESHOLD, kept))
