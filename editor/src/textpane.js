// The story text as a CodeMirror 6 editor: collaborative (collab), per-client undo, diagnostics as lint
// marks with quick fixes, scene sentences tinted, the sentences playing at the current time highlighted,
// and completion of what can be said.
//
// The server's offsets (sentences, diagnostics) count code points of the version it computed; they are
// shown once this tab has that version, mapped through the local changes not yet confirmed.

import { autocompletion, completionKeymap } from "@codemirror/autocomplete";
import { collab, sendableUpdates } from "@codemirror/collab";
import { defaultKeymap, history, historyKeymap } from "@codemirror/commands";
import { lintGutter, lintKeymap, setDiagnostics } from "@codemirror/lint";
import { EditorState, StateEffect, StateField, Transaction } from "@codemirror/state";
import { Decoration, EditorView, keymap, placeholder } from "@codemirror/view";
import { quickFixes } from "./quickfix.js";
import { remoteCarets, setRemoteCaret } from "./remotecarets.js";
import { cpToUtf16, utf16ToCp } from "./textdiff.js";
import { storyCompletions } from "./vocabulary.js";

const setSentences = StateEffect.define();
const setActive = StateEffect.define();

// Sentence spans as mark decorations (spec: {sid, kind}); mapped through every change.
const sentenceField = StateField.define({
  create: () => Decoration.none,
  update(marks, tr) {
    for (const e of tr.effects) if (e.is(setSentences)) return e.value;
    return marks.map(tr.changes);
  },
  provide: (f) => EditorView.decorations.from(f),
});

// The sentences playing now, highlighted (rebuilt from sentenceField when the set changes).
const activeField = StateField.define({
  create: () => Decoration.none,
  update(marks, tr) {
    for (const e of tr.effects) if (e.is(setActive)) return e.value;
    return marks.map(tr.changes);
  },
  provide: (f) => EditorView.decorations.from(f),
});

const theme = EditorView.theme(
  {
    "&": { height: "100%", backgroundColor: "var(--bg)", color: "var(--text)" },
    ".cm-scroller": { font: "var(--font)", overflow: "auto" },
    ".cm-content": { padding: "12px 0", caretColor: "var(--accent)" },
    ".cm-line": { padding: "0 14px" },
    "&.cm-focused": { outline: "2px solid var(--accent)", outlineOffset: "-2px" },
    ".cm-cursor": { borderLeftColor: "var(--accent)", borderLeftWidth: "2px" },
    ".cm-scene": { backgroundColor: "rgba(90, 169, 255, 0.10)" },
    ".cm-active-sentence": { backgroundColor: "rgba(255, 210, 80, 0.25)" },
    "&.cm-focused .cm-selectionBackground, .cm-selectionBackground": { backgroundColor: "#3a4f73" },
    ".cm-tooltip": { backgroundColor: "var(--panel)", color: "var(--text)", border: "1px solid var(--control-border)" },
    ".cm-diagnosticAction": { backgroundColor: "#2b5ea8", color: "#fff" },
  },
  { dark: true },
);

export class TextPane {
  /**
   * @param {{parent: HTMLElement, list: HTMLElement, onInput: () => void, vocabulary: () => object}} opts
   *   vocabulary() gives {characters, sceneObjects} of the current animation for completion.
   */
  constructor({ parent, list, onInput, vocabulary, onSelection = () => {} }) {
    this.parent = parent;
    this.onSelection = onSelection;
    this.list = list;
    this.onInput = onInput;
    this.vocabulary = vocabulary;
    this.diagnostics = [];
    this.sentences = [];
    this.active = new Set();
    this.view = new EditorView({ state: this.createState(""), parent });
  }

  createState(text) {
    return EditorState.create({
      doc: text,
      extensions: [
        EditorState.lineSeparator.of("\n"),
        collab(),
        history(),
        EditorView.lineWrapping,
        placeholder("In the office there is a desk near a window$. Eve walks to the desk. Eve sits on the chair."),
        EditorView.contentAttributes.of({ "aria-label": "Story text", spellcheck: "false" }),
        keymap.of([...completionKeymap, ...lintKeymap, ...historyKeymap, ...defaultKeymap]),
        autocompletion({ override: [(ctx) => storyCompletions(ctx, this.vocabulary())] }),
        lintGutter(),
        sentenceField,
        activeField,
        remoteCarets,
        theme,
        EditorView.updateListener.of((u) => {
          if (u.docChanged && u.transactions.some((tr) => !tr.annotation(Transaction.remote))) this.onInput();
          if (u.selectionSet || u.docChanged) this.onSelection();
        }),
      ],
    });
  }

  /** Start over on this text (a new document, or local changes the server refused). */
  reset(text) {
    this.view.setState(this.createState(text));
  }

  getText() {
    return this.view.state.doc.toString();
  }

  /**
   * Server offsets (code points of `confirmed`, the text at the version this tab has) -> a function from an
   * offset to a position in the editor now, through the unconfirmed local changes.
   */
  mapper(confirmed) {
    const pending = sendableUpdates(this.view.state);
    const local = pending.length ? pending.slice(1).reduce((a, u) => a.compose(u.changes), pending[0].changes) : null;
    return (cp, assoc) => {
      const pos = Math.min(cpToUtf16(confirmed, cp), confirmed.length);
      return local ? local.mapPos(pos, assoc) : pos;
    };
  }

  /** Where this tab's selection is, in code points of the text now. */
  selectionCp() {
    const text = this.getText();
    const { anchor, head } = this.view.state.selection.main;
    return { anchor: utf16ToCp(text, anchor), head: utf16ToCp(text, head) };
  }

  /** Show (or, with `gone`, remove) another tab's caret; positions are code points of `confirmed`. */
  showRemoteCaret(msg, confirmed) {
    if (msg.gone) {
      this.view.dispatch({ effects: setRemoteCaret.of({ client: msg.client, head: null }) });
      return;
    }
    const at = this.mapper(confirmed);
    this.view.dispatch({
      effects: setRemoteCaret.of({ client: msg.client, anchor: at(msg.anchor, 1), head: at(msg.head, 1) }),
    });
  }

  /** Show a diagnostics message when it belongs to the version this tab has (`confirmed` is its text). */
  setDiagnostics(msg, confirmed) {
    this.diagnostics = msg.diagnostics;
    this.sentences = msg.sentences;
    this.renderList();
    if (confirmed === null) return;
    const at = this.mapper(confirmed);
    const size = this.view.state.doc.length;
    const lint = [];
    for (const d of msg.diagnostics) {
      let from = at(d.start, 1);
      let to = at(Math.max(d.end, d.start), -1);
      if (to <= from) to = Math.min(from + 1, size);
      if (from >= size) from = Math.max(0, size - 1);
      lint.push({
        from,
        to,
        severity: d.severity === "error" ? "error" : d.severity === "warning" ? "warning" : "info",
        source: d.code,
        message: d.message,
        actions: quickFixes(d),
      });
    }
    const marks = [];
    for (const s of msg.sentences) {
      const from = at(s.start, 1);
      const to = at(s.end, -1);
      if (to > from) marks.push(Decoration.mark({ class: s.kind === "scene" ? "cm-scene" : "cm-sentence", sid: s.id, kind: s.kind }).range(from, to));
    }
    const tr = setDiagnostics(this.view.state, lint);
    this.view.dispatch({ ...tr, effects: [...tr.effects, setSentences.of(Decoration.set(marks, true))] });
    this.active = new Set();
  }

  setActive(ids) {
    const key = [...ids].sort().join(",");
    if (key === [...this.active].sort().join(",")) return;
    this.active = new Set(ids);
    const marks = [];
    const iter = this.view.state.field(sentenceField).iter();
    for (; iter.value; iter.next()) {
      if (this.active.has(iter.value.spec.sid)) marks.push(Decoration.mark({ class: "cm-active-sentence" }).range(iter.from, iter.to));
    }
    this.view.dispatch({ effects: setActive.of(Decoration.set(marks, true)) });
  }

  /** Select a document range (code points of the text now) and move the focus there. */
  select(start, end) {
    const text = this.getText();
    const from = cpToUtf16(text, start);
    const to = cpToUtf16(text, end);
    this.view.dispatch({ selection: { anchor: from, head: to }, scrollIntoView: true });
    this.view.focus();
  }

  renderList() {
    this.list.innerHTML = "";
    for (const d of this.diagnostics) {
      const li = document.createElement("li");
      li.className = d.severity;
      const button = document.createElement("button");
      button.type = "button";
      button.className = "diag-item";
      button.setAttribute("aria-label", `${d.severity} ${d.code}: ${d.message} (select it in the text)`);
      const code = document.createElement("span");
      code.className = "code";
      code.textContent = d.code;
      button.append(code, ` ${d.message}`);
      button.addEventListener("click", () => this.select(d.start, d.end));
      li.appendChild(button);
      this.list.appendChild(li);
    }
  }
}
