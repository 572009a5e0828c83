// The help panel: what can be said, generated from the catalog, the action library and the command set
// (vocabulary.json), and the example stories.

import { VOCABULARY } from "./vocabulary.js";

function section(title, intro, items) {
  const details = document.createElement("details");
  const summary = document.createElement("summary");
  summary.textContent = `${title} (${items.length})`;
  const p = document.createElement("p");
  p.textContent = intro;
  const list = document.createElement("p");
  list.className = "words";
  list.textContent = items.join(", ");
  details.append(summary, p, list);
  return details;
}

/** Fill the help panel. */
export function renderHelp(panel) {
  panel.innerHTML = "";
  const h = document.createElement("h2");
  h.textContent = "What you can write";
  const rule = document.createElement("p");
  rule.innerHTML =
    "A sentence ending in <kbd>$</kbd> describes the scene: <em>A lamp is on the desk$.</em> " +
    "Other sentences make characters act: <em>Eve walks to the desk. She sits on the chair.</em> " +
    "A line on its own can be a command: <em>camera left</em>, <em>night</em>, <em>wait 2 seconds</em>.";
  const keys = document.createElement("p");
  keys.innerHTML =
    "Keys: <kbd>Ctrl</kbd>+<kbd>Space</kbd> completes a word, <kbd>Ctrl</kbd>+<kbd>.</kbd> applies a quick fix, " +
    "<kbd>Ctrl</kbd>+<kbd>Shift</kbd>+<kbd>M</kbd> lists the diagnostics, <kbd>F8</kbd> goes to the next one; " +
    "in the 3D view the arrow keys orbit and <kbd>f</kbd> frames the characters; <kbd>Space</kbd> plays.";
  panel.append(
    h,
    rule,
    keys,
    section("Commands", "On a line of their own.", VOCABULARY.commands),
    section("Actions", "What a character can do (walks, runs and turns go anywhere).", VOCABULARY.actions),
    section("Objects", "What a scene sentence can put in the room.", VOCABULARY.objects),
  );
}

/** Fill the example picker with the example stories. */
export function fillExamples(select) {
  VOCABULARY.examples.forEach((ex, i) => {
    const option = document.createElement("option");
    option.value = String(i);
    option.textContent = ex.title;
    select.appendChild(option);
  });
}
