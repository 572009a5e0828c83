// The three.js viewer: room, catalog objects (GLB fetched once per variant), characters, orbit camera,
// camera presets and light from the text's commands.

import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { GLTFLoader } from "three/examples/jsm/loaders/GLTFLoader.js";
import { cameraAt } from "./directorcam.js";

import { apiUrl, authHeaders } from "./api.js";
import { CharacterFigure } from "./character.js";

// The MP4's clear colour in its default light (services/render/weather.py, LOOKS' default background).
const VIDEO_BACKGROUND = [0.62, 0.78, 0.95];
const CATEGORY_COLOURS = [0x8d6e63, 0x90a4ae, 0xa1887f, 0x78909c, 0xbcaaa4, 0x607d8b];

function hashColour(category) {
  let h = 0;
  for (const c of category) h = (h * 31 + c.charCodeAt(0)) >>> 0;
  return CATEGORY_COLOURS[h % CATEGORY_COLOURS.length];
}

export class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.shadowMap.enabled = true;
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x2a2f38);
    this.camera = new THREE.PerspectiveCamera(50, 1, 0.05, 200);
    this.camera.position.set(0, 2.2, 6);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0, 0.9, 0);
    this.controls.enableDamping = true;
    this.hemi = new THREE.HemisphereLight(0xffffff, 0x444455, 1.4);
    this.sun = new THREE.DirectionalLight(0xffffff, 1.6);
    this.sun.position.set(3, 6, 4);
    this.sun.castShadow = true;
    this.sun.shadow.mapSize.set(1024, 1024);
    this.sun.shadow.bias = -0.0005;
    this.sun.shadow.normalBias = 0.02;
    Object.assign(this.sun.shadow.camera, { left: -6, right: 6, top: 6, bottom: -6, far: 30 });
    this.scene.add(this.hemi, this.sun);
    // While the export plays: a light from the lens, as the video's renderer lights what it sees.
    // Intensities times pi: three.js divides diffuse light by pi (physical units); the video's Phong
    // light gives a surface facing the lens about 1.3 times its colour and one seen edge-on about half.
    this.headlight = new THREE.DirectionalLight(0xffffff, 0.8 * Math.PI);
    this.ambient = new THREE.AmbientLight(0xffffff, 0.5 * Math.PI);
    this.ambient.visible = false;
    this.scene.add(this.ambient);
    this.headlight.position.set(0, 0, 1);
    this.headlight.target.position.set(0, 0, -1);
    this.headlight.visible = false;
    this.camera.add(this.headlight, this.headlight.target);
    this.scene.add(this.camera);
    this.exportScene = null;
    this.exportMixer = null;
    this.exportCharacters = [];
    this.exportVersion = null;
    this.roomGroup = new THREE.Group();
    this.roomGroup.name = "room";
    this.objectGroup = new THREE.Group();
    this.objectGroup.name = "objects";
    this.characterGroup = new THREE.Group();
    this.characterGroup.name = "characters";
    this.scene.add(this.roomGroup, this.objectGroup, this.characterGroup);
    this.loader = new GLTFLoader();
    this.loader.setRequestHeader(authHeaders());
    this.meshes = new Map(); // mesh URL -> Promise<THREE.Object3D | null>
    this.characters = [];
    this.lastCharacterUpdate = { built: [], kept: [] };
    this.objects = new Map(); // object id -> {key, node}
    this.room = null;
    this.cameraKey = "";
    this.follow = null;
    this.frame = -1;
    this.director = null; // the director's camera (directorcam.js) while "Director" is on
    this.dirty = true; // render only when something changed: software GL in a test browser is slow
    this.controls.addEventListener("change", () => this.invalidate());
    this.setRoom(null);
    this.cameraPreset("");
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (!w || !h) return;
    const aspect = this.director?.aspect;
    if (aspect) {
      // The video's picture: its aspect, as large as fits, centred (the MP4's framing, not a crop of it).
      const fw = Math.min(w, Math.round(h * aspect));
      const fh = Math.min(h, Math.round(fw / aspect));
      this.renderer.setSize(fw, fh, true);
      this.camera.aspect = fw / fh;
    } else {
      this.renderer.setSize(w, h, false);
      this.renderer.domElement.style.width = this.renderer.domElement.style.height = "";
      this.camera.aspect = w / h;
    }
    this.container.classList.toggle("video", Boolean(aspect));
    this.camera.updateProjectionMatrix();
    this.invalidate();
  }

  invalidate() {
    this.dirty = true;
  }

  setRoom(room) {
    const r = room || { room_type: "", width: 6, depth: 6, height: 2.8 };
    const key = `${r.width}x${r.depth}x${r.height}`;
    if (this.room === key) return;
    this.room = key;
    this.roomGroup.clear();
    const floor = new THREE.Mesh(
      new THREE.PlaneGeometry(r.width, r.depth),
      new THREE.MeshStandardMaterial({ color: 0x6b6257, roughness: 0.9 }),
    );
    floor.rotation.x = -Math.PI / 2;
    floor.receiveShadow = true;
    floor.name = "floor";
    const grid = new THREE.GridHelper(Math.max(r.width, r.depth), Math.round(Math.max(r.width, r.depth) * 2), 0x888888, 0x555555);
    grid.position.y = 0.002;
    grid.material.transparent = true;
    grid.material.opacity = 0.25;
    // Walls face inward and are culled from behind, so a camera outside the room still sees in.
    const wallMaterial = new THREE.MeshStandardMaterial({ color: 0xb8b2a7, roughness: 1, side: THREE.FrontSide });
    const walls = [
      [r.width, 0, -r.depth / 2, 0],
      [r.width, 0, r.depth / 2, Math.PI],
      [r.depth, -r.width / 2, 0, Math.PI / 2],
      [r.depth, r.width / 2, 0, -Math.PI / 2],
    ].map(([length, x, z, yaw]) => {
      const wall = new THREE.Mesh(new THREE.PlaneGeometry(length, r.height), wallMaterial);
      wall.position.set(x, r.height / 2, z);
      wall.rotation.y = yaw;
      wall.receiveShadow = true;
      return wall;
    });
    this.roomGroup.add(floor, grid, ...walls);
    this.roomSize = r;
    this.cameraKey = null; // a new room: place the camera again
    this.invalidate();
  }

  /** The GLB of one object variant, fetched once; null (a box is drawn) when the gateway cannot make it. */
  mesh(url) {
    if (!this.meshes.has(url)) {
      this.meshes.set(url, this.loader.loadAsync(apiUrl(url)).then((gltf) => gltf.scene, () => null));
    }
    return this.meshes.get(url);
  }

  setObjects(objects) {
    const seen = new Set();
    for (const o of objects) {
      seen.add(o.id);
      const key = JSON.stringify([o.mesh_url, o.position, o.yaw, o.scale]);
      const existing = this.objects.get(o.id);
      if (existing && existing.key === key) continue;
      if (existing) this.objectGroup.remove(existing.node);
      const node = new THREE.Group();
      node.name = `object:${o.id}`;
      node.userData = { kind: "object", id: o.id, category: o.category };
      node.position.fromArray(o.position);
      node.rotation.y = o.yaw;
      node.scale.fromArray(o.scale);
      this.objectGroup.add(node);
      this.objects.set(o.id, { key, node });
      this.mesh(o.mesh_url).then((template) => {
        if (this.objects.get(o.id)?.node !== node) return;
        if (template) {
          const copy = template.clone(true);
          copy.traverse((m) => {
            if (m.isMesh) m.castShadow = m.receiveShadow = true;
          });
          node.add(copy);
        } else {
          const box = new THREE.Mesh(
            new THREE.BoxGeometry(0.5, 0.5, 0.5),
            new THREE.MeshStandardMaterial({ color: hashColour(o.category), transparent: true, opacity: 0.8 }),
          );
          box.position.y = 0.25;
          node.add(box);
        }
        this.invalidate();
      });
    }
    for (const [id, entry] of this.objects) {
      if (!seen.has(id)) {
        this.objectGroup.remove(entry.node);
        this.objects.delete(id);
      }
    }
  }

  /**
   * Show these characters. A figure whose entry has the same name, content hash and place as before is
   * kept as it is; only the others are rebuilt. The current frame and the camera are kept.
   * @returns {{built: string[], kept: string[]}} names of the figures rebuilt and kept
   */
  setCharacters(characters) {
    const previous = new Map(this.characters.map((c) => [c.key, c]));
    const built = [];
    const kept = [];
    this.characters = characters.map((data, i) => {
      const key = data.hash ? `${i}\u0000${data.name}\u0000${data.hash}` : null;
      const figure = key !== null ? previous.get(key) : undefined;
      if (figure) {
        previous.delete(key);
        kept.push(data.name);
        return figure;
      }
      const fresh = new CharacterFigure(data, i);
      fresh.key = key;
      built.push(data.name);
      this.characterGroup.add(fresh.group);
      return fresh;
    });
    for (const c of previous.values()) {
      this.characterGroup.remove(c.group);
      c.dispose();
    }
    this.lastCharacterUpdate = { built, kept };
    const frame = this.frame;
    this.frame = -1; // pose every figure again at the current frame (new ones start at frame 0)
    if (frame >= 0) this.setFrame(frame);
    this.invalidate();
    return this.lastCharacterUpdate;
  }

  /** Apply camera and light commands (only when they changed, so the user's orbiting is kept). */
  setCommands(commands) {
    this.lastCommands = commands;
    const camera = commands.filter((c) => c.kind === "camera").at(-1);
    const weather = commands.filter((c) => c.kind === "weather").at(-1);
    const key = JSON.stringify([camera?.value, camera?.target, weather?.value]);
    if (key === this.cameraKey) return;
    this.cameraKey = key;
    this.applyWeather(weather?.value || "");
    if (this.director) return; // the director's camera plays; the presets are for the free camera
    this.follow = null;
    const value = camera?.value || "";
    if (value === "follow" || value === "close") {
      this.follow = { target: camera?.target || "", distance: value === "close" ? 1.6 : 3.5 };
    } else {
      this.cameraPreset(value);
    }
  }

  /** Place the camera inside the room by a wall (front/back/left/right), above it (top), or the default view. */
  cameraPreset(value) {
    const r = this.roomSize;
    const w = r.width / 2 - 0.2;
    const d = r.depth / 2 - 0.2;
    const h = Math.min(r.height - 0.2, 2.2);
    const presets = {
      front: [0, h, d],
      back: [0, h, -d],
      left: [-w, h, 0],
      right: [w, h, 0],
      top: [0, Math.max(r.width, r.depth) * 1.4 + 2, 0.01],
    };
    // Default: a dollhouse view from above the front-right corner (the near walls are culled).
    const size = Math.max(r.width, r.depth);
    this.camera.position.fromArray(presets[value] || [r.width * 0.55 + 0.8, size * 0.9 + 1.2, r.depth * 0.55 + 1.5]);
    this.controls.target.set(0, 0.7, 0);
    this.invalidate();
  }

  /** Aim the camera at the characters (or the room centre) from where it stands. */
  /** Orbit the free camera by keyboard: azimuth and elevation steps in radians (the director's is left alone). */
  orbitBy(azimuth, elevation) {
    if (this.director) return;
    const offset = this.camera.position.clone().sub(this.controls.target);
    const s = new THREE.Spherical().setFromVector3(offset);
    s.theta += azimuth;
    s.phi = Math.min(Math.max(s.phi - elevation, 0.05), Math.PI / 2 - 0.02);
    this.camera.position.copy(this.controls.target).add(new THREE.Vector3().setFromSpherical(s));
    this.camera.lookAt(this.controls.target);
    this.invalidate();
  }

  frameCharacters() {
    if (!this.characters.length) return this.cameraPreset("");
    const centre = new THREE.Vector3();
    for (const c of this.characters) centre.add(c.position());
    centre.divideScalar(this.characters.length);
    const offset = this.camera.position.clone().sub(this.controls.target).setLength(3.2);
    offset.y = Math.max(offset.y, 1.2);
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).add(offset);
    this.invalidate();
  }

  applyWeather(value) {
    const looks = {
      night: [0x0b1020, 0.35, 0.3, null],
      foggy: [0x9aa3ad, 1.1, 0.6, [0x9aa3ad, 2, 14]],
      rainy: [0x4a5560, 0.9, 0.5, [0x4a5560, 4, 20]],
      snowy: [0xdfe6ee, 1.3, 0.9, [0xdfe6ee, 4, 22]],
      sunny: [0x87b8e8, 1.6, 2.2, null],
    };
    const [bg, hemi, sun, fog] = looks[value] || [0x2a2f38, 1.4, 1.6, null];
    if (this.exportScene) this.liveBackground = new THREE.Color(bg); // the video's colour stays while it plays
    else this.scene.background = new THREE.Color(bg);
    this.hemi.intensity = hemi;
    this.sun.intensity = sun;
    this.scene.fog = fog ? new THREE.Fog(...fog) : null;
    this.invalidate();
  }

  /** Play the director's camera (read from the render service's scene.glb), or null: the free orbit camera. */
  useDirector(cam) {
    this.director = cam;
    this.controls.enabled = !cam;
    this.resize(); // the video's aspect while the director plays
    if (cam) {
      this.applyDirector();
    } else {
      // The export's scene stays (orbit round the MP4's own characters) until a new version replaces it.
      this.camera.fov = 50;
      this.camera.updateProjectionMatrix();
      this.cameraKey = null;
      this.setCommands(this.lastCommands || []);
    }
    this.invalidate();
  }

  /**
   * Show the render service's own scene.glb (an ArrayBuffer) in place of the live figures: the skinned
   * characters, the room with its one-sided walls and the objects the MP4 is drawn from, played by its
   * animation at the current frame, lit by a light that travels with the camera as the video's renderer
   * lights its picture. null: back to the live room, objects and figures.
   * @returns {Promise<void>} resolved once the scene is shown
   */
  async useExport(buffer, version = null) {
    if (this.exportScene) {
      this.scene.remove(this.exportScene);
      this.exportScene.traverse((o) => o.geometry?.dispose());
    }
    this.exportScene = null;
    this.exportMixer = null;
    this.exportCharacters = [];
    this.exportVersion = null;
    this.headlight.visible = false;
    if (buffer) {
      const gltf = await this.loader.parseAsync(buffer, "");
      const root = gltf.scene;
      root.name = "export";
      root.traverse((o) => {
        if (o.isSkinnedMesh) this.exportCharacters.push(o);
        if (o.isMesh) o.frustumCulled = !o.isSkinnedMesh; // a skinned body's bounds are its rest pose
      });
      const clip = gltf.animations[0];
      if (clip) {
        this.exportMixer = new THREE.AnimationMixer(root);
        const action = this.exportMixer.clipAction(clip);
        action.setLoop(THREE.LoopOnce, 1);
        action.clampWhenFinished = true;
        action.play();
      }
      this.exportScene = root;
      this.exportVersion = version;
      this.scene.add(root);
      this.headlight.visible = true;
    }
    const live = !this.exportScene;
    this.roomGroup.visible = this.objectGroup.visible = this.characterGroup.visible = live;
    this.sun.visible = this.hemi.visible = live;
    this.ambient.visible = !live;
    // The video's renderer lights the GLB's colours as they are stored and writes the result unencoded
    // (fixed Phong lights, no sRGB transfer): so does the preview, on the video's clear colour.
    this.renderer.outputColorSpace = live ? THREE.SRGBColorSpace : THREE.LinearSRGBColorSpace;
    if (live && this.liveBackground) this.scene.background = this.liveBackground;
    if (!live) {
      this.liveBackground = this.liveBackground || this.scene.background;
      this.scene.background = new THREE.Color(...VIDEO_BACKGROUND);
    } else {
      this.liveBackground = null;
    }
    this.poseExport();
    this.invalidate();
  }

  poseExport() {
    if (!this.exportMixer) return;
    this.exportMixer.setTime(Math.max(0, this.frame) / 30);
  }

  applyDirector() {
    const pose = cameraAt(this.director, Math.max(0, this.frame));
    this.camera.position.fromArray(pose.position);
    this.camera.quaternion.fromArray(pose.quaternion);
    this.camera.fov = pose.fovDeg;
    this.camera.updateProjectionMatrix();
  }

  /** Pose every character at frame f. */
  setFrame(f) {
    if (f === this.frame) return;
    this.frame = f;
    this.invalidate();
    for (const c of this.characters) c.setFrame(f);
    this.poseExport();
    if (this.director) {
      this.applyDirector();
    } else if (this.follow && this.characters.length) {
      const who = this.characters.find((c) => c.name === this.follow.target) || this.characters[0];
      const p = who.position();
      const offset = this.camera.position.clone().sub(this.controls.target).setLength(this.follow.distance);
      this.controls.target.copy(p);
      this.camera.position.copy(p).add(offset);
    }
  }

  /** Draw when something changed (or force it). */
  render(force = false) {
    const moving = this.director ? false : this.controls.update(); // the orbit would re-aim the director's camera
    if (!force && !moving && !this.dirty) return;
    this.dirty = false;
    this.renderer.render(this.scene, this.camera);
  }
}
