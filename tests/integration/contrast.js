// WCAG 2.x contrast of what the page shows now (run in the page by test_editor_contrast.py).
// Text: every visible element with its own text (and buttons, selects, inputs), its colour over the
// backgrounds under it composited from the element up to the page; 4.5:1, or 3:1 for large text (24 px, or
// 18.66 px bold). Disabled controls are exempt (WCAG 1.4.3). Non-text (WCAG 1.4.11), 3:1 against the
// background they sit on: the borders of buttons and selects, the focus ring of the focused element, and
// the lint marks' underlines (CodeMirror draws them as an SVG wave whose stroke colour is in the CSS).
(mode) => {
  const parse = (s) => {
    const m = /rgba?\(([^)]+)\)/.exec(s || "");
    if (!m) return null;
    const p = m[1].split(/[\s,/]+/).filter(Boolean).map(Number);
    return [p[0], p[1], p[2], p.length > 3 ? p[3] : 1];
  };
  const hex = (h) => {
    const x = h.length === 3 ? [...h].map((c) => c + c).join("") : h;
    return [parseInt(x.slice(0, 2), 16), parseInt(x.slice(2, 4), 16), parseInt(x.slice(4, 6), 16), 1];
  };
  const over = (top, bottom) => {
    const a = top[3];
    return [0, 1, 2].map((i) => top[i] * a + bottom[i] * (1 - a)).concat(1);
  };
  const lum = (c) => {
    const [r, g, b] = c.slice(0, 3).map((v) => {
      const s = v / 255;
      return s <= 0.04045 ? s / 12.92 : ((s + 0.055) / 1.055) ** 2.4;
    });
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
  };
  const ratio = (a, b) => {
    const [hi, lo] = [lum(a), lum(b)].sort((x, y) => y - x);
    return (hi + 0.05) / (lo + 0.05);
  };
  // the opaque colour under an element: its own background and its ancestors', composited
  const backdrop = (el, includeSelf = true) => {
    const chain = [];
    for (let e = includeSelf ? el : el.parentElement; e; e = e.parentElement) chain.push(e);
    let base = [255, 255, 255, 1];
    for (const e of chain.reverse()) {
      const c = parse(getComputedStyle(e).backgroundColor);
      if (c && c[3] > 0) base = over(c, base);
    }
    return base;
  };
  const visible = (el) => {
    const r = el.getBoundingClientRect();
    if (r.width <= 1 || r.height <= 1) return false; // sr-only text is 1 px
    for (let e = el; e; e = e.parentElement) {
      const s = getComputedStyle(e);
      if (s.display === "none" || s.visibility === "hidden" || Number(s.opacity) === 0) return false;
      if (s.clip && s.clip !== "auto" && s.position === "absolute") return false;
    }
    return true;
  };
  const name = (el) =>
    `${el.tagName.toLowerCase()}${el.id ? "#" + el.id : ""}${el.className && typeof el.className === "string" ? "." + el.className.trim().split(/\s+/).join(".") : ""}`;
  const out = [];
  const seen = new Set();
  const ringOf = (el) => {
    const s = getComputedStyle(el);
    const ring = parse(s.outlineColor);
    if (s.outlineStyle === "none" || !(parseFloat(s.outlineWidth) > 0) || !ring) return null;
    const around = backdrop(el, parseFloat(s.outlineOffset) < 0); // an inset ring lies on the element
    return ratio(over(ring, around), around);
  };
  if (mode === "focus") {
    // the focused element's ring (CodeMirror draws it on the editor around the focused content)
    const focused = document.activeElement;
    if (!focused || focused === document.body) return [];
    const target = focused.closest(".cm-editor") || focused;
    const r = ringOf(target);
    return [{ kind: "focus", element: name(target), text: (target.innerText || "").trim().slice(0, 20), ratio: r ?? 1, need: 3, ring: r !== null }];
  }
  for (const el of document.querySelectorAll("body *")) {
    if (["SCRIPT", "STYLE", "CANVAS", "OPTION", "svg", "path"].includes(el.tagName)) continue;
    const own = [...el.childNodes].some((n) => n.nodeType === 3 && n.textContent.trim());
    const control = ["BUTTON", "SELECT"].includes(el.tagName);
    if (!own && !control) continue;
    if (!visible(el)) continue;
    if (el.closest(":disabled, [aria-disabled=true]")) continue;
    const s = getComputedStyle(el);
    const bg = backdrop(el);
    const fg = over(parse(s.color), bg);
    const size = parseFloat(s.fontSize);
    const large = size >= 24 || (size >= 18.66 && Number(s.fontWeight) >= 700);
    const text = (el.innerText || el.value || "").trim().slice(0, 40);
    const key = `${name(el)}|${s.color}|${bg.join()}`;
    if (seen.has(key)) continue;
    seen.add(key);
    out.push({ kind: "text", element: name(el), text, ratio: ratio(fg, bg), need: large ? 3 : 4.5 });
  }
  for (const el of document.querySelectorAll("button, select")) {
    if (!visible(el) || el.disabled) continue;
    const s = getComputedStyle(el);
    const around = backdrop(el, false);
    const border = parse(s.borderTopColor);
    const own = parse(s.backgroundColor) || [0, 0, 0, 0];
    const bordered = parseFloat(s.borderTopWidth) > 0 && border && border[3] > 0;
    if (!bordered && own[3] === 0) continue; // a control drawn as text alone: its text identifies it
    const fill = over(own, around);
    // the component is told apart from what is around it by its border or by its fill
    const best = Math.max(
      bordered ? ratio(over(border, around), around) : 1,
      ratio(fill, around),
    );
    const key = `boundary|${el.tagName}|${s.borderTopColor}|${s.backgroundColor}|${around.join()}`;
    if (seen.has(key)) continue;
    seen.add(key);
    out.push({ kind: "boundary", element: name(el), text: (el.innerText || "").trim().slice(0, 20), ratio: best, need: 3 });
  }
  for (const el of document.querySelectorAll(".cm-lintRange")) {
    if (!visible(el)) continue;
    const img = getComputedStyle(el).backgroundImage;
    const m = /stroke(?:=|%3D)(?:"|'|%22|%27|\\")*(?:#|%23)?([0-9a-fA-F]{6}|[0-9a-fA-F]{3}|[a-z]+)/i.exec(img);
    if (!m) continue;
    if (!/^[0-9a-f]{3,6}$/i.test(m[1])) {
      const ctx = document.createElement("canvas").getContext("2d"); // a colour name, as the browser reads it
      ctx.fillStyle = m[1];
      m[1] = ctx.fillStyle.slice(1);
    }
    const bg = backdrop(el);
    const key = `lint|${m[1]}|${bg.join()}`;
    if (seen.has(key)) continue;
    seen.add(key);
    out.push({ kind: "lint mark", element: name(el), text: el.textContent.slice(0, 20), ratio: ratio(hex(m[1]), bg), need: 3 });
  }
  return out;
};
