"""One BLAS thread for the small matrix products of inference (parse, synthesis, IK, the optimiser).

numpy's OpenBLAS starts one thread per core for every product, however small. The products here are tens
of rows (a sentence's tokens, a skeleton's joints): waking the threads costs more than the product, and on
a machine whose cores are busy with other work the threads wait on each other (a 12 x 288 by 288 x 288
product: 0.06 ms on one thread, 13 ms on two threads of a loaded two-core machine). Results do not depend
on the thread count (OpenBLAS splits the output, not the sums). ``single_threaded`` sets the count through
the library numpy loaded; anything else (no OpenBLAS, not Linux) is left as it is.
"""

from __future__ import annotations

import ctypes
import functools
from pathlib import Path

SETTERS = ("scipy_openblas_set_num_threads64_", "openblas_set_num_threads64_", "openblas_set_num_threads")


def _loaded_openblas() -> list[str]:
    """Paths of the OpenBLAS libraries mapped into this process (Linux), numpy's first."""
    import numpy  # noqa: F401  (maps numpy's OpenBLAS)

    try:
        maps = Path("/proc/self/maps").read_text()
    except OSError:
        return []
    paths = {line.split()[-1] for line in maps.splitlines() if "openblas" in line.rsplit("/", 1)[-1]}
    return sorted(paths, key=lambda p: "numpy" not in p)


@functools.cache
def single_threaded() -> bool:
    """Set numpy's BLAS to one thread (once per process); True when a library took it."""
    done = False
    for path in _loaded_openblas():
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        for name in SETTERS:
            setter = getattr(lib, name, None)
            if setter is not None:
                setter(1)
                done = True
                break
    return done
