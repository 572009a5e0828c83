"""The NLP service: sentence text -> semantic scene graph fragment (proto.ssg.SentenceGraph).

CONTRACT:
    ParseRequest          -> ParseReply          one sentence, unresolved (pronouns as written)
    ParseBatchRequest     -> ParseBatchReply     several sentences, same order
    ResolveRequest        -> ResolveReply        names/pronouns resolved across a document's graphs
    ParseDocumentRequest  -> ParseDocumentReply  split + parse + resolve a whole text
    anything else / bad input -> proto.common.ErrorReply (E001 undecodable, E010 invalid input)

Python API (in-process, pure, cached):
    services.nlp.segment.split_sentences(text) -> list[(start, end, kind_hint)]
    services.nlp.parse.parse_sentence(text, sentence_id="", offset=0, kind_hint="") -> SentenceGraph
    services.nlp.parse.shift_spans(graph, delta) -> SentenceGraph
    services.nlp.resolve.resolve(graphs, offsets=None) -> list[SentenceGraph]
    services.nlp.parse.parse_document(text) -> list[SentenceGraph]

Modules: segment (sentence splitting, quoted speech kept whole), commands (camera/weather/wait/speed lines), pipeline (the
trained spaCy pipeline, lazily loaded), lemmatizer, lexicon (words -> catalog categories and action
names), compounds (glued words), mentions (noun phrases -> objects/characters), scene (relations),
repair (two parser errors on character sentences), arguments (a verb's objects and obliques),
actions (characters, actions, social), verbs (the verbs people write -> clips, and the verbs no clip
can show), timephrase ("the next morning", "after a while"), suggest ("did you mean ..."), builder,
parse, resolve (names, pronouns, one object node per object), errors (diagnostic codes), cli (which
also reads Fountain screenplays through wana.screenplay).
The pipeline is rebuilt by ``scripts/train_nlp.py``.
"""

import sys as _sys


def _load_thinc_without_torch() -> None:
    """Import thinc (spaCy's ML layer) without torch: parsing runs on thinc's numpy ops.

    ``thinc.compat`` imports torch whenever it is installed, which costs about 1.3 s of every start-up
    although the shipped pipeline (a CNN tok2vec) never calls it. A ``None`` entry in ``sys.modules``
    makes that ``import torch`` fail fast; the entry is removed at once, so training code that imports
    torch later in the same process still gets it. A process that already imported torch is left alone.
    """
    if "torch" in _sys.modules or "thinc" in _sys.modules:
        return
    _sys.modules["torch"] = None  # type: ignore[assignment]
    try:
        import thinc.compat  # noqa: F401
    finally:
        if _sys.modules.get("torch", ...) is None:
            del _sys.modules["torch"]


_load_thinc_without_torch()
