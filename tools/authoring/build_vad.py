"""Rebuild ``assets/social/vad.tsv``: valence/arousal/dominance of the words the social model needs.

Source: the Glasgow Norms (Scott, Keitel, Becirspahic, Yao & Sereno 2019, "The Glasgow Norms: Ratings of
5,500 words on nine scales", Behavior Research Methods 51:1258-1270; CC BY 4.0), ratings 1..9 scaled to
[-1, 1] by (x - 5) / 4. Words Glasgow lacks take their valence from VADER (Hutto & Gilbert 2014, MIT
licence; -4..4 scaled by / 4) and have no arousal or dominance ("nan" in the table).

Rows:
    word rows (kind "word"): every content word of every action name and synonym in the motion library,
        the NLP stage's social verbs, emotion words and relation words, and the relation labels of
        ``services.social.relations``.
    action rows (kind "action", key = action name): the mean over the action's name and synonyms of each
        phrase's mean word VAD (dimensions without data are skipped), with a ``response`` flag (the clip
        may be proposed as a character's reaction) and ``contact`` flag (the clip touches the other person).

Usage: ``python -m tools.authoring.build_vad [--glasgow CSV] [--vader TXT] [-o assets/social/vad.tsv]``.
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path

from services.social.lexicon import content_words, word_variants
from services.social.relations import RELATIONS
from wana.domain.paths import asset_path

REPO = Path(__file__).resolve().parents[2]  # a build tool: runs from the checkout it rebuilds
SHARED = REPO.parent / "shared" / "data"
DEFAULT_GLASGOW = SHARED / "glasgow_norms" / "glasgow_norms.csv"
DEFAULT_VADER = SHARED / "vader_lexicon" / "vader_lexicon.txt"
DEFAULT_OUT = asset_path("social", "vad.tsv")

# Tags of clips that read as a reaction to another person (and need no object but, at most, that person).
# (Upper-body or head clips only, plus a few whole-body recoils; never the object or exercise clips.)
RESPONSE_TAGS = frozenset("social emotion agree disagree doubt affection respect frustrated".split())
MOOD_TAGS = frozenset("angry sad happy scared".split())
RESPONSE_EXTRA = frozenset({"step_back", "get_hit", "hide", "block", "stomp"})
NOT_RESPONSES = frozenset({"punch_left", "wave_left_hand", "introduce", "beckon", "point", "talk", "whisper"})
EXTRA_WORDS = (
    "apologize thank forgive praise insult threaten hurt shy sorry guilty lonely grateful respect "
    "admire fear disgust joy anger sadness surprise shame pride".split()
)

HEADER = (
    "# VAD of the words and actions wana's social model needs, each in [-1, 1] (valence, arousal, dominance).\n"
    "# Source: Glasgow Norms, Scott, Keitel, Becirspahic, Yao & Sereno (2019), Behavior Research Methods "
    "51:1258-1270, CC BY 4.0: ratings 1..9 scaled by (x - 5) / 4.\n"
    "# Fill-in (source 'vader'): VADER lexicon, Hutto & Gilbert (2014), MIT licence: valence only, -4..4 "
    "scaled by / 4; arousal and dominance 'nan'.\n"
    "# Action rows (kind 'action', source 'derived'): mean over the action's name and synonyms of each "
    "phrase's mean word VAD.\n"
    "# Regenerate: python -m tools.authoring.build_vad\n"
)
COLUMNS = ("key", "kind", "valence", "arousal", "dominance", "source", "response", "contact")

Vad = tuple[float, float, float]


def read_glasgow(path: Path) -> dict[str, Vad]:
    """Glasgow word -> VAD in [-1, 1]; sense-tagged entries ("bank (money)") also give their plain word
    (mean of its senses) when the plain word has no row of its own."""
    plain: dict[str, Vad] = {}
    senses: dict[str, list[Vad]] = {}
    with open(path, newline="", encoding="utf-8") as fh:
        for row in csv.DictReader(fh):
            word = row["Word"].strip().lower()
            vad = tuple((float(row[c]) - 5.0) / 4.0 for c in ("Valence", "Arousal", "Dominance"))
            if " (" in word:
                senses.setdefault(word.split(" (")[0], []).append(vad)  # type: ignore[arg-type]
            else:
                plain[word] = vad  # type: ignore[assignment]
    for word, vads in senses.items():
        if word not in plain:
            plain[word] = tuple(sum(v[i] for v in vads) / len(vads) for i in range(3))  # type: ignore[assignment]
    return plain


def read_vader(path: Path) -> dict[str, float]:
    """VADER token -> valence in [-1, 1]."""
    out: dict[str, float] = {}
    with open(path, encoding="utf-8") as fh:
        for line in fh:
            parts = line.rstrip("\n").split("\t")
            if len(parts) >= 2 and parts[0].isalpha():
                out[parts[0].lower()] = float(parts[1]) / 4.0
    return out


def needed_words() -> tuple[set[str], dict[str, list[str]], dict[str, tuple[bool, bool]]]:
    """(words, action -> phrases, action -> (response, contact)) from the motion library and NLP lexicon."""
    from services.nlp import lexicon
    from wana.domain.actions import load_library

    words: set[str] = set()
    phrases: dict[str, list[str]] = {}
    flags: dict[str, tuple[bool, bool]] = {}
    for clip in sorted(load_library().values(), key=lambda c: c.name):
        ps = [clip.name.replace("_", " "), *clip.synonyms]
        phrases[clip.name] = ps
        for p in ps:
            words.update(content_words(p))
        obj = clip.interaction.object if clip.interaction else None
        tags = set(clip.tags)
        upper = not ({"full_body", "lower_body", "legs"} & set(clip.body_parts))
        reacts = bool(RESPONSE_TAGS & tags) or ("gesture" in tags and bool(MOOD_TAGS & tags))
        response = clip.name in RESPONSE_EXTRA or (
            reacts and upper and obj in (None, "person") and clip.name not in NOT_RESPONSES
        )
        flags[clip.name] = (response, obj == "person")
    for group in (
        lexicon.SOCIAL_VERBS,
        lexicon.EMOTION_WORDS,
        lexicon.SOCIAL_RELATION_WORDS,
        RELATIONS,
        EXTRA_WORDS,
    ):
        words.update(w.lower() for w in group)
    return words, phrases, flags


def lookup(word: str, glasgow: dict[str, Vad], vader: dict[str, float]) -> tuple[Vad, str] | None:
    """The word's VAD and source, trying its spelling and inflection variants in order."""
    for w in word_variants(word):
        if w in glasgow:
            return glasgow[w], "glasgow"
    for w in word_variants(word):
        if w in vader:
            return (vader[w], math.nan, math.nan), "vader"
    return None


def _nanmean(vads: list[Vad]) -> Vad:
    out = []
    for i in range(3):
        xs = [v[i] for v in vads if not math.isnan(v[i])]
        out.append(sum(xs) / len(xs) if xs else math.nan)
    return out[0], out[1], out[2]


def build_rows(glasgow: dict[str, Vad], vader: dict[str, float]) -> tuple[list[tuple], list[str]]:
    """Table rows (word rows sorted, then action rows sorted) and the words found in neither source."""
    words, phrases, flags = needed_words()
    rows: list[tuple] = []
    known: dict[str, Vad] = {}
    missing = []
    for w in sorted(words):
        hit = lookup(w, glasgow, vader)
        if hit is None:
            missing.append(w)
            continue
        known[w] = hit[0]
        rows.append((w, "word", *hit[0], hit[1], 0, 0))
    for name in sorted(phrases):
        per_phrase = [_nanmean([known[w] for w in content_words(p) if w in known]) for p in phrases[name]]
        per_phrase = [v for v in per_phrase if not all(math.isnan(x) for x in v)]
        vad = _nanmean(per_phrase) if per_phrase else (0.0, 0.0, 0.0)
        vad = tuple(0.0 if math.isnan(x) else x for x in vad)  # type: ignore[assignment]
        response, contact = flags[name]
        rows.append((name, "action", *vad, "derived", int(response), int(contact)))
    return rows, missing


def write_table(rows: list[tuple], out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    with open(out, "w", encoding="utf-8") as fh:
        fh.write(HEADER)
        fh.write("\t".join(COLUMNS) + "\n")
        for key, kind, v, a, d, source, response, contact in rows:
            cells = ["nan" if math.isnan(x) else f"{x:.4f}" for x in (v, a, d)]
            fh.write("\t".join([key, kind, *cells, source, str(response), str(contact)]) + "\n")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m tools.authoring.build_vad",
        description="Rebuild assets/social/vad.tsv (VAD norms of action, emotion and relation words) from the "
        "Glasgow Norms, with VADER valence for words Glasgow lacks.",
    )
    parser.add_argument("--glasgow", type=Path, default=DEFAULT_GLASGOW, help="glasgow_norms.csv")
    parser.add_argument("--vader", type=Path, default=DEFAULT_VADER, help="vader_lexicon.txt")
    parser.add_argument("-o", "--out", type=Path, default=DEFAULT_OUT, help="table to write")
    args = parser.parse_args(argv)
    for p in (args.glasgow, args.vader):
        if not p.is_file():
            print(f"error: {p} not found (the shared datasets live in ../shared/data)", file=sys.stderr)
            return 2
    rows, missing = build_rows(read_glasgow(args.glasgow), read_vader(args.vader))
    write_table(rows, args.out)
    n_vader = sum(1 for r in rows if r[5] == "vader")
    print(f"wrote {len(rows)} rows to {args.out} ({n_vader} words with VADER valence only)")
    if missing:
        print(f"{len(missing)} words in neither source (neutral at run time): {' '.join(missing)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
