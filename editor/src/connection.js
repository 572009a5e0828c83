// The live document: keeps the text in sync with the gateway over the document WebSocket.
//
// One edit is in flight at a time, always based on the last acknowledged version, so edits typed while
// waiting are coalesced into the next one. A `stale` reply or a `remote_edit` from another client is
// rebased; on reconnect the client resumes with its last version and rebases onto the server's text.

import { liveUrl } from "./api.js";
import { applyChanges, diff, rebase } from "./textdiff.js";

export class LiveDocument {
  /**
   * @param {string} docId
   * @param {{getText: () => string, setText: (text: string, change: object|null) => void,
   *          onMessage: (msg: object) => void, onStatus: (status: string) => void}} hooks
   */
  constructor(docId, hooks) {
    this.docId = docId;
    this.hooks = hooks;
    this.version = null; // last version acknowledged by the server
    this.confirmed = ""; // the text at `version`
    this.inFlight = null; // {text, seq} of the edit awaiting its ack
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
    ws.onmessage = (event) => this.receive(JSON.parse(event.data));
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

  /** Call after every local change of the text; sends it when no edit is in flight. */
  flush() {
    if (!this.ready || this.inFlight || this.ws.readyState !== WebSocket.OPEN) return;
    const text = this.hooks.getText();
    const change = diff(this.confirmed, text);
    if (!change) return;
    this.seq += 1;
    this.inFlight = { text, seq: this.seq };
    this.ws.send(JSON.stringify({ type: "edit", base_version: this.version, changes: [change], client_seq: this.seq }));
  }

  adopt(serverText, version) {
    const local = this.hooks.getText();
    const { text, local: change } = rebase(this.confirmed, local, serverText);
    this.confirmed = serverText;
    this.version = version;
    if (text !== local) this.hooks.setText(text, change);
  }

  receive(msg) {
    switch (msg.type) {
      case "state": {
        if (this.inFlight && msg.text === this.inFlight.text) {
          this.confirmed = msg.text; // the edit in flight when the connection dropped was acknowledged
          this.version = msg.version;
        } else if (this.version === null) {
          this.confirmed = msg.text;
          this.version = msg.version;
          this.hooks.setText(msg.text, null);
        } else {
          this.adopt(msg.text, msg.version);
        }
        this.inFlight = null;
        this.ready = true;
        break;
      }
      case "ack": {
        if (this.inFlight && msg.client_seq === this.inFlight.seq) {
          this.confirmed = this.inFlight.text;
          this.version = msg.version;
          this.inFlight = null;
        }
        break;
      }
      case "stale": {
        this.inFlight = null;
        this.adopt(msg.text, msg.current_version);
        break;
      }
      case "remote_edit": {
        if (msg.base_version === this.version && !this.inFlight) {
          this.adopt(applyChanges(this.confirmed, msg.changes), msg.version);
        }
        // with an edit in flight, the server answers it `stale` and we rebase then
        break;
      }
      case "error": {
        if (this.inFlight && msg.client_seq === this.inFlight.seq) {
          this.inFlight = null; // refused (too large, bad range): go back to the server's text
          this.hooks.setText(this.confirmed, null);
        }
        break;
      }
      default:
        break;
    }
    this.hooks.onMessage(msg);
    queueMicrotask(() => this.flush());
  }
}
