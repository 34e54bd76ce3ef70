"""Giving the memory a big program's check freed back to the system.

Reading and planning a program of millions of moves makes and frees many arrays of a few
hundred kilobytes to a few megabytes. glibc's allocator raises its threshold for serving
requests from fresh mappings as big blocks are freed, so those arrays come from the heap, and
the freed ones then lie between blocks still in use, where the heap cannot shrink: measured on
a 2,000,000-line program, the process kept about 1 GB more than it used until the freed pages
were handed back. ``malloc_trim`` does that in a few milliseconds; it is called once a load is
done, never per cycle. Elsewhere than glibc it does nothing.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import sys

__all__ = ["trim_heap"]


def _libc_trim():
    if not sys.platform.startswith("linux"):
        return None
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        trim = libc.malloc_trim
    except (OSError, AttributeError):  # another C library (musl has no malloc_trim)
        return None
    trim.argtypes = [ctypes.c_size_t]
    trim.restype = ctypes.c_int
    return trim


_TRIM = _libc_trim()


def trim_heap() -> bool:
    """Hand the heap's free pages back to the system; True when any was given back."""
    return bool(_TRIM(0)) if _TRIM is not None else False
