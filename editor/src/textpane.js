// The text area with an overlay behind it: per-sentence diagnostics underlined, scene sentences tinted,
// and the sentences playing at the current time highlighted.

import { cpToUtf16, mapOffset, utf16ToCp } from "./textdiff.js";

const SEVERITY_RANK = { error: 3, warning: 2, info: 1 };

function escapeHtml(s) {
  return s.replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" })[c]);
}

export class TextPane {
  constructor({ textarea, backdrop, list, onInput }) {
    this.textarea = textarea;
    this.backdrop = backdrop;
    this.list = list;
    this.sentences = []; // [{id, start, end, kind}] code points, for `version`
    this.diagnostics = [];
    this.active = new Set();
    this.version = null;
    this.textVersion = null; // the version the current text was last confirmed at (overlay shown only then)
    textarea.addEventListener("input", () => {
      this.render();
      onInput();
    });
    textarea.addEventListener("scroll", () => this.syncScroll());
  }

  getText() {
    return this.textarea.value;
  }

  /** Replace the text, keeping the caret where it was (mapped through `change` when given). */
  setText(text, change) {
    const old = this.textarea.value;
    const focused = document.activeElement === this.textarea;
    const selStart = utf16ToCp(old, this.textarea.selectionStart);
    const selEnd = utf16ToCp(old, this.textarea.selectionEnd);
    this.textarea.value = text;
    if (focused) {
      const a = change ? mapOffset(selStart, change) : Math.min(selStart, text.length);
      const b = change ? mapOffset(selEnd, change) : Math.min(selEnd, text.length);
      this.textarea.setSelectionRange(cpToUtf16(text, a), cpToUtf16(text, b));
    }
    this.render();
  }

  setDiagnostics(msg, confirmedText) {
    this.sentences = msg.sentences;
    this.diagnostics = msg.diagnostics;
    this.version = msg.version;
    this.overlayText = confirmedText;
    this.render();
    this.renderList();
  }

  setActive(ids) {
    const key = [...ids].sort().join(",");
    if (key === [...this.active].sort().join(",")) return;
    this.active = new Set(ids);
    this.render();
  }

  /** Select a document range (code points) in the text area. */
  select(start, end) {
    const text = this.textarea.value;
    this.textarea.focus();
    this.textarea.setSelectionRange(cpToUtf16(text, start), cpToUtf16(text, end));
  }

  render() {
    const text = this.textarea.value;
    // Offsets belong to the version the server computed; while the user types ahead, show plain text.
    if (text !== this.overlayText) {
      this.backdrop.innerHTML = escapeHtml(text) + "\n";
      this.syncScroll();
      return;
    }
    const cps = Array.from(text);
    const marks = new Array(cps.length + 1).fill(null).map(() => ({ classes: new Set(), titles: [] }));
    for (const s of this.sentences) {
      for (let i = s.start; i < s.end && i < cps.length; i++) {
        marks[i].sentence = s.id;
        if (s.kind === "scene") marks[i].classes.add("kind-scene");
        if (this.active.has(s.id)) marks[i].classes.add("active");
      }
    }
    for (const d of this.diagnostics) {
      const end = Math.max(d.end, d.start + 1);
      for (let i = d.start; i < end && i < cps.length; i++) {
        const worst = marks[i].severity;
        if (!worst || SEVERITY_RANK[d.severity] > SEVERITY_RANK[worst]) marks[i].severity = d.severity;
      }
    }
    let html = "";
    let run = "";
    let runKey = null;
    const flush = () => {
      if (!run) return;
      html += runKey ? `<mark class="${runKey}">${escapeHtml(run)}</mark>` : escapeHtml(run);
      run = "";
    };
    for (let i = 0; i < cps.length; i++) {
      const m = marks[i];
      const classes = [...m.classes];
      if (m.severity) classes.push("diag", `diag-${m.severity}`);
      const key = classes.length ? classes.join(" ") + (m.sentence ? ` s-${m.sentence}` : "") : null;
      if (key !== runKey) {
        flush();
        runKey = key;
      }
      run += cps[i];
    }
    flush();
    this.backdrop.innerHTML = html + "\n";
    this.syncScroll();
  }

  renderList() {
    this.list.innerHTML = "";
    for (const d of this.diagnostics) {
      const li = document.createElement("li");
      li.className = d.severity;
      li.innerHTML = `<span class="code">${escapeHtml(d.code)}</span> ${escapeHtml(d.message)}`;
      li.addEventListener("click", () => this.select(d.start, d.end));
      this.list.appendChild(li);
    }
  }

  syncScroll() {
    this.backdrop.scrollTop = this.textarea.scrollTop;
    this.backdrop.scrollLeft = this.textarea.scrollLeft;
  }
}
