// Quick fixes for a diagnostic: "did you mean 'sit'?" replaces the word; a missing object gets a scene
// sentence that adds it.

/** The words a diagnostic message suggests ("...; did you mean 'sit' or 'sits'?"). */
export function suggestedWords(message) {
  const m = /did you mean (.+)\?/.exec(message);
  if (!m) return [];
  return [...m[1].matchAll(/'([^']+)'|"([^"]+)"/g)].map((x) => x[1] ?? x[2]);
}

/** The word a message quotes as unknown ("unknown action word: 'sitts' is not an action ..."). */
export function unknownWord(message) {
  return /'([^']+)' is not/.exec(message)?.[1] ?? "";
}

/** An object the message says is missing from the scene ("no armchair in the scene"), or null. */
export function missingObject(message) {
  const m = /\bno (?:free )?([a-z][a-z ]*?) (?:in the scene|in the room|to sit on|is in the scene)/i.exec(message);
  return m ? m[1] : null;
}

/** "sit" for "sitts" in a sentence -> "sits": an action keeps the third person the writer used. */
export function inflectLike(suggestion, unknown, message) {
  const isAction = /not an action/.test(message);
  if (!isAction || !/s$/.test(unknown) || /s$/.test(suggestion) || suggestion.includes(" ")) return suggestion;
  if (/(s|sh|ch|x|z)$/.test(suggestion)) return `${suggestion}es`;
  if (/[^aeiou]y$/.test(suggestion)) return `${suggestion.slice(0, -1)}ies`;
  return `${suggestion}s`;
}

/**
 * CodeMirror lint actions for one server diagnostic.
 * @param {{message: string}} d the diagnostic
 */
export function quickFixes(d) {
  const actions = [];
  const unknown = unknownWord(d.message);
  for (const suggestion of suggestedWords(d.message)) {
    const word = inflectLike(suggestion, unknown, d.message);
    actions.push({
      name: `did you mean ${word}?`,
      apply(view, from, to) {
        // replace the word the message quotes ("'sitts' is not an action ..."), else the first word marked
        const text = view.state.sliceDoc(from, to);
        const index = unknown ? text.indexOf(unknown) : -1;
        const m = index >= 0 ? { index, 0: unknown } : /[A-Za-z][\w'-]*/.exec(text);
        const at = m ? from + m.index : from;
        const end = m ? at + m[0].length : to;
        view.dispatch({ changes: { from: at, to: end, insert: word } });
      },
    });
  }
  const missing = missingObject(d.message);
  if (missing) {
    actions.push({
      name: `add a ${missing} to the scene`,
      apply(view) {
        view.dispatch({ changes: { from: 0, to: 0, insert: `There is a ${missing} in the room$. ` } });
      },
    });
  }
  return actions;
}
