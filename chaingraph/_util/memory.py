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

__all__ = ["KEPT", "MAPPED", "keep_freed_memory"]

#: the freed memory the heap keeps before giving it back (bytes)
KEPT = 64 * 1024 * 1024

#: blocks at least this large (bytes) are mapped on their own: glibc's largest dynamic
#: threshold, which setting the trim threshold would otherwise freeze at 128 kB
MAPPED = 32 * 1024 * 1024

_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3     # mallopt's parameter numbers (malloc.h)


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
    if "MALLOC_MMAP_THRESHOLD_" not in os.environ:
        # (setting the trim threshold stops glibc raising its mapping threshold as it
        # does by itself; raised here as far as it would go, large arrays are kept too)
        mallopt(_M_MMAP_THRESHOLD, MAPPED)
    return bool(mallopt(_M_TRIM_THRESHOLD, kept))
