// Text diffs in Unicode code points (the gateway's offsets), and rebasing a local change over a remote one.

/** Code-point length of a string. */
export function cpLength(s) {
  let n = 0;
  for (const _ of s) n++;
  return n;
}

/** Code-point offset -> UTF-16 index in s. */
export function cpToUtf16(s, cp) {
  let i = 0;
  let n = 0;
  while (n < cp && i < s.length) {
    const c = s.codePointAt(i);
    i += c > 0xffff ? 2 : 1;
    n++;
  }
  return i;
}

/** UTF-16 index -> code-point offset in s. */
export function utf16ToCp(s, index) {
  let i = 0;
  let n = 0;
  while (i < index && i < s.length) {
    const c = s.codePointAt(i);
    i += c > 0xffff ? 2 : 1;
    n++;
  }
  return n;
}

/**
 * The single change turning `before` into `after`: {start, end, text} in code points of `before`
 * (common prefix and suffix removed), or null when the texts are equal.
 */
export function diff(before, after) {
  if (before === after) return null;
  const a = Array.from(before);
  const b = Array.from(after);
  let p = 0;
  while (p < a.length && p < b.length && a[p] === b[p]) p++;
  let s = 0;
  while (s < a.length - p && s < b.length - p && a[a.length - 1 - s] === b[b.length - 1 - s]) s++;
  return { start: p, end: a.length - s, text: b.slice(p, b.length - s).join("") };
}

/** Apply changes (code points, base offsets, non-overlapping) to text. */
export function applyChanges(text, changes) {
  const cps = Array.from(text);
  const ordered = [...changes].sort((x, y) => y.start - x.start);
  for (const c of ordered) cps.splice(c.start, c.end - c.start, ...Array.from(c.text));
  return cps.join("");
}

/** Map a code-point offset of `base` through a change to the changed text. */
export function mapOffset(offset, change) {
  if (!change) return offset;
  const delta = cpLength(change.text) - (change.end - change.start);
  if (offset <= change.start) return offset;
  if (offset >= change.end) return offset + delta;
  return change.start + cpLength(change.text);
}

/**
 * Rebase local edits onto a newer server text. `base` is the text both started from. When the local and
 * remote changes touch the same characters, the server wins and the local change is dropped.
 * Returns {text, local} where local is the rebased local change (relative to `server`) or null.
 */
export function rebase(base, local, server) {
  const mine = diff(base, local);
  const theirs = diff(base, server);
  if (!mine) return { text: server, local: null };
  if (!theirs) return { text: local, local: mine };
  const overlap = mine.start < theirs.end && theirs.start < mine.end;
  const touching = mine.start === mine.end && theirs.start === theirs.end && mine.start === theirs.start;
  if (overlap || touching) return { text: server, local: null };
  const moved = mine.start >= theirs.end
    ? { start: mapOffset(mine.start, theirs), end: mapOffset(mine.end, theirs), text: mine.text }
    : mine;
  return { text: applyChanges(server, [moved]), local: moved };
}
