"""What one pipeline run produces for a document version (read by the gateway, the CLI and the tests)."""

from __future__ import annotations

from dataclasses import dataclass, field

from proto.motion_data import Motion
from proto.optimizer import OptimiseReply
from proto.retrieval import ComposeReply
from proto.scene import Scene
from proto.ssg import Command, Diagnostic, SentenceGraph


@dataclass(frozen=True)
class SentenceView:
    id: str
    start: int
    end: int
    text: str
    kind: str


@dataclass
class PipelineResult:
    doc_id: str
    version: int
    sentences: list[SentenceView] = field(default_factory=list)
    graphs: dict[str, SentenceGraph] = field(default_factory=dict)  # resolved, sentence-relative spans
    diagnostics: dict[str, list[Diagnostic]] = field(default_factory=dict)  # sentence id -> doc offsets
    scene: Scene | None = None
    scene_report: ComposeReply | None = None
    motions: dict[str, Motion] = field(default_factory=dict)
    commands: list[tuple[str, Command]] = field(default_factory=list)  # (sentence id, command)
    ran: list[str] = field(default_factory=list)
    reused: list[str] = field(default_factory=list)
    unavailable: dict[str, str] = field(default_factory=dict)  # stage -> why
    optimisations: list[OptimiseReply] = field(default_factory=list)  # one per optimised interaction
    cut: dict[str, str] = field(default_factory=dict)  # sentence id -> what the compute budget cut (W501)
