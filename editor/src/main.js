// The wana editor: text on the left, the live animation on the right, one WebSocket per document.

import "./style.css";
import {
  createDocument,
  deleteDocument,
  deleteCast,
  downloadExport,
  exportVideo,
  fetchExport,
  listCast,
  putCast,
  getDocument,
  listDocuments,
  renameDocument,
} from "./api.js";
import { directorCamera } from "./directorcam.js";
import { fillExamples, renderHelp } from "./help.js";
import { VOCABULARY } from "./vocabulary.js";
import { LiveDocument } from "./connection.js";
import { DiagnosticsMerge } from "./diagmerge.js";
import { Holdings } from "./holdings.js";
import { TextPane } from "./textpane.js";
import { Timeline } from "./timeline.js";
import { Tracks } from "./tracks.js";
import { Viewer } from "./viewer.js";

const $ = (id) => document.getElementById(id);

const state = {
  docId: null,
  live: null,
  version: null, // version of the last animation shown
  animation: null,
  diagnostics: null,
  diagMerge: null,
  tracksSentences: null, // the sentences (id:start:end) the timeline's clips were labelled with
  progress: null,
  messages: 0,
  lastInput: -Infinity, // when the writer last typed in the text (performance.now())
  pendingAnimation: null, // the newest animation, resolved, waiting for the writer to stop typing
  holdings: new Holdings(), // characters and objects of the last animation, by hash
  received: null, // what the last animation message carried: {version, unchanged, patched: [character names]}
};

const TYPING_QUIET_MS = 400;
const viewer = new Viewer($("viewport"));
// A key in the text counts as typing from its keydown (before CodeMirror handles it).
document.addEventListener(
  "keydown",
  (e) => {
    if (e.target.closest?.("#text")) state.lastInput = performance.now();
  },
  true,
);
const pane = new TextPane({
  parent: $("text"),
  list: $("diagnostics"),
  onInput: () => {
    state.lastInput = performance.now();
    state.live?.flush();
    updateExports();
  },
  onSelection: () => state.live?.sendPresence(),
  vocabulary: () => ({
    characters: (state.animation?.characters ?? []).map((c) => c.name),
    sceneObjects: (state.animation?.objects ?? []).map((o) => o.category),
  }),
});
const timeline = new Timeline({
  playButton: $("play"),
  scrub: $("scrub"),
  label: $("time"),
  onFrame: (f) => {
    viewer.setFrame(f);
    tracks.setFrame(f);
    pane.setActive(viewer.characters.flatMap((c) => c.activeSentences(f)));
  },
});

const tracks = new Tracks($("tracks"), {
  seek: (frame) => {
    timeline.pause();
    timeline.seek(frame / (state.animation?.fps || 30));
  },
  selectSentence: (sid) => {
    const s = state.diagnostics?.sentences.find((x) => x.id === sid);
    if (s) pane.select(s.start, s.end);
  },
});
$("speed").addEventListener("change", (e) => {
  timeline.speed = Number(e.target.value);
});
$("loop").addEventListener("change", (e) => {
  timeline.loop = e.target.checked;
});

/** A sentence's text (code points of the text the diagnostics were computed for), "" when unknown. */
function sentenceText(sid) {
  const s = state.diagnostics?.sentences.find((x) => x.id === sid);
  return s ? Array.from(pane.getText()).slice(s.start, s.end).join("") : "";
}

function showProgress(msg) {
  const fraction = msg.total ? msg.done / msg.total : 1;
  $("progress-bar").style.width = `${Math.round(60 * fraction)}px`;
  $("progress-text").textContent = `${msg.stage} ${msg.done}/${msg.total}`;
}

/** Show an animation message; its `unchanged` entries are filled from the last one (by content hash). */
function showAnimation(received) {
  const { message: msg, missing, unchanged, patched } = state.holdings.resolve(received);
  if (!msg) {
    // A stub of something this page does not hold (should not happen): get everything again.
    console.warn(`animation v${received.version}: ${missing.length} entries missing, resuming`);
    state.live.resume();
    return;
  }
  state.pendingAnimation = { msg, unchanged, patched };
  showWhenQuiet();
}

/** While the writer types the 3D view waits (keystrokes first); the newest animation is shown after. */
function typing() {
  return performance.now() - state.lastInput < TYPING_QUIET_MS;
}
function showWhenQuiet() {
  if (!state.pendingAnimation) return;
  if (typing()) {
    clearTimeout(state.quietTimer);
    state.quietTimer = setTimeout(showWhenQuiet, TYPING_QUIET_MS);
    return;
  }
  const { msg, unchanged, patched } = state.pendingAnimation;
  state.pendingAnimation = null;
  state.received = { version: msg.version, unchanged, patched };
  state.animation = msg;
  state.version = msg.version;
  viewer.setRoom(msg.room);
  viewer.setObjects(msg.objects);
  viewer.setCharacters(msg.characters); // rebuilds only the figures whose hash changed
  viewer.setCommands(msg.commands);
  scheduleSkinned(); // the skinned characters of this version, once the versions stop changing
  viewer.invalidate();
  timeline.setLength(msg.frames, msg.fps);
  tracks.render(msg, sentenceText);
  state.tracksSentences = state.diagnostics?.version === msg.version
    ? state.diagnostics.sentences.map((x) => `${x.id}:${x.start}:${x.end}`).join(",")
    : null;
  updateExports();
  $("progress-bar").style.width = "0";
  $("progress-text").textContent = msg.characters.length || msg.objects.length
    ? `v${msg.version}: ${msg.objects.length} objects, ${msg.characters.length} characters, ${msg.stats.total_ms ?? msg.stats.compute_ms} ms`
    : `v${msg.version}: nothing to animate yet`;
}

function onMessage(msg) {
  state.messages += 1;
  switch (msg.type) {
    case "state":
      $("doc-version").textContent = `v${msg.version}`;
      showPickerVersion(msg.version);
      $("export-status").textContent = "";
      updateExports();
      break;
    case "ack":
    case "remote_edit":
      $("doc-version").textContent = `v${msg.version}`;
      showPickerVersion(msg.version);
      break;
    case "progress":
      state.progress = msg;
      showProgress(msg);
      break;
    case "diagnostics": {
      const merged = state.diagMerge.apply(msg); // a delta: only the sentences whose diagnostics changed
      state.diagnostics = merged;
      pane.setDiagnostics(merged, state.live.version === merged.version ? state.live.confirmed : null);
      // the animation comes before its diagnostics: its clips get their sentences' text when they arrive
      const key = merged.sentences.map((x) => `${x.id}:${x.start}:${x.end}`).join(",");
      if (state.animation && key !== state.tracksSentences) {
        state.tracksSentences = key;
        tracks.render(state.animation, sentenceText);
      }
      break;
    }
    case "animation":
      showAnimation(msg);
      break;
    case "error":
      $("progress-text").textContent = `${msg.code}: ${msg.message}`;
      break;
    default:
      break;
  }
}

async function open(docId) {
  state.exportAbort?.abort(); // an export of the last document is cancelled: its status belonged there
  state.exportAbort = null;
  state.live?.close();
  state.docId = docId;
  state.version = null;
  state.holdings = new Holdings();
  state.diagMerge = new DiagnosticsMerge();
  state.animation = null;
  state.pendingAnimation = null;
  state.directorCam = null;
  if (viewer.exportScene) viewer.useExport(null); // the last document's skinned characters
  viewer.exportDoc = null;
  updateExports();
  $("cast-list").replaceChildren();
  $("cast-status").textContent = "";
  refreshCast(docId);
  if (location.hash !== `#doc=${docId}`) history.replaceState(null, "", `#doc=${docId}`);
  state.live = new LiveDocument(docId, {
    view: () => pane.view,
    reset: (text) => pane.reset(text),
    selection: () => pane.selectionCp(),
    onPresence: (msg, confirmed) => pane.showRemoteCaret(msg, confirmed),
    onMessage,
    onStatus: (status) => {
      const badge = $("connection");
      badge.textContent = status;
      badge.classList.toggle("online", status === "online");
    },
  });
  await refreshPicker();
}

/** The open document's entry in the picker shows its live version. */
function showPickerVersion(version) {
  const option = [...$("doc-picker").options].find((o) => o.value === state.docId);
  if (option) option.textContent = `${option.dataset.title} (v${version})`;
}

async function refreshPicker() {
  const picker = $("doc-picker");
  const docs = await listDocuments().catch(() => []);
  picker.innerHTML = "";
  for (const d of docs) {
    const option = document.createElement("option");
    option.value = d.doc_id;
    option.dataset.title = d.title || d.doc_id;
    option.textContent = `${option.dataset.title} (v${d.doc_id === state.docId && state.live?.version != null ? state.live.version : d.version})`;
    option.selected = d.doc_id === state.docId;
    picker.appendChild(option);
  }
}

$("doc-picker").addEventListener("change", (e) => open(e.target.value));
$("delete-doc").addEventListener("click", async () => {
  const title = $("doc-picker").selectedOptions[0]?.dataset.title ?? state.docId;
  if (!state.docId || !window.confirm(`Delete "${title}"? This cannot be undone.`)) return;
  const gone = state.docId;
  state.live?.close();
  await deleteDocument(gone).catch(() => null);
  const docs = await listDocuments().catch(() => []);
  const next = docs.find((d) => d.doc_id !== gone) ?? (await createDocument("", "untitled"));
  await open(next.doc_id);
});
$("rename-doc").addEventListener("click", async () => {
  const docId = state.docId;
  const current = $("doc-picker").selectedOptions[0]?.dataset.title ?? "";
  const title = window.prompt("Rename the document", current)?.trim();
  if (!docId || !title || title === current) return;
  try {
    await renameDocument(docId, title);
  } catch (err) {
    $("export-status").textContent = `rename failed: ${err.message}`;
    return;
  }
  await refreshPicker();
});
$("new-doc").addEventListener("click", async () => {
  const doc = await createDocument("", `untitled ${new Date().toLocaleString()}`);
  await open(doc.doc_id);
  pane.view.focus();
});
/** Exports need something to export: a non-empty text (and, for BVH, a character); one at a time. */
function updateExports() {
  const empty = !pane.getText().trim();
  for (const button of document.querySelectorAll("#exports button[data-format]")) {
    const noCharacters = button.dataset.format === "bvh" && !(state.animation?.characters ?? []).length;
    button.disabled = empty || noCharacters || !!state.exportAbort;
  }
  updateCastNames();
}

/** The cast row: the story's characters to pick from, and the ones your files play. */
function updateCastNames() {
  const select = $("cast-name");
  const names = (state.animation?.characters ?? []).map((c) => (typeof c === "string" ? c : c.name)).filter(Boolean);
  const have = [...select.options].map((o) => o.value);
  if (names.join("\n") === have.join("\n")) return;
  const chosen = select.value;
  select.replaceChildren(...names.map((n) => new Option(n, n, false, n === chosen)));
  $("cast-file").disabled = !names.length;
}

/** The 3D view shows the render service's scene.glb: fetch it again, now with (or without) the user's rig. */
function reskin(docId) {
  if (docId !== state.docId) return;
  viewer.exportVersion = null;
  scheduleSkinned();
}

async function refreshCast(docId = state.docId) {
  if (!docId) return;
  let cast = {};
  try {
    cast = await listCast(docId);
  } catch (err) {
    $("cast-status").textContent = String(err.message || err);
    return;
  }
  if (docId !== state.docId) return;
  $("cast-list").replaceChildren(
    ...Object.keys(cast).map((name) => {
      const item = document.createElement("li");
      item.dataset.name = name;
      item.append(`${name} `);
      const remove = document.createElement("button");
      remove.type = "button";
      remove.textContent = "×";
      remove.setAttribute("aria-label", `play ${name} with the built-in character again`);
      remove.addEventListener("click", async () => {
        await deleteCast(docId, name).catch(() => null);
        $("cast-status").textContent = `${name}: built-in character`;
        await refreshCast(docId);
        reskin(docId);
      });
      item.append(remove);
      return item;
    }),
  );
}

$("cast-file").addEventListener("change", async (e) => {
  const file = e.target.files?.[0];
  const name = $("cast-name").value;
  const docId = state.docId;
  e.target.value = "";
  if (!file || !name || !docId) return;
  const status = $("cast-status");
  status.textContent = `${name}: reading ${file.name}…`;
  try {
    const answer = await putCast(docId, name, file);
    status.textContent = `${name} plays ${file.name} (${answer.mapped} joints mapped); every export wears it`;
    reskin(docId);
  } catch (err) {
    status.textContent = `${name}: ${err.message || err}`;
  }
  await refreshCast(docId);
});
for (const button of document.querySelectorAll("#exports button[data-format]")) {
  button.addEventListener("click", async () => {
    const format = button.dataset.format;
    const docId = state.docId;
    const status = $("export-status");
    status.textContent = `${format.toUpperCase()}…`;
    if (format === "bvh") {
      // every character's BVH, in one zip
      const count = (state.animation?.characters ?? []).length;
      status.textContent = `BVH of ${count} character${count === 1 ? "" : "s"}…`;
      const message = await downloadExport(docId, "bvh", "*").catch((err) => String(err.message || err));
      if (docId === state.docId) status.textContent = message;
      return;
    }
    // The others render on the server and may be cancelled; the MP4 is a job that reports the frames
    // rendered of the total (services/gateway/videojobs.py), the rest show the time taken.
    const abort = new AbortController();
    const started = performance.now();
    const cancel = $("export-cancel");
    const bar = $("export-progress");
    cancel.hidden = false;
    cancel.onclick = () => abort.abort();
    state.exportAbort = abort; // opening another document cancels it
    updateExports();
    const label = format.toUpperCase();
    const ticker =
      format === "mp4"
        ? null
        : setInterval(() => {
            if (docId === state.docId) status.textContent = `${label} rendering… ${((performance.now() - started) / 1000).toFixed(0)} s`;
          }, 500);
    const onProgress = (job) => {
      if (docId !== state.docId) return;
      bar.hidden = false;
      bar.value = job.percent;
      status.textContent =
        job.total && job.stage === "rendering"
          ? `MP4 ${Math.floor(job.percent)}% (${job.done} of ${job.total} frames)`
          : job.stage === "joining"
            ? `MP4 100% (${job.total} frames), joining…`
            : `MP4 ${job.stage}…`;
    };
    let message;
    try {
      const cycles = format === "mp4" && $("export-cycles").checked ? { renderer: "blender" } : {};
      message =
        format === "mp4"
          ? await exportVideo(docId, onProgress, abort.signal, cycles)
          : await downloadExport(docId, format, "", abort.signal);
    } catch (err) {
      message = String(err.message || err);
    } finally {
      clearInterval(ticker);
      cancel.hidden = true;
      bar.hidden = true;
      if (state.exportAbort === abort) state.exportAbort = null;
      updateExports();
    }
    if (docId === state.docId) status.textContent = message;
  });
}
$("help-toggle").addEventListener("click", () => {
  const help = $("help");
  help.hidden = !help.hidden;
  $("help-toggle").setAttribute("aria-expanded", String(!help.hidden));
  if (!help.hidden) help.querySelector("summary")?.focus();
});
renderHelp($("help"));
fillExamples($("example-picker"));
$("example-picker").addEventListener("change", async (e) => {
  const example = VOCABULARY.examples[Number(e.target.value)];
  e.target.value = "";
  if (!example) return;
  const doc = await createDocument(example.text, example.title);
  await open(doc.doc_id);
});
$("viewport").addEventListener("keydown", (e) => {
  const step = Math.PI / 18;
  const moves = { ArrowLeft: [step, 0], ArrowRight: [-step, 0], ArrowUp: [0, step], ArrowDown: [0, -step] };
  const move = moves[e.key];
  if (move) {
    e.preventDefault();
    viewer.orbitBy(...move);
  } else if (e.key === "f") {
    viewer.frameCharacters();
  } else if (e.key === " ") {
    e.preventDefault();
    timeline.toggle();
  }
});
$("focus").addEventListener("click", () => viewer.frameCharacters());

// "Director" plays the camera the MP4 is rendered with (read from the render service's scene.glb);
// "Free camera" gives it back to the mouse. Fetched again when a new version arrives while it is on.
const directorButton = document.createElement("button");
directorButton.type = "button";
directorButton.id = "director";
directorButton.title = "play the director's camera (the MP4's) or orbit freely";
directorButton.textContent = "Free camera";
$("focus").after(directorButton);
state.directorOn = false;
// Both cameras show the render service's skinned characters (its scene.glb of the version shown: preview =
// export), from the first animation on; it is fetched once the versions stop changing for SKIN_QUIET_MS, and
// the capsule figures stand in until it arrives (or when the render service is not available).
const SKIN_QUIET_MS = 600;
let skinTimer = null;
let skinning = false;
function scheduleSkinned() {
  clearTimeout(skinTimer);
  skinTimer = setTimeout(loadSkinned, SKIN_QUIET_MS);
}
async function loadSkinned() {
  const { docId, version } = state;
  if (!docId || version === null || !(state.animation?.characters ?? []).length) {
    if (viewer.exportScene) viewer.useExport(null);
    return viewer.useDirector(null);
  }
  if (viewer.exportVersion === version && viewer.exportDoc === docId) {
    if (state.directorOn !== !!viewer.director) viewer.useDirector(state.directorOn ? state.directorCam : null);
    return;
  }
  if (skinning || typing()) return scheduleSkinned();
  skinning = true;
  try {
    const glb = await fetchExport(docId, "glb");
    if (version !== state.version || docId !== state.docId) return;
    state.directorCam = directorCamera(glb);
    viewer.useDirector(state.directorOn ? state.directorCam : null);
    await viewer.useExport(glb, version);
    viewer.exportDoc = docId;
  } catch (err) {
    if (state.directorOn && docId === state.docId) $("export-status").textContent = String(err.message || err);
    if (viewer.exportScene && viewer.exportDoc !== state.docId) viewer.useExport(null); // another document's
  } finally {
    skinning = false;
  }
}
function loadDirector() {
  if (!state.directorOn) viewer.useDirector(null);
  else if (viewer.exportVersion === state.version && state.directorCam) viewer.useDirector(state.directorCam);
  loadSkinned();
}
directorButton.addEventListener("click", () => {
  state.directorOn = !state.directorOn;
  directorButton.textContent = state.directorOn ? "Director" : "Free camera";
  loadDirector();
});
document.addEventListener("keydown", (e) => {
  if (e.target !== document.body) return; // typing in the text
  if (e.code === "Space") {
    e.preventDefault();
    timeline.toggle();
  } else if (e.key === "f") {
    viewer.frameCharacters();
  }
});

// While the writer types (and TYPING_QUIET_MS after the last key), the 3D view is not drawn and new
// animations wait, so a keystroke never queues behind a frame of the (software-rendered) scene; playback
// holds while the writer types and goes on when typing stops.
function frameLoop() {
  if (!typing()) {
    timeline.tick(performance.now()); // poses the figures and highlights the sentences playing
    viewer.render();
  }
  requestAnimationFrame(frameLoop);
}
requestAnimationFrame(frameLoop);

async function start() {
  const wanted = /#doc=([A-Za-z0-9_-]+)/.exec(location.hash)?.[1];
  try {
    if (wanted) {
      await getDocument(wanted);
      return open(wanted);
    }
    const docs = await listDocuments();
    if (docs.length) return open(docs[0].doc_id);
    const doc = await createDocument("", "untitled");
    return open(doc.doc_id);
  } catch (error) {
    $("connection").textContent = `error: ${error.message}`;
  }
}
window.addEventListener("hashchange", () => {
  const wanted = /#doc=([A-Za-z0-9_-]+)/.exec(location.hash)?.[1];
  if (wanted && wanted !== state.docId) open(wanted);
});

// For tests and the curious: the scene graph and the live state.
window.wana = { state, viewer, pane, timeline, onMessage };
start();
