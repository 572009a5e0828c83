// CodeMirror change sets <-> the gateway's text changes ({start, end, text} in code points of the base text).
//
// CodeMirror counts UTF-16 code units, the gateway (Python str) counts code points; the two agree on text
// without astral characters, which is checked once per conversion so the common case costs nothing.

import { ChangeSet } from "@codemirror/state";
import { cpToUtf16, utf16ToCp } from "./textdiff.js";

const ASTRAL = /[\uD800-\uDFFF]/;

/** A change set made against `base` -> the gateway's changes (base offsets, ascending, non-overlapping). */
export function toWire(changes, base) {
  const astral = ASTRAL.test(base);
  const out = [];
  changes.iterChanges((fromA, toA, _fromB, _toB, inserted) => {
    out.push({
      start: astral ? utf16ToCp(base, fromA) : fromA,
      end: astral ? utf16ToCp(base, toA) : toA,
      text: inserted.toString(),
    });
  });
  return out;
}

/** The gateway's changes against `base` -> a CodeMirror change set of a document of length base.length. */
export function fromWire(changes, base) {
  const astral = ASTRAL.test(base);
  const specs = changes.map((c) => ({
    from: astral ? cpToUtf16(base, c.start) : c.start,
    to: astral ? cpToUtf16(base, c.end) : c.end,
    insert: c.text,
  }));
  return ChangeSet.of(specs, base.length, "\n");
}
