// Other tabs' carets and selections: a decoration per remote client, mapped through every change.

import { StateEffect, StateField } from "@codemirror/state";
import { Decoration, EditorView, WidgetType } from "@codemirror/view";

const COLOURS = ["#ff8a65", "#81c784", "#ba68c8", "#4dd0e1", "#fff176", "#f06292"];

function colourOf(id) {
  let h = 0;
  for (const c of id) h = (h * 31 + c.charCodeAt(0)) >>> 0;
  return COLOURS[h % COLOURS.length];
}

class CaretWidget extends WidgetType {
  constructor(id) {
    super();
    this.id = id;
  }
  eq(other) {
    return other.id === this.id;
  }
  toDOM() {
    const span = document.createElement("span");
    span.className = "cm-remote-caret";
    span.style.borderLeftColor = colourOf(this.id);
    span.setAttribute("aria-hidden", "true");
    span.dataset.client = this.id;
    return span;
  }
}

/** {client, anchor, head} in positions of the document now; head null removes the client's caret. */
export const setRemoteCaret = StateEffect.define();

export const remoteCarets = StateField.define({
  create: () => new Map(), // client -> {anchor, head}
  update(carets, tr) {
    let next = carets;
    if (!tr.changes.empty) {
      next = new Map();
      for (const [id, c] of carets) next.set(id, { anchor: tr.changes.mapPos(c.anchor), head: tr.changes.mapPos(c.head) });
    }
    for (const e of tr.effects) {
      if (!e.is(setRemoteCaret)) continue;
      if (next === carets) next = new Map(carets);
      if (e.value.head === null) next.delete(e.value.client);
      else next.set(e.value.client, { anchor: e.value.anchor, head: e.value.head });
    }
    return next;
  },
  provide: (f) =>
    EditorView.decorations.from(f, (carets) => {
      const ranges = [];
      for (const [id, c] of carets) {
        const from = Math.min(c.anchor, c.head);
        const to = Math.max(c.anchor, c.head);
        if (to > from) {
          ranges.push(Decoration.mark({ class: "cm-remote-selection", attributes: { style: `background-color: ${colourOf(id)}33` } }).range(from, to));
        }
        ranges.push(Decoration.widget({ widget: new CaretWidget(id), side: 1 }).range(c.head));
      }
      return Decoration.set(ranges, true);
    }),
});
