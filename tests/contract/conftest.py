"""Make ``from tests.contract.harness import ...`` work under ``--import-mode=importlib``.

pytest's importlib mode does not put the repository root on sys.path, and ``tests`` is not an
installed package, so the root is added here (conftest files load before the test modules).
"""

from __future__ import annotations

import sys
from pathlib import Path

_REPO = str(Path(__file__).resolve().parents[2])
if _REPO not in sys.path:
    sys.path.insert(0, _REPO)
