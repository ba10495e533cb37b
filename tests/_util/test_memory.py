"""The allocator keeps freed memory for the next arrays: a sweep no longer takes its
memory back from the system page by page on every call."""

import json
import os
import platform
import subprocess
import sys

import pytest

from chaingraph._util.memory import keep_freed_memory

GLIBC = sys.platform.startswith("linux") and platform.libc_ver()[0] == "glibc"

#: a fresh process (the heap of a long test run is not the heap of a solve): the page
#: faults of five repeated sweeps with glibc's default threshold, then with chaingraph's
FAULTS = """
import json, resource, chaingraph
from chaingraph._util.memory import keep_freed_memory
chain = chaingraph.load(chaingraph.catalog_path("reciprocating-engine"))
def faults():
    chaingraph.solve(chain, steps=3600, summary=False)      # the heap grows once
    before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    for _ in range(5):
        chaingraph.solve(chain, steps=3600, summary=False)
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before
told = [keep_freed_memory(128 * 1024)]
given_back = faults()
told.append(keep_freed_memory())
print(json.dumps([told, given_back, faults()]))
"""


@pytest.mark.skipif(not GLIBC, reason="glibc's malloc is the allocator tuned")
def test_glibc_is_told_and_a_repeated_sweep_takes_no_memory_from_the_system():
    env = {k: v for k, v in os.environ.items() if k != "MALLOC_TRIM_THRESHOLD_"}
    done = subprocess.run([sys.executable, "-c", FAULTS], capture_output=True, text=True,
                          env=env, check=True)
    told, given_back, kept = json.loads(done.stdout.strip().splitlines()[-1])
    assert told == [True, True]
    # five calls each: kept, (almost) none; given back, about 300 here (glibc trims its
    # heap's top past 128 kB free), though another C library may not trim at all
    assert kept < 25 and kept <= given_back, (given_back, kept)


def test_a_process_that_sets_the_threshold_itself_keeps_its_choice(monkeypatch):
    monkeypatch.setenv("MALLOC_TRIM_THRESHOLD_", "131072")
    assert keep_freed_memory() is False
