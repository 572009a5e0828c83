// What the editor holds of the last animation message: its characters and objects by content hash.
//
// The gateway sends an entry the client already holds as a stub `{name|id, hash, unchanged: true}`
// (services/gateway/delta.py); `resolve` fills the stubs in from the previous message's entries and then
// holds exactly this message's entries, as the gateway assumes. A character of a binary frame comes with
// `ops` (every frame, or a patch of the held entry it names: editor/src/animwire.js) and is rebuilt here.

import { rebuild } from "./animwire.js";

export class Holdings {
  constructor() {
    this.characters = new Map(); // hash -> full character entry
    this.objects = new Map(); // hash -> full object entry
  }

  /** Forget everything (the next animation message must come in full). */
  clear() {
    this.characters.clear();
    this.objects.clear();
  }

  /**
   * Fill the `unchanged` stubs of an animation message from the entries held.
   * @param {object} msg an animation message as received
   * @returns {{message: object|null, missing: string[], unchanged: string[], patched: string[]}} the message
   *   with every entry in full (null when a stub names a hash not held: ask the gateway to resume), the
   *   missing hashes, and the names of the characters that were sent as unchanged and as patches.
   */
  resolve(msg) {
    const missing = [];
    const unchanged = [];
    const fill = (entries, held) =>
      (entries || []).map((entry) => {
        if (entry.ops) {
          const base = entry.patch ? held.get(entry.patch) : null;
          if (entry.patch && !base?._q) {
            missing.push(entry.patch);
            return entry;
          }
          return rebuild(entry, base);
        }
        if (!entry.unchanged) return entry;
        const kept = held.get(entry.hash);
        if (!kept) missing.push(entry.hash);
        return kept || entry;
      });
    for (const c of msg.characters || []) if (c.unchanged) unchanged.push(c.name);
    const patched = (msg.characters || []).filter((c) => c.patch).map((c) => c.name);
    const characters = fill(msg.characters, this.characters);
    const objects = fill(msg.objects, this.objects);
    if (missing.length) {
      this.clear();
      return { message: null, missing, unchanged, patched };
    }
    this.characters = new Map(characters.filter((c) => c.hash).map((c) => [c.hash, c]));
    this.objects = new Map(objects.filter((o) => o.hash).map((o) => [o.hash, o]));
    return { message: { ...msg, characters, objects }, missing, unchanged, patched };
  }
}
