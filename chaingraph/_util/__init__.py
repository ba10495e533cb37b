"""Small helpers shared by every layer: text for reprs, tidy numbers, the process
runner, the progress bar, union-find, writes that a reader never sees half made, and the
names a package's face loads when first used.

* :mod:`.text` counted nouns, short lists, columns, degrees of freedom in words;
* :mod:`.numbers` floats tidied for JSON;
* :mod:`.parallel` the local process runner (and the serial one);
* :mod:`.progress` the progress bar on standard error;
* :mod:`.disjoint` union-find (:class:`DisjointSets`);
* :mod:`.atomic` files and folders that appear whole;
* :mod:`.lazy` PEP 562 names loaded when first used;
* :mod:`.memory` the C library's allocator told to keep freed memory for the next arrays.
"""

from chaingraph._util.atomic import INDEX, staged, withdraw, write_atomic
from chaingraph._util.disjoint import DisjointSets
from chaingraph._util.lazy import lazy_attribute
from chaingraph._util.memory import keep_freed_memory
from chaingraph._util.numbers import tidy
from chaingraph._util.parallel import (
    ignore_interrupts,
    prepare_worker,
    process_runner,
    serial,
)
from chaingraph._util.progress import ProgressBar
from chaingraph._util.text import counted, csv_text, freedom, short_list, write_columns

__all__ = ["counted", "csv_text", "freedom", "short_list", "write_columns", "tidy", "serial",
           "process_runner", "ignore_interrupts", "prepare_worker", "ProgressBar",
           "DisjointSets", "write_atomic", "withdraw", "staged", "INDEX", "lazy_attribute",
           "keep_freed_memory"]
