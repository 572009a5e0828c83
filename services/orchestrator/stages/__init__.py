"""The pipeline's stages, one module each: parse (and resolve), scene, social, motion.

Each stage is a function of a `StageContext` (the backend, the query engine, the document and revision,
the seed) and of the previous stages' values; it asks the engine for its query nodes and the backend for
the service calls behind them. The order and the node names are the pipeline's (services/orchestrator/
pipeline.py); what each node reads is cut down by services/orchestrator/views.py.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TypeVar

import msgspec

from proto.common import Header
from services.orchestrator.backend import Backend
from services.orchestrator.queries import QueryEngine

R = TypeVar("R", bound=msgspec.Struct)

NO_HEADER = Header(msg_id="")  # what a memoised reply carries instead of its (random) message ids


def content_of(reply: R) -> R:
    """A reply without its message header, as a query node keeps it: its hash is then a hash of its content,
    so a node that re-runs to the same answer backdates (early cutoff) and an incremental run hashes the same
    as a cold one."""
    return msgspec.structs.replace(reply, header=NO_HEADER)  # type: ignore[type-var]


@dataclass(frozen=True)
class StageContext:
    backend: Backend
    engine: QueryEngine
    doc_id: str
    version: int  # the document version being computed (the requests' revision)
    seed: int = 0  # every service's random choices

    def header(self) -> Header:
        """A fresh request header (its own msg_id) for this document and version."""
        return Header(doc_id=self.doc_id, revision=self.version)
