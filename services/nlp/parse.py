"""One sentence -> its SentenceGraph; a document -> sentence graphs with names and pronouns resolved.

``parse_sentence`` is pure and cached (same text, id, offset and hint -> the same graph); it never
raises: anything wrong becomes a diagnostic with a character span. ``parse_document`` splits a text
with :func:`services.nlp.segment.split_sentences`, parses each sentence and runs
:func:`services.nlp.resolve.resolve` over the result.
"""

from __future__ import annotations

import functools
import logging
import re
import threading
import unicodedata
from collections import OrderedDict

import msgspec
from spacy.language import Language
from spacy.tokens import Doc

from proto.common import Span
from proto.ssg import Diagnostic, SentenceGraph
from services.nlp.actions import extract_actions, extract_relative_actions
from services.nlp.builder import GraphBuilder
from services.nlp.commands import looks_like_command, parse_command, unknown_camera_detail
from services.nlp.errors import MAX_SENTENCE_CHARS, diagnostic
from services.nlp.lexicon import TITLES
from services.nlp.repair import repair_character_sentence, repair_scene_sentence
from services.nlp.scene import extract_scene, is_scene_like
from services.nlp.segment import kind_hint as _kind_hint
from services.nlp.segment import quote_spans, split_sentences
from services.nlp.suggest import did_you_mean

log = logging.getLogger(__name__)
_WORD = re.compile(r"[^\W\d_]+", re.UNICODE)


def _binary_garbage(text: str) -> bool:
    bad = sum(
        1
        for ch in text
        if (unicodedata.category(ch) in ("Cc", "Cs", "Co", "Cn") and ch not in "\t\n\r") or ch == "\ufffd"
    )
    return bad > 0 and bad >= max(1, len(text) // 50)


@functools.lru_cache(maxsize=1)
def _english_words() -> frozenset[str]:
    from services.nlp.compounds import _catalog_words
    from services.nlp.compounds import _english_words as treebank_words

    return treebank_words() | _catalog_words()


def _not_english(text: str) -> bool:
    words = _WORD.findall(text)
    if not words:
        return False
    letters = sum(len(w) for w in words)
    ascii_letters = sum(1 for w in words for ch in w if ch.isascii())
    if ascii_letters < 0.7 * letters:
        return True
    vocab = _english_words()
    words = [w for w in words if len(w) >= 3]  # the vocabulary holds words of three letters or more
    if len(words) < 3 or not vocab:
        return False
    known = sum(1 for w in words if w.lower() in vocab or w[0].isupper() or _inflected_verb(w.lower()))
    return known < 0.5 * len(words)


def _inflected_verb(word: str) -> bool:
    """ "apologizing", "quarrelled": an inflection of a verb the action vocabulary knows."""
    from services.nlp.lemmatizer import verb_lemma_candidates
    from services.nlp.lexicon import verb_words

    known = verb_words()
    return any(c in known for c in verb_lemma_candidates(word))


def _masked_speech(text: str) -> str:
    """Quoted speech replaced by a same-length stand-in ("hello" and dashes): what a character says is
    the caption, not objects or actions of the story ('Tom says "I drank it."' is one talking action)."""
    out = text
    for start, end in quote_spans(text):
        n = end - start - 2
        if n >= 5:
            out = out[: start + 1] + "hello" + "-" * (n - 5) + out[end - 1 :]
        elif n > 0:
            out = out[: start + 1] + "hi".ljust(n, "-")[:n] + out[end - 1 :]
    return out


_CAN_COMPOUND = re.compile(r"\b([A-Za-z]+) (cans?)\b")


def _glued_cans(text: str) -> str:
    """ "a trash can", "a watering can" -> "trash_can": else the parser reads the modal "can" (same length)."""
    from wana.assets import vocabulary

    def glue(m: re.Match[str]) -> str:
        phrase = f"{m.group(1).lower()} {m.group(2).lower()}"
        return (
            f"{m.group(1)}_{m.group(2)}"
            if vocabulary.lookup(phrase) not in (None, "soda_can")
            else m.group(0)
        )

    return _CAN_COMPOUND.sub(glue, text) if " can" in text else text


_NOUN_VERB = re.compile(r"\b(fist)[ ](pump|pumps|pumped|pumping)\b", re.IGNORECASE)


def _glued_noun_verbs(text: str) -> str:
    """ "fist pumps" -> "fist-pumps": one verb, else the parser reads a noun and a verb
    (same length)."""
    if "fist " not in text.lower():
        return text
    return _NOUN_VERB.sub(lambda m: f"{m.group(1)}-{m.group(2)}", text)


def _parser_text(text: str) -> str:
    """The sentence as the parser reads it: a terminal "$" becomes "." and quoted speech is masked
    (same length, same offsets)."""
    chars = list(_glued_noun_verbs(_glued_cans(_masked_speech(text))))
    i = len(chars) - 1
    while i >= 0 and (chars[i] in ".!?$ " or chars[i] in "\"')"):
        if chars[i] == "$":
            after = "".join(chars[i + 1 :]).strip()
            chars[i] = " " if after and after[0] in ".!?" else "."
        i -= 1
    return "".join(chars)


def _graph(
    sentence_id: str, text: str, kind: str, diagnostics: list[Diagnostic], **kw: object
) -> SentenceGraph:
    return SentenceGraph(sentence_id=sentence_id, text=text, kind=kind, diagnostics=diagnostics, **kw)  # type: ignore[arg-type]


_CACHE_SIZE = 16384
_cache: OrderedDict[tuple[str, str], SentenceGraph] = OrderedDict()
_cache_lock = threading.Lock()


def _cache_get(key: tuple[str, str]) -> SentenceGraph | None:
    with _cache_lock:
        graph = _cache.get(key)
        if graph is not None:
            _cache.move_to_end(key)
        return graph


def _cache_put(key: tuple[str, str], graph: SentenceGraph) -> None:
    with _cache_lock:
        _cache[key] = graph
        while len(_cache) > _CACHE_SIZE:
            _cache.popitem(last=False)


def clear_cache() -> None:
    """Forget every cached parse (benchmarks; tests of the pipeline itself)."""
    with _cache_lock:
        _cache.clear()


def parse_sentence(text: str, sentence_id: str = "", offset: int = 0, kind_hint: str = "") -> SentenceGraph:
    """Parse one sentence into its SSG fragment.

    Pure and cached by (text, kind_hint): the same sentence moved elsewhere in the document is not
    parsed again, its spans are shifted.

    Args:
        text: the sentence as written (with its terminator; "$" marks a scene sentence).
        sentence_id: stable id the orchestrator gave the sentence.
        offset: position of ``text`` in the document; every span is shifted by it.
        kind_hint: "scene" / "action" / "command" from the splitter; "" = decide here.

    Returns:
        The sentence's graph; problems are diagnostics on it, never exceptions.
    """
    return parse_sentences([(text, sentence_id, offset, kind_hint)])[0]


def parse_sentences(items: list[tuple[str, str, int, str]]) -> list[SentenceGraph]:
    """Parse several ``(text, sentence_id, offset, kind_hint)`` at once (the pipeline runs batched)."""
    keys = [(text, hint) for text, _, _, hint in items]
    base: dict[tuple[str, str], SentenceGraph] = {}
    todo: list[tuple[tuple[str, str], str, str, list[Diagnostic]]] = []
    for key in dict.fromkeys(keys):
        cached = _cache_get(key)
        if cached is not None:
            base[key] = cached
            continue
        try:
            prepared = _prepare(key[0], key[1])
        except Exception as exc:  # the parser must never take the document down
            log.exception("parse failed for %r", key[0][:200])
            prepared = _failed(key[0], exc)
        if isinstance(prepared, SentenceGraph):
            base[key] = prepared
            _cache_put(key, prepared)
        else:
            todo.append((key, *prepared))
    if todo:
        from services.nlp.pipeline import get_nlp

        nlp = get_nlp()
        docs = nlp.pipe([_titled_doc(nlp, parser_text) for _, parser_text, _, _ in todo], batch_size=64)
        for (key, _, kind, diagnostics), doc in zip(todo, docs, strict=True):
            try:
                graph = _extract(doc, key[0], kind, diagnostics)
            except Exception as exc:
                log.exception("extraction failed for %r", key[0][:200])
                graph = _failed(key[0], exc)
            base[key] = graph
            _cache_put(key, graph)
    return [
        msgspec.structs.replace(shift_spans(base[key], offset), sentence_id=sid)
        for key, (_, sid, offset, _) in zip(keys, items, strict=True)
    ]


def _titled_doc(nlp: Language, text: str) -> Doc:
    """The tokenized sentence with no sentence break inside a titled name: the parser would otherwise end
    a sentence at the abbreviation's period ("Prof. | Kim waves")."""
    doc = nlp.make_doc(text)
    toks = list(doc)
    words = [t.text for t in toks]
    for i in range(
        1, len(toks)
    ):  # the splitter already cut the text: no break but after . ! ? ("hands | Tom the cup")
        prev = words[i - 1]
        if not (prev[-1:] in ".!?;" or prev in ('"', "'", ")")):
            toks[i].is_sent_start = False
    for i in range(len(toks) - 1):
        word = words[i]
        if word[:1].isupper() and word.lower().rstrip(".") in TITLES and words[i + 1][:1].isupper():
            toks[i + 1].is_sent_start = False
    for start, end in quote_spans(text):  # nor inside (or at) quoted speech
        for tok in toks[1:]:
            if start <= tok.idx < end:
                tok.is_sent_start = False
    return doc


def _failed(text: str, exc: Exception) -> SentenceGraph:
    return _graph("", text, "action", [diagnostic("E112", f"{type(exc).__name__}: {exc}", 0, len(text))])


def _prepare(text: str, kind_hint: str) -> SentenceGraph | tuple[str, str, list[Diagnostic]]:
    """A finished graph (empty, garbage, command, not English) or (parser text, kind, diagnostics)."""
    stripped = text.strip()
    lead = len(text) - len(text.lstrip())
    if not stripped:
        return _graph("", text, "empty", [diagnostic("I111", "", 0, len(text))])
    if _binary_garbage(text):
        return _graph("", text, "empty", [diagnostic("E110", f"{len(text)} characters", 0, len(text))])
    kind = kind_hint or _kind_hint(stripped)
    command = parse_command(text, 0)
    if command is not None:
        return _graph("", text, "command", [], commands=[command])
    if kind == "command" or looks_like_command(stripped):
        return _graph(
            "",
            text,
            "command",
            [
                diagnostic(
                    "W104",
                    unknown_camera_detail(stripped) + did_you_mean(stripped[:60], "command"),
                    lead,
                    lead + len(stripped),
                )
            ],
        )
    diagnostics: list[Diagnostic] = []
    body = text
    if len(body) > MAX_SENTENCE_CHARS:
        diagnostics.append(
            diagnostic(
                "W108", f"{len(text)} characters, parsed {MAX_SENTENCE_CHARS}", MAX_SENTENCE_CHARS, len(text)
            )
        )
        body = body[:MAX_SENTENCE_CHARS]
    if _not_english(body):
        diagnostics.append(diagnostic("W106", f"'{stripped[:40]}'", lead, lead + len(stripped)))
        return _graph("", text, "scene" if kind == "scene" else "action", diagnostics)
    return _parser_text(body), kind, diagnostics


def _extract(doc: Doc, text: str, kind: str, diagnostics: list[Diagnostic]) -> SentenceGraph:
    stripped = text.strip()
    lead = len(text) - len(text.lstrip())
    builder = GraphBuilder(text, 0)
    builder.diagnostics.extend(diagnostics)
    is_scene = kind == "scene"
    sents = list(doc.sents) or [doc[:]]
    # repaired first: "In the evening, Jack lights/NOUN a candle/ROOT" reads as a scene sentence otherwise
    if not is_scene and any([repair_character_sentence(s) for s in sents]):
        sents = list(doc.sents) or [doc[:]]
    if not is_scene and all(is_scene_like(s) for s in sents):
        is_scene = True
    for sent in sents:
        if is_scene:
            repair_scene_sentence(sent)
            extract_scene(sent, builder)
            extract_relative_actions(sent, builder)
        else:
            extract_actions(sent, builder)
    if is_scene and not builder.objects and not builder.room_type:
        if not any(d.code == "W101" for d in builder.diagnostics):
            builder.diagnose("W101", f"no object named in '{stripped[:60]}'", lead, lead + len(stripped))
    silent = not (builder.objects or builder.characters or builder.social or builder.commands)
    if silent and not builder.room_type and not builder.diagnostics and stripped:
        # "camrea left": no character, thing or command; say so, never drop the line unremarked
        hint = did_you_mean(stripped[:60], "command")
        builder.diagnose(
            "W115",
            f"'{stripped[:60]}' names no character, thing or command{hint}",
            lead,
            lead + len(stripped),
        )
    return builder.build("", "scene" if is_scene else "action")


def shift_spans(graph: SentenceGraph, delta: int) -> SentenceGraph:
    """The same graph with every span moved by ``delta`` characters (a sentence moved in the document)."""
    if delta == 0:
        return graph

    def mv(s: Span) -> Span:
        return Span(s.start + delta, s.end + delta)

    def rep(node, **kw):  # noqa: ANN001, ANN202 - small local helper over several struct types
        return msgspec.structs.replace(node, span=mv(node.span), **kw)

    return msgspec.structs.replace(
        graph,
        objects=[rep(o) for o in graph.objects],
        relations=[rep(r) for r in graph.relations],
        characters=[
            msgspec.structs.replace(c, actions=[rep(a) for a in c.actions]) for c in graph.characters
        ],
        social=[rep(s) for s in graph.social],
        commands=[rep(c) for c in graph.commands],
        diagnostics=[rep(d) for d in graph.diagnostics],
    )


def parse_document_with_spans(text: str) -> tuple[list[tuple[int, int, str]], list[SentenceGraph]]:
    """Split, parse and resolve a document; returns the sentence spans and their graphs.

    Empty input gives one span (0, len(text), "empty") with an "empty" graph carrying I111.
    """
    from services.nlp.resolve import resolve

    pieces = split_sentences(text)
    if not pieces:
        return [(0, len(text), "empty")], [parse_sentence(text, "s0", 0, "")]
    graphs = parse_sentences([(text[s:e], f"s{i}", s, hint) for i, (s, e, hint) in enumerate(pieces)])
    return pieces, resolve(graphs, [s for s, _, _ in pieces])


def parse_document(text: str) -> list[SentenceGraph]:
    """Split, parse and resolve a whole document; sentence ids are "s0", "s1", ..."""
    return parse_document_with_spans(text)[1]
