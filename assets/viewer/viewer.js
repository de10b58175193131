// SIMS-C++ story viewer. Reads motion.json (io::MotionRecord: fps, keyframes, per-frame root
// positions) and scene.glb (io::ExportGltf: scene meshes + the 15-node character with its
// "motion" animation) and plays the animation with a timeline, a keyframe list and a caption.
// window.simsViewer exposes the state for automated tests.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);

const state = {
  ready: false,
  time: 0,
  duration: 0,
  fps: 30,
  playing: false,
  speed: 1,
  current: -1,
  keyframes: [],
};

function fail(message) {
  const n = $('notice');
  n.textContent = message;
  n.className = 'error';
  n.style.display = 'flex';
  console.error(message);
}

async function fetchJson(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return r.json();
}

function formatTime(t) {
  return t.toFixed(2);
}

function escapeHtml(s) {
  return String(s ?? '').replace(/[&<>"']/g, (c) => (
    { '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' }[c]));
}

async function main() {
  const [motion, gltf] = await Promise.all([
    fetchJson('motion.json'),
    new GLTFLoader().loadAsync('scene.glb'),
  ]);
  if (motion.format !== 'sims-motion-record') throw new Error('motion.json: not a sims-motion-record');
  state.fps = motion.fps;
  state.duration = Math.max(0, (motion.num_frames - 1) / motion.fps);
  state.keyframes = motion.keyframes;

  // --- three.js scene -------------------------------------------------------------------
  const view = $('view');
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.shadowMap.enabled = true;
  view.prepend(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xcfd6dd);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8a80, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(-3, 8, 4);
  scene.add(sun);
  scene.add(gltf.scene);

  const world = gltf.scene.getObjectByName('sims_world');
  const pelvis = gltf.scene.getObjectByName('pelvis');
  if (!world || !pelvis) throw new Error('scene.glb: no sims_world / pelvis node');
  const walls = [];
  gltf.scene.traverse((o) => {
    if (o.isMesh && o.name.startsWith('walls')) {
      o.material = o.material.clone();
      o.material.transparent = true;
      o.material.opacity = 0.35;
      o.material.depthWrite = false;
      walls.push(o);
    }
  });

  // Root trail (project Z-up coordinates live under the sims_world node).
  const trail = new Float32Array(motion.frames.length * 3);
  motion.frames.forEach((f, i) => trail.set([f.root_pos[0], f.root_pos[1], 0.01], 3 * i));
  const trailGeom = new THREE.BufferGeometry();
  trailGeom.setAttribute('position', new THREE.BufferAttribute(trail, 3));
  world.add(new THREE.Line(trailGeom, new THREE.LineBasicMaterial({ color: 0x3366cc })));

  // Pose sampling straight from the glTF animation tracks.
  const clip = gltf.animations[0];
  const tracks = [];
  if (clip) {
    for (const track of clip.tracks) {
      const parsed = THREE.PropertyBinding.parseTrackName(track.name);
      const node = gltf.scene.getObjectByName(parsed.nodeName);
      if (node) tracks.push({ node, property: parsed.propertyName, interp: track.createInterpolant() });
    }
  }
  function applyPose(t) {
    for (const { node, property, interp } of tracks) {
      const v = interp.evaluate(t);
      if (property === 'quaternion') node.quaternion.fromArray(v);
      else if (property === 'position') node.position.fromArray(v);
    }
  }

  const camera = new THREE.PerspectiveCamera(50, 1, 0.05, 500);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;
  const target = new THREE.Vector3();
  applyPose(0);
  gltf.scene.updateMatrixWorld(true);
  pelvis.getWorldPosition(target);
  camera.position.copy(target).add(new THREE.Vector3(2.8, 1.6, 2.8));
  controls.target.copy(target);
  controls.update();

  function resize() {
    const w = view.clientWidth, h = view.clientHeight;
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
  window.addEventListener('resize', resize);
  resize();

  // --- UI ---------------------------------------------------------------------------------
  $('title').textContent = motion.title || 'Story';
  const reached = motion.keyframes.filter((k) => k.start_frame >= 0);
  const ok = motion.keyframes.filter((k) => k.success).length;
  $('meta').textContent = `scene ${motion.scene?.name || '?'} · ${formatTime(state.duration)} s · ` +
      `${ok}/${motion.keyframes.length} keyframes succeeded` +
      (reached.length < motion.keyframes.length ? ` · ${motion.keyframes.length - reached.length} not reached` : '');
  const list = $('keyframes');
  motion.keyframes.forEach((k, i) => {
    const li = document.createElement('li');
    const reachedK = k.start_frame >= 0;
    li.className = 'kf ' + (!reachedK ? 'unreached' : k.success ? 'ok' : 'fail');
    li.dataset.index = i;
    const range = reachedK
      ? `${formatTime(k.start_frame / state.fps)}–${formatTime(k.end_frame / state.fps)} s` : 'not reached';
    li.innerHTML = `<div class="head"><span><span class="skill">${i + 1}. ${escapeHtml(k.skill)}</span>` +
        `${k.emotion ? ' · ' + escapeHtml(k.emotion) : ''}</span>` +
        `<span class="result">${!reachedK ? '–' : k.success ? '✓ success' : '✗ failed'}</span></div>` +
        `<div class="caption">${escapeHtml(k.caption)}</div>` +
        `<div class="info">${range}${k.furniture ? ' · ' + escapeHtml(k.furniture) : ''}` +
        `${k.detail ? ' · ' + escapeHtml(k.detail) : ''}</div>`;
    if (reachedK) li.addEventListener('click', () => setTime(k.start_frame / state.fps));
    list.appendChild(li);
  });
  const segs = $('segments');
  if (state.duration > 0) {
    for (const k of reached) {
      const d = document.createElement('div');
      d.style.left = `${100 * (k.start_frame / state.fps) / state.duration}%`;
      d.style.width = `${Math.max(0.3, 100 * ((k.end_frame - k.start_frame) / state.fps) / state.duration)}%`;
      d.style.background = k.success ? '#2e9d4a' : '#d03b3b';
      segs.appendChild(d);
    }
  }
  const scrub = $('scrub');
  scrub.max = state.duration;
  scrub.step = 1 / state.fps;
  scrub.disabled = false;
  scrub.addEventListener('input', () => setTime(parseFloat(scrub.value)));
  const play = $('play');
  play.disabled = false;
  play.addEventListener('click', () => (state.playing ? pause() : start()));
  $('speed').addEventListener('change', (e) => { state.speed = parseFloat(e.target.value); });
  $('walls').addEventListener('change', (e) => walls.forEach((w) => { w.visible = e.target.checked; }));

  function keyframeAt(frame) {
    let best = -1;
    motion.keyframes.forEach((k, i) => {
      if (k.start_frame >= 0 && k.start_frame <= frame &&
          (best < 0 || k.start_frame >= motion.keyframes[best].start_frame)) best = i;
    });
    return best;
  }

  function updateUi() {
    scrub.value = state.time;
    $('time').textContent = `${formatTime(state.time)} / ${formatTime(state.duration)} s`;
    play.textContent = state.playing ? 'Pause' : 'Play';
    const k = keyframeAt(Math.round(state.time * state.fps));
    if (k !== state.current) {
      state.current = k;
      list.querySelectorAll('.kf').forEach((li) => li.classList.toggle('current', +li.dataset.index === k));
      const cap = $('caption');
      if (k < 0) {
        cap.innerHTML = '';
      } else {
        const a = motion.keyframes[k];
        cap.innerHTML = `<span class="skill">${escapeHtml(a.skill)}</span>` +
            `${a.emotion ? ' · ' + escapeHtml(a.emotion) : ''} · ${a.success ? 'success' : 'failed'}` +
            `<br>${escapeHtml(a.caption)}`;
        list.children[k]?.scrollIntoView({ block: 'nearest' });
      }
    }
  }

  const followed = new THREE.Vector3();
  function render() {
    applyPose(state.time);
    gltf.scene.updateMatrixWorld(true);
    if ($('follow').checked) {
      pelvis.getWorldPosition(followed);
      const delta = followed.clone().sub(controls.target);
      camera.position.add(delta);
      controls.target.copy(followed);
    }
    controls.update();
    renderer.render(scene, camera);
  }

  function setTime(t) {
    state.time = Math.min(Math.max(t, 0), state.duration);
    updateUi();
    render();
  }
  function start() {
    if (state.time >= state.duration) state.time = 0;
    state.playing = true;
    updateUi();
  }
  function pause() {
    state.playing = false;
    updateUi();
  }

  let last = performance.now();
  function tick(now) {
    const dt = Math.min(0.1, (now - last) / 1000);
    last = now;
    if (state.playing) {
      state.time += dt * state.speed;
      if (state.time >= state.duration) {
        state.time = state.duration;
        state.playing = false;
      }
      updateUi();
    }
    render();
    requestAnimationFrame(tick);
  }

  // Pixels that change when the character is hidden (tests check it is drawn).
  function characterPixels() {
    const gl = renderer.getContext();
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const read = () => {
      render();
      const px = new Uint8Array(w * h * 4);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
      return px;
    };
    const withCharacter = read();
    pelvis.visible = false;
    const without = read();
    pelvis.visible = true;
    render();
    let changed = 0;
    for (let i = 0; i < withCharacter.length; i += 4) {
      if (withCharacter[i] !== without[i] || withCharacter[i + 1] !== without[i + 1] ||
          withCharacter[i + 2] !== without[i + 2]) changed++;
    }
    return changed;
  }

  window.simsViewer = {
    get ready() { return state.ready; },
    get time() { return state.time; },
    get duration() { return state.duration; },
    get playing() { return state.playing; },
    get currentKeyframe() { return state.current; },
    get keyframes() { return state.keyframes; },
    setTime, play: start, pause,
    setCharacterVisible(v) { pelvis.visible = v; render(); },
    characterPixels,
  };

  $('notice').style.display = 'none';
  updateUi();
  render();
  state.ready = true;
  requestAnimationFrame(tick);
}

main().catch((e) => fail(`Could not load the story: ${e.message}`));
