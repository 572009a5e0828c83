// Diagnostics arrive as deltas (services/gateway/diagdelta.py): each message replaces the entries and
// verdicts of the sentences it lists in `changed`, forgets those in `dropped`, and keeps the rest, moved by
// how far their sentence moved. `base_seq` null: the message is the whole state. The merged state has the
// shape of a whole diagnostics message, so the text pane and the list read it unchanged.

export class DiagnosticsMerge {
  constructor() {
    this.reset();
  }

  reset() {
    this.seq = null;
    this.starts = new Map(); // sentence id -> its start in the version last merged
    this.entries = new Map(); // sentence id -> its diagnostics (offsets of the version last merged)
    this.verdicts = new Map(); // sentence id -> its verdict entry
  }

  /** Merge one diagnostics message; returns the whole state as a diagnostics message. */
  apply(msg) {
    if (msg.base_seq === null || msg.base_seq === undefined || msg.base_seq !== this.seq) {
      this.entries = new Map();
      this.verdicts = new Map();
    }
    const starts = new Map(msg.sentences.map((s) => [s.id, s.start]));
    for (const sid of msg.dropped ?? []) {
      this.entries.delete(sid);
      this.verdicts.delete(sid);
    }
    const changed = new Set(msg.changed ?? []);
    for (const [sid, items] of this.entries) {
      if (changed.has(sid)) continue;
      const shift = (starts.get(sid) ?? 0) - (this.starts.get(sid) ?? 0);
      if (shift !== 0) this.entries.set(sid, items.map((d) => ({ ...d, start: d.start + shift, end: d.end + shift })));
    }
    for (const sid of changed) {
      this.entries.delete(sid);
      this.verdicts.delete(sid);
    }
    for (const d of msg.diagnostics) {
      if (!this.entries.has(d.sentence_id)) this.entries.set(d.sentence_id, []);
      this.entries.get(d.sentence_id).push(d);
    }
    for (const v of msg.verdicts ?? []) this.verdicts.set(v.sentence_id, v);
    this.seq = msg.seq ?? null;
    this.starts = starts;
    const diagnostics = [...this.entries.values()].flat();
    diagnostics.sort((a, b) => a.start - b.start || a.end - b.end || (a.code < b.code ? -1 : a.code > b.code ? 1 : 0));
    return {
      type: "diagnostics",
      version: msg.version,
      seq: msg.seq,
      sentences: msg.sentences,
      unavailable: msg.unavailable,
      diagnostics,
      verdicts: [...this.verdicts.values()],
      verdicts_pending: Boolean(msg.verdicts_pending),
    };
  }
}
