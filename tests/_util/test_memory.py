"""The allocator keeps freed memory for the next arrays: a sweep no longer takes its
memory back from the system page by page on every call."""

import platform
import resource
import sys

import pytest

import chaingraph
from chaingraph._util.memory import keep_freed_memory

from ..conftest import catalog_path

GLIBC = sys.platform.startswith("linux") and platform.libc_ver()[0] == "glibc"


@pytest.mark.skipif(not GLIBC, reason="glibc's malloc is the allocator tuned")
def test_glibc_is_told_and_a_repeated_sweep_takes_no_memory_from_the_system(monkeypatch):
    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    chain = chaingraph.load(catalog_path("reciprocating-engine"))

    def faults():
        chaingraph.solve(chain, steps=3600, summary=False)      # the heap grows once
        before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        for _ in range(5):
            chaingraph.solve(chain, steps=3600, summary=False)
        return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before

    try:
        assert keep_freed_memory(128 * 1024)          # glibc's default: given back
        given_back = faults()
    finally:
        assert keep_freed_memory()
    kept = faults()
    assert given_back >= 100 and kept < 25, (given_back, kept)   # five calls each


def test_a_process_that_sets_the_threshold_itself_keeps_its_choice(monkeypatch):
    monkeypatch.setenv("MALLOC_TRIM_THRESHOLD_", "131072")
    assert keep_freed_memory() is False
