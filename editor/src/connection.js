// The live document: CodeMirror's collab extension against the gateway, which is the authority on versions.
//
// The gateway orders every edit (version N+1 is applied to version N); this client sends its unconfirmed
// CodeMirror updates as one edit against the last version it has, at most one edit in flight. Acks and
// other tabs' `remote_edit`s may arrive out of order (each is sent by its own coroutine), so they are
// buffered by version and applied strictly in order through `receiveUpdates`, which rebases the local
// unconfirmed changes over remote ones, maps carets and keeps the undo history per client (remote changes
// are not added to it). A `stale` reply carries the edits this client missed; it resends after applying them.
// On reconnect the server's whole text is rebased onto as one remote change.

import { getClientID, receiveUpdates, sendableUpdates } from "@codemirror/collab";
import { decodeMessage } from "./animwire.js";
import { liveUrl } from "./api.js";
import { fromWire, toWire } from "./collabwire.js";
import { applyChanges, diff } from "./textdiff.js";

const SERVER_ID = "gateway"; // the clientID of every change that is not this tab's own

export class LiveDocument {
  /**
   * @param {string} docId
   * @param {{view: () => import("@codemirror/view").EditorView, reset: (text: string) => void,
   *          selection: () => {anchor: number, head: number}, onPresence: (msg: object, confirmed: string) => void,
   *          onMessage: (msg: object) => void, onStatus: (status: string) => void}} hooks
   */
  constructor(docId, hooks) {
    this.docId = docId;
    this.hooks = hooks;
    this.version = null; // last version applied here (the server's numbering)
    this.confirmed = ""; // the text at `version`
    this.inFlight = null; // {count, seq, changes, text} of the edit awaiting its ack
    this.pending = new Map(); // version -> {own} | {changes}: received ahead of their turn
    this.waitFor = 0; // after a stale reply: send nothing until this version has been applied
    this.seq = 0;
    this.ready = false;
    this.closed = false;
    this.retryMs = 250;
    this.connect();
  }

  connect() {
    if (this.closed) return;
    this.hooks.onStatus("connecting");
    const ws = new WebSocket(liveUrl(this.docId, this.version));
    this.ws = ws;
    ws.onopen = () => {
      this.retryMs = 250;
      this.hooks.onStatus("online");
    };
    ws.binaryType = "arraybuffer";
    // messages are handled in arrival order; binary ones (animation frames, compressed JSON) are inflated
    // first, and a text message that arrives meanwhile waits for them (per connection)
    let queue = Promise.resolve();
    let decoding = 0;
    ws.onmessage = (event) => {
      const data = event.data;
      if (typeof data === "string" && !decoding) {
        this.receive(JSON.parse(data));
        return;
      }
      decoding += 1;
      queue = queue
        .then(() => (typeof data === "string" ? JSON.parse(data) : decodeMessage(data)))
        .then((msg) => ws === this.ws && this.receive(msg))
        .catch((err) => console.error("live message:", err))
        .finally(() => {
          decoding -= 1;
        });
    };
    ws.onclose = (event) => {
      this.ready = false;
      if (this.closed) return;
      if (event.code === 4404 || event.code === 1008) {
        this.hooks.onStatus(event.code === 4404 ? "no such document" : "refused (token?)");
        return;
      }
      this.hooks.onStatus("reconnecting");
      setTimeout(() => this.connect(), this.retryMs);
      this.retryMs = Math.min(this.retryMs * 2, 5000);
    };
  }

  /** Ask for the current text and results again; the animation then comes with every entry in full. */
  resume() {
    if (this.ws?.readyState !== WebSocket.OPEN) return;
    this.ws.send(JSON.stringify({ type: "resume", version: this.version ?? -1 }));
  }

  close() {
    this.closed = true;
    this.ws?.close();
  }

  /** Local changes not yet acknowledged (CodeMirror updates, oldest first). */
  unconfirmed() {
    return sendableUpdates(this.hooks.view().state);
  }

  /** Call after every local change of the text; sends the unconfirmed changes when no edit is in flight. */
  flush() {
    if (!this.ready || this.inFlight || this.ws?.readyState !== WebSocket.OPEN) return;
    if (this.version < this.waitFor) return;
    const updates = this.unconfirmed();
    if (!updates.length) return;
    const composed = updates.slice(1).reduce((a, u) => a.compose(u.changes), updates[0].changes);
    const changes = toWire(composed, this.confirmed);
    this.seq += 1;
    this.inFlight = { count: updates.length, seq: this.seq, changes, text: applyChanges(this.confirmed, changes) };
    this.ws.send(JSON.stringify({ type: "edit", base_version: this.version, changes, client_seq: this.seq }));
  }

  /** Tell the other tabs where the selection is, once nothing local is unconfirmed (throttled). */
  sendPresence() {
    if (this.presenceTimer) return;
    this.presenceTimer = setTimeout(() => {
      this.presenceTimer = null;
      if (!this.ready || this.ws?.readyState !== WebSocket.OPEN) return;
      if (this.inFlight || this.unconfirmed().length) return; // sent again once acknowledged
      const sel = this.hooks.selection();
      const key = `${this.version}:${sel.anchor}:${sel.head}`;
      if (key === this.presenceSent) return;
      this.presenceSent = key;
      this.ws.send(JSON.stringify({ type: "presence", version: this.version, anchor: sel.anchor, head: sel.head }));
    }, 80);
  }

  /** Apply the buffered versions that are next in line. */
  drain() {
    const view = this.hooks.view();
    while (this.pending.has(this.version + 1)) {
      const next = this.pending.get(this.version + 1);
      this.pending.delete(this.version + 1);
      if (next.own) {
        const own = this.unconfirmed().slice(0, this.inFlight.count);
        const clientID = getClientID(view.state);
        view.dispatch(receiveUpdates(view.state, own.map((u) => ({ changes: u.changes, clientID }))));
        this.confirmed = this.inFlight.text;
        this.inFlight = null;
      } else {
        const changes = fromWire(next.changes, this.confirmed);
        view.dispatch(receiveUpdates(view.state, [{ changes, clientID: SERVER_ID }]));
        this.confirmed = applyChanges(this.confirmed, next.changes);
      }
      this.version += 1;
    }
    for (const v of this.pending.keys()) if (v <= this.version) this.pending.delete(v);
  }

  /** Move to the server's whole text at `version`, as one remote change (local changes rebased over it). */
  jump(text, version) {
    const change = diff(this.confirmed, text);
    if (change) {
      const view = this.hooks.view();
      const changes = fromWire([change], this.confirmed);
      view.dispatch(receiveUpdates(view.state, [{ changes, clientID: SERVER_ID }]));
    }
    this.confirmed = text;
    this.version = version;
    for (const v of this.pending.keys()) if (v <= version) this.pending.delete(v);
    this.drain();
  }

  receive(msg) {
    switch (msg.type) {
      case "state": {
        if (this.version === null) {
          this.confirmed = msg.text;
          this.version = msg.version;
          this.hooks.reset(msg.text);
        } else if (this.inFlight && msg.text === this.inFlight.text && msg.version === this.version + 1) {
          this.pending.set(msg.version, { own: true }); // the edit in flight when the connection dropped landed
          this.drain();
        } else if (msg.version !== this.version || msg.text !== this.confirmed) {
          this.inFlight = null;
          this.jump(msg.text, msg.version);
        }
        this.inFlight = null;
        this.waitFor = 0;
        this.ready = true;
        break;
      }
      case "ack": {
        if (this.inFlight && msg.client_seq === this.inFlight.seq) {
          this.pending.set(msg.version, { own: true });
          this.drain();
        }
        break;
      }
      case "remote_edit": {
        if (this.version !== null && msg.version > this.version) {
          this.pending.set(msg.version, { changes: msg.changes });
          this.drain();
        }
        break;
      }
      case "stale": {
        if (this.inFlight && msg.client_seq === this.inFlight.seq) this.inFlight = null;
        this.waitFor = Math.max(this.waitFor, msg.current_version);
        if (msg.updates) {
          for (const u of msg.updates) if (u.version > this.version) this.pending.set(u.version, { changes: u.changes });
          this.drain();
        } else if (msg.current_version > this.version) {
          this.jump(msg.text, msg.current_version);
        }
        break;
      }
      case "presence": {
        if (msg.gone || msg.version === this.version) this.hooks.onPresence(msg, this.confirmed);
        break;
      }
      case "error": {
        if (this.inFlight && msg.client_seq === this.inFlight.seq) {
          // refused (too large, bad range): drop the local changes, back to the server's text
          this.inFlight = null;
          this.hooks.reset(this.confirmed);
        }
        break;
      }
      default:
        break;
    }
    this.hooks.onMessage(msg);
    queueMicrotask(() => {
      this.flush();
      if (msg.type === "ack" || msg.type === "state") this.sendPresence();
    });
  }
}
