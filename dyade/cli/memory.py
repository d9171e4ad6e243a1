"""Keep freed array memory in the process (a glibc malloc tuning, issue 7).

A sweep allocates a few MB of arrays and frees most of them when the caller is done
with the result. glibc hands blocks above 128 kB back to the operating system (mmap and
munmap, heap trimming), so the next sweep takes a page fault for every 4 kB it touches
again: with the four-bar at 3600 positions that was 60 % of the engine time (1.9 ms
against 0.78 ms with freed memory kept). ``keep_freed_memory`` raises both thresholds
once per process. With another C library (macOS, Windows, musl) it does nothing; it
changes speed only, never results.

It pays where one process runs many sweeps (a batch, ``dyade accuracy``): a single sweep
in a fresh process touches its pages for the first time anyway, and importing ctypes
costs 2.7 ms of its start-up, so ``dyade analyse FILE`` does without it.
"""

from __future__ import annotations

import ctypes

M_TRIM_THRESHOLD = -1
M_MMAP_THRESHOLD = -3
MMAP_THRESHOLD = 32 << 20  # [B] glibc's upper limit on 64-bit systems
TRIM_THRESHOLD = 128 << 20  # [B] free memory kept before the heap is trimmed

_tuned = False


def keep_freed_memory() -> None:
    """Ask glibc to serve arrays up to 32 MB from the heap and to keep up to 128 MB of
    freed memory instead of returning it to the system (once; a no-op elsewhere)."""
    global _tuned
    if _tuned:
        return
    _tuned = True
    try:
        mallopt = ctypes.CDLL("libc.so.6").mallopt
    except (OSError, AttributeError):  # not glibc
        return
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)
    mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD)
