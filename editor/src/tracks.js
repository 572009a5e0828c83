// The timeline's tracks: one per character with a clip per action (labelled with its sentence), the camera
// commands on a track of their own, and a playhead. A clip is a button: clicking it (or Enter) seeks to its
// start and selects its sentence in the text.

function clipLabel(action, sentence) {
  const words = sentence ? sentence.trim().replace(/\s+/g, " ") : "";
  return words ? `${action.replace(/_/g, " ")}: ${words}` : action.replace(/_/g, " ");
}

export class Tracks {
  /**
   * @param {HTMLElement} root
   * @param {{seek: (frame: number) => void, selectSentence: (id: string) => void}} hooks
   */
  constructor(root, hooks) {
    this.root = root;
    this.hooks = hooks;
    this.frames = 0;
    this.playhead = null;
  }

  /**
   * @param {object} animation the animation message (characters with segments, commands, frames)
   * @param {(id: string) => string} sentenceText the text of a sentence id ("" when unknown)
   */
  render(animation, sentenceText) {
    this.root.innerHTML = "";
    this.frames = Math.max(animation?.frames ?? 0, 1);
    if (!animation || (!animation.characters.length && !animation.commands.length)) return;
    const rows = animation.characters.map((c) => ({
      name: c.name,
      clips: c.segments
        .filter((s) => s.action !== "hold" && s.end_frame > s.start_frame)
        .map((s) => ({ start: s.start_frame, end: s.end_frame, sid: s.sentence_id, label: clipLabel(s.action, sentenceText(s.sentence_id)) })),
    }));
    const shots = animation.commands.filter((c) => c.kind === "camera");
    if (shots.length) {
      // a camera command holds until the next one
      const starts = shots.map((c) => this.startOf(animation, c.sentence_id));
      rows.push({
        name: "camera",
        clips: shots.map((c, i) => ({
          start: starts[i],
          end: i + 1 < shots.length ? Math.max(starts[i + 1], starts[i] + 1) : this.frames,
          sid: c.sentence_id,
          label: `camera ${c.value}`,
        })),
      });
    }
    for (const row of rows) {
      const track = document.createElement("div");
      track.className = "track";
      track.setAttribute("role", "group");
      track.setAttribute("aria-label", `${row.name}'s track`);
      const name = document.createElement("span");
      name.className = "track-name";
      name.textContent = row.name;
      const lane = document.createElement("div");
      lane.className = "lane";
      for (const clip of row.clips) {
        const b = document.createElement("button");
        b.type = "button";
        b.className = "clip";
        b.style.left = `${(100 * clip.start) / this.frames}%`;
        b.style.width = `${(100 * (clip.end - clip.start)) / this.frames}%`;
        b.textContent = clip.label;
        b.title = clip.label;
        b.dataset.sentence = clip.sid ?? "";
        b.setAttribute("aria-label", `${row.name}: ${clip.label}, at ${(clip.start / (animation.fps || 30)).toFixed(1)} s`);
        b.addEventListener("click", () => {
          this.hooks.seek(clip.start);
          if (clip.sid) this.hooks.selectSentence(clip.sid);
        });
        lane.appendChild(b);
      }
      track.append(name, lane);
      this.root.appendChild(track);
    }
    this.playhead = document.createElement("div");
    this.playhead.className = "playhead";
    this.playhead.setAttribute("aria-hidden", "true");
    this.root.appendChild(this.playhead);
  }

  /** The first frame any character acts on a sentence (0 when none does). */
  startOf(animation, sid) {
    const starts = animation.characters.flatMap((c) => c.segments.filter((s) => s.sentence_id === sid).map((s) => s.start_frame));
    return starts.length ? Math.min(...starts) : 0;
  }

  setFrame(frame) {
    if (this.playhead) this.playhead.style.left = `calc(12px + var(--track-name) + (100% - 24px - var(--track-name)) * ${frame / this.frames})`;
  }
}
