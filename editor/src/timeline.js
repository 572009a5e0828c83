// Play, pause and scrub through the animation; reports the current frame on every tick.

export class Timeline {
  constructor({ playButton, scrub, label, onFrame }) {
    this.playButton = playButton;
    this.scrub = scrub;
    this.label = label;
    this.onFrame = onFrame;
    this.fps = 30;
    this.frames = 0;
    this.time = 0; // seconds
    this.playing = true;
    this.last = null;
    this.speed = 1; // playback rate
    this.loop = true; // at the end: start again, or stop
    playButton.addEventListener("click", () => this.toggle());
    scrub.addEventListener("input", () => {
      this.pause();
      this.seek(Number(scrub.value) / this.fps);
    });
    this.updateButton();
  }

  setLength(frames, fps) {
    this.frames = frames;
    this.fps = fps || 30;
    this.scrub.max = String(Math.max(frames - 1, 0));
    this.seek(Math.min(this.time, Math.max(frames - 1, 0) / this.fps));
  }

  get frame() {
    return Math.min(Math.floor(this.time * this.fps + 1e-6), Math.max(this.frames - 1, 0));
  }

  toggle() {
    if (this.playing) this.pause();
    else this.play();
  }

  play() {
    this.playing = true;
    this.last = null;
    this.updateButton();
  }

  pause() {
    this.playing = false;
    this.updateButton();
  }

  seek(seconds) {
    this.time = Math.max(0, seconds);
    this.scrub.value = String(this.frame);
    this.label.textContent = `${this.time.toFixed(2)} s / ${(this.frames / this.fps).toFixed(2)} s`;
    this.onFrame(this.frame);
  }

  /** Advance by wall-clock time (called every animation frame); loops at the end. */
  tick(now) {
    if (this.playing && this.frames > 1) {
      const dt = this.last === null ? 0 : (now - this.last) / 1000;
      let t = this.time + Math.min(dt, 0.25) * this.speed;
      const length = this.frames / this.fps;
      if (t >= length) {
        if (this.loop) t = t % length;
        else {
          t = Math.max(length - 1 / this.fps, 0);
          this.pause();
        }
      }
      this.seek(t);
    }
    this.last = now;
  }

  updateButton() {
    this.playButton.textContent = this.playing ? "❚❚" : "▶";
    this.playButton.setAttribute("aria-pressed", String(this.playing));
  }
}
