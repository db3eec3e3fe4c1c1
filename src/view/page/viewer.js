// ECO's viewer: one recorded frame at a time, drawn in the ego frame (the sensor at the origin,
// world axes), from /api/run (the run's index) and /api/frame (a frame, thinned by the server).
// window.ecoView reports what is drawn, for the browser tests.
'use strict';

const COLORS = { inserted: 0x39ff88, dropped: 0xff9b21, cleared: 0xff3df5, voxel: 0x7f8fb0, box: 0xc8d0e0,
                 path: 0xffffff, reference: 0x5fb4ff, background: 0x10131a };
const PARAMS = new URLSearchParams(location.search);
const POLL_MS = 700;
const PLAY_MS = 100;  // at most ten frames a second: the sensor's rate

const $ = (id) => document.getElementById(id);
const state = { run: null, frames: [], index: -1, shown: null, loading: false, wanted: -1, playing: false, frame: null };
window.ecoView = { frame: -1, held: -1, ready: false, error: '', lastSwitchMs: NaN, switches: [], frameCount: 0 };

// --- the scene ----------------------------------------------------------------------------------
const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
renderer.setClearColor(COLORS.background);
$('view').appendChild(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(55, 1, 0.1, 2000);
camera.up.set(0, 0, 1);
camera.position.set(-22, -18, 24);
const controls = new THREE.OrbitControls(camera, renderer.domElement);
controls.addEventListener('change', render);

function pointsLayer(size, color) {
  const material = new THREE.PointsMaterial({ size, sizeAttenuation: false, vertexColors: color === undefined ? THREE.VertexColors : THREE.NoColors });
  if (color !== undefined) material.color.setHex(color);
  const layer = new THREE.Points(new THREE.BufferGeometry(), material);
  layer.frustumCulled = false;
  scene.add(layer);
  return layer;
}
const held = pointsLayer(2);
const dropped = pointsLayer(3, COLORS.dropped);
const cleared = pointsLayer(3, COLORS.cleared);
const voxels = new THREE.Points(new THREE.BufferGeometry(),
  new THREE.PointsMaterial({ size: 0.1, sizeAttenuation: true, color: COLORS.voxel, transparent: true, opacity: 0.55 }));
voxels.frustumCulled = false;
scene.add(voxels);
const boxMaterial = new THREE.LineBasicMaterial({ color: COLORS.box });
const box = new THREE.LineSegments(new THREE.EdgesGeometry(new THREE.BoxBufferGeometry(1, 1, 1)), boxMaterial);
scene.add(box);
// Config::region as the map held it this frame: a ball (three great circles) or a box turned with
// the sensor's heading (yaw) or its whole orientation (full); the group carries the turn
const region = new THREE.Group();
const ball = new THREE.Group();
for (const axis of [[0, 0, 0], [Math.PI / 2, 0, 0], [0, Math.PI / 2, 0]]) {
  const circle = new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(
    Array.from({ length: 96 }, (_, i) => new THREE.Vector3(Math.cos(i * Math.PI / 48), Math.sin(i * Math.PI / 48), 0))), boxMaterial);
  circle.rotation.set(...axis);
  ball.add(circle);
}
const turnedBox = new THREE.LineSegments(box.geometry, boxMaterial);
region.add(ball, turnedBox);
scene.add(region);
const sensor = new THREE.Mesh(new THREE.SphereBufferGeometry(0.25, 12, 8), new THREE.MeshBasicMaterial({ color: 0xff4040 }));
scene.add(sensor);
const path = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: COLORS.path }));
const reference = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: COLORS.reference }));
path.frustumCulled = reference.frustumCulled = false;
scene.add(path, reference);

function resize() {
  const el = $('view');
  renderer.setSize(el.clientWidth, el.clientHeight);
  camera.aspect = el.clientWidth / Math.max(1, el.clientHeight);
  camera.updateProjectionMatrix();
  render();
}
function render() { renderer.render(scene, camera); }

// --- colours ------------------------------------------------------------------------------------
const LOW = new THREE.Color(0x23407a), HIGH = new THREE.Color(0xe4ecff);
function ramp(t, out, i) {  // cool tones, deep blue to near white: the highlights stay apart from them
  const s = Math.min(1, Math.max(0, t));
  out[3 * i] = LOW.r + s * (HIGH.r - LOW.r); out[3 * i + 1] = LOW.g + s * (HIGH.g - LOW.g); out[3 * i + 2] = LOW.b + s * (HIGH.b - LOW.b);
}
function colorsFor(frame) {
  const n = frame.drawn, out = new Float32Array(3 * n);
  let by = $('color-by').value;
  const ages = frame.age, highlight = $('show-changes').checked;
  let lo = 0, hi = 1, value;
  if (by === 'height') { lo = -2.5 / frame.step; hi = 3.5 / frame.step; value = (i) => frame.xyz[3 * i + 2]; }
  if (by === 'age') { hi = Math.max(1, ...sample(ages)); value = (i) => hi - ages[i]; }
  if (by === 'intensity' && frame.intensity) { hi = Math.max(1e-6, ...sample(frame.intensity)); value = (i) => frame.intensity[i]; }
  if (by === 'id' ? !frame.id : value === undefined) { lo = 0; hi = 1; value = () => 0.5; by = 'flat'; }  // not recorded
  $('scale').textContent = {
    height: 'blue −2.5 m → white +3.5 m about the sensor', age: `white new → blue ${hi} frames old`, intensity: `blue 0 → white ${Number(hi).toPrecision(3)}`,
    id: 'a hue an id', flat: 'not recorded in this run' }[by];
  const rgb = new THREE.Color();
  for (let i = 0; i < n; ++i) {
    if (highlight && ages[i] === 0) {
      rgb.setHex(COLORS.inserted);
      out[3 * i] = rgb.r; out[3 * i + 1] = rgb.g; out[3 * i + 2] = rgb.b;
    } else if (by === 'id') {
      rgb.setHSL(((frame.id[i] * 0.618034) % 1 + 1) % 1, 0.7, frame.id[i] ? 0.55 : 0.3);
      out[3 * i] = rgb.r; out[3 * i + 1] = rgb.g; out[3 * i + 2] = rgb.b;
    } else {
      ramp((value(i) - lo) / (hi - lo), out, i);
    }
  }
  return out;
}
function sample(values) {  // up to 4096 values, for a scale's top without a spread of a million
  const step = Math.max(1, Math.floor(values.length / 4096)), out = [];
  for (let i = 0; i < values.length; i += step) out.push(values[i]);
  return out;
}

// --- a frame from the server --------------------------------------------------------------------
function decode(buffer) {
  const length = new DataView(buffer).getUint32(0, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, length)));
  let at = 4 + length;
  const take = (Type, count) => { const a = new Type(buffer, at, count); at += Type.BYTES_PER_ELEMENT * count; return a; };
  const n = header.drawn;
  const frame = Object.assign(header, { xyz: take(Int16Array, 3 * n), age: take(Uint16Array, n) });
  frame.intensity = header.has_intensity ? take(Float32Array, n) : null;
  frame.id = header.has_ids ? take(Uint32Array, n) : null;
  Object.assign(frame, { droppedXyz: take(Float32Array, 3 * header.dropped_drawn), clearedXyz: take(Float32Array, 3 * header.cleared_drawn),
    voxelXyz: take(Float32Array, 3 * header.voxels_drawn) });
  if (at !== buffer.byteLength) throw new Error(`frame ${header.frame}: ${buffer.byteLength - at} bytes left over`);
  return frame;
}
function setPoints(layer, xyz, colors) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
  if (colors) g.setAttribute('color', new THREE.BufferAttribute(colors, 3));
  layer.geometry.dispose();
  layer.geometry = g;
}

// Frames are fetched ahead: the one after the shown one (and the one before) wait in `cache`, so
// that stepping and playing pay for drawing only. A frame's bytes are fetched once.
const cache = new Map();  // frame number → Promise of its ArrayBuffer
function fetchFrame(n) {
  if (!cache.has(n)) {
    const voxels = $('show-voxels').checked ? 1 : 0;  // the voxel map is fetched only while shown
    cache.set(n, fetch(`/api/frame?n=${n}&budget=${budget()}&voxels=${voxels}`).then(async (response) => {
      if (!response.ok) throw new Error((await response.text()).trim() || `frame ${n}: HTTP ${response.status}`);
      return response.arrayBuffer();
    }));
    cache.get(n).catch(() => {});  // a failure is shown when the frame is, and fetched anew once it left the cache
  }
  return cache.get(n);
}
function budget() { return Math.max(1, Number($('budget').value) || 1); }
function prefetchAround(index) {
  const keep = new Set([index - 1, index, index + 1].filter((i) => i >= 0 && i < state.frames.length).map((i) => state.frames[i]));
  for (const n of cache.keys()) if (!keep.has(n)) cache.delete(n);
  for (const n of keep) fetchFrame(n);
}

async function show(index) {
  if (index < 0 || index >= state.frames.length) return;
  state.wanted = index;
  if (state.loading) return;  // the newest wish is taken when this load ends
  state.loading = true;
  const start = performance.now();
  const n = state.frames[index];
  const prefetched = cache.has(n);
  try {
    const frame = decode(await fetchFrame(n));
    const fetched = performance.now();
    state.frame = frame;
    state.index = index;
    draw();
    const gl = renderer.getContext();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));  // waits for the drawing
    const ms = performance.now() - start;
    window.ecoView.lastSwitchMs = ms;
    window.ecoView.switches.push({ frame: n, ms, fetchMs: fetched - start, drawn: frame.drawn, prefetched });
    $('switch-ms').textContent = `${ms.toFixed(0)} ms`;
    setError('');
  } catch (e) {
    state.index = index;  // the slider stays where the user put it; the last good frame stays drawn
    setError(String(e.message || e));
    updatePanel(null);
  } finally {
    state.loading = false;
  }
  prefetchAround(state.index);
  if (state.wanted !== state.index) show(state.wanted);
}

function draw() {
  const f = state.frame;
  setPoints(held, f.xyz, colorsFor(f));
  held.scale.setScalar(f.step);
  const changes = $('show-changes').checked;
  setPoints(dropped, f.droppedXyz); dropped.visible = changes;
  setPoints(cleared, f.clearedXyz); cleared.visible = changes;
  setPoints(voxels, f.voxelXyz); voxels.visible = $('show-voxels').checked;
  voxels.material.size = f.voxel_size;
  drawRegion(f);
  drawPaths(f.sensor);
  updatePanel(f);
  render();
}

/// The cube, or the region the map holds in it (run.json's shape, frames.csv's extents).
function drawRegion(f) {
  const run = state.run.run, shown = $('show-box').checked, shape = run.region || 'cube';
  const [radius, ahead, behind, left, right, up, down] = state.run.frames.region[state.index] || [0, 0, 0, 0, 0, 0, 0];
  const side = run.box_side || 0;
  box.scale.set(side, side, side);
  box.visible = shown && side > 0 && shape === 'cube';
  region.visible = shown && shape !== 'cube';
  ball.visible = shape === 'ball';
  turnedBox.visible = shape === 'oriented_box';
  ball.scale.setScalar(Math.max(radius, 1e-3));
  turnedBox.scale.set(Math.max(ahead + behind, 1e-3), Math.max(left + right, 1e-3), Math.max(up + down, 1e-3));
  turnedBox.position.set((ahead - behind) / 2, (left - right) / 2, (up - down) / 2);
  const r = f.turn || [1, 0, 0, 0, 1, 0, 0, 0, 1];
  const turn = new THREE.Matrix4();
  if (run.turn_with === 'full' || shape === 'ball') {
    turn.set(r[0], r[1], r[2], 0, r[3], r[4], r[5], 0, r[6], r[7], r[8], 0, 0, 0, 0, 1);
  } else {  // the heading alone: the sensor's x axis on the ground
    turn.makeRotationZ(Math.atan2(r[3], r[0]));
  }
  region.setRotationFromMatrix(turn);
}

function drawPaths(origin) {
  const cols = state.run.frames, last = state.index, line = [], ref = [];
  for (let i = 0; i <= last && i < cols.x.length; ++i) {
    line.push(cols.x[i] - origin[0], cols.y[i] - origin[1], cols.z[i] - origin[2]);
    const r = cols.ref[i];
    if (r) ref.push(r[0] - origin[0], r[1] - origin[1], r[2] - origin[2]);
  }
  setPoints(path, new Float32Array(line));
  setPoints(reference, new Float32Array(ref));
  path.visible = reference.visible = $('show-path').checked;
}

// --- the panel ----------------------------------------------------------------------------------
const fmt = (v) => (v === undefined || v === null ? '–' : Number(v).toLocaleString('en-US'));
function updatePanel(frame) {
  const i = state.index, cols = state.run.frames;
  $('frame-number').textContent = state.frames[i];
  $('frame-slider').value = i;
  $('held-count').textContent = fmt(cols.held[i]);
  $('scan-count').textContent = fmt(cols.scan[i]);
  $('inserted-count').textContent = fmt(cols.inserted[i]);
  $('pruned-count').textContent = fmt(cols.pruned[i]);
  $('cleared-count').textContent = fmt(cols.cleared[i]);
  $('update-ms').textContent = `${cols.update_ms[i].toFixed(2)} ms`;
  $('voxel-count').textContent = frame ? fmt(frame.voxels) : '–';
  $('drawn-count').textContent = frame ? `${fmt(frame.drawn)}${frame.stride === 1 ? ' (all)' : ` (1 in ${frame.stride})`}` : '–';
  Object.assign(window.ecoView, { frame: state.frames[i], held: cols.held[i], ready: window.ecoView.ready || !!frame,
    voxelsDrawn: frame ? frame.voxels_drawn : 0 });
  drawChart();
}
function setError(text) {
  $('error').hidden = !text;
  $('error').textContent = text;
  window.ecoView.error = text;
}

function drawChart() {
  const canvas = $('chart'), g = canvas.getContext('2d'), ms = state.run.frames.update_ms;
  const w = canvas.width, h = canvas.height, pad = 22;
  g.clearRect(0, 0, w, h);
  if (!ms.length) return;
  const top = Math.max(...ms) * 1.1 || 1, x = (i) => pad + (w - pad - 4) * (ms.length > 1 ? i / (ms.length - 1) : 0.5);
  const y = (v) => h - 14 - (h - 20) * (v / top);
  g.strokeStyle = '#2b3140'; g.fillStyle = '#6b7486'; g.font = '10px sans-serif';
  g.beginPath(); g.moveTo(pad, y(0)); g.lineTo(w - 4, y(0)); g.stroke();
  g.fillText(top.toFixed(1), 0, y(top) + 8); g.fillText('0', 8, y(0) + 3);
  const frames = state.frames;
  g.fillText(`frame ${frames[0]}`, pad, h - 2);
  g.fillText(`${frames[frames.length - 1]}`, w - 4 - g.measureText(`${frames[frames.length - 1]}`).width, h - 2);
  g.strokeStyle = '#5fb4ff'; g.beginPath();
  ms.forEach((v, i) => (i ? g.lineTo(x(i), y(v)) : g.moveTo(x(i), y(v))));
  g.stroke();
  if (state.index >= 0) {
    g.strokeStyle = '#ff4040'; g.beginPath(); g.moveTo(x(state.index), 4); g.lineTo(x(state.index), h - 14); g.stroke();
  }
}

// --- the run's index, polled while a live run grows -----------------------------------------------
async function poll() {
  try {
    const run = await (await fetch('/api/run', { cache: 'no-store' })).json();
    const grew = !state.run || run.frames.frame.length !== state.frames.length;
    state.run = run;
    state.frames = run.frames.frame;
    if (!$('budget').value) $('budget').value = PARAMS.get('budget') || run.budget;
    window.ecoView.frameCount = state.frames.length;
    if (run.error) setError(run.error);
    $('title').textContent = run.run.title || 'ECO';
    $('frame-last').textContent = state.frames.length ? state.frames[state.frames.length - 1] : '–';
    $('frame-slider').max = Math.max(0, state.frames.length - 1);
    if (grew && state.frames.length && ($('follow').checked || state.index < 0)) {
      show($('follow').checked ? state.frames.length - 1 : 0);
    } else if (grew) drawChart();
  } catch (e) {
    setError(`the run's index: ${e.message || e}`);
  }
  setTimeout(poll, POLL_MS);
}

// --- controls -----------------------------------------------------------------------------------
function step(delta) { $('follow').checked = false; show(Math.min(state.frames.length - 1, Math.max(0, state.index + delta))); }
function play(on) {
  state.playing = on;
  $('play').textContent = on ? 'pause' : 'play';
  if (on) { $('follow').checked = false; tick(); }
}
function tick() {
  if (!state.playing) return;
  if (!state.loading && state.index < state.frames.length - 1) show(state.index + 1);
  setTimeout(tick, PLAY_MS);
}
$('frame-slider').addEventListener('input', (e) => { $('follow').checked = false; show(Number(e.target.value)); });
$('prev').addEventListener('click', () => step(-1));
$('next').addEventListener('click', () => step(1));
$('play').addEventListener('click', () => play(!state.playing));
$('follow').addEventListener('change', (e) => { if (e.target.checked) { play(false); show(state.frames.length - 1); } });
$('budget').addEventListener('change', () => { cache.clear(); show(state.index); });
$('show-voxels').addEventListener('change', (e) => {
  if (e.target.checked && state.frame && state.frame.voxels_drawn < Math.min(state.frame.voxels, 1)) {
    cache.clear();  // fetched without the voxel map
    show(state.index);
  }
});
for (const id of ['color-by', 'show-changes', 'show-voxels', 'show-box', 'show-path']) {
  $(id).addEventListener('change', () => { if (state.frame) draw(); });
}
document.addEventListener('keydown', (e) => {
  if (e.target.tagName === 'INPUT' && e.target.type !== 'checkbox') return;
  if (e.key === 'ArrowLeft') step(-1);
  if (e.key === 'ArrowRight') step(1);
  if (e.key === ' ') { e.preventDefault(); play(!state.playing); }
});
window.addEventListener('resize', resize);

/// Pixels unlike the background in the drawn canvas, and a checksum of them (the tests' eyes).
window.ecoView.region = () => ({
  cube: box.visible, ball: region.visible && ball.visible, box: region.visible && turnedBox.visible,
  radius: ball.scale.x, size: turnedBox.scale.toArray(), centre: turnedBox.position.toArray(),
  turn: region.matrixWorld.elements.slice(0, 11),
});
window.ecoView.pixels = () => {
  render();
  const gl = renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
  const rgba = new Uint8Array(4 * w * h);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
  const bg = new THREE.Color(COLORS.background);
  const [br, bgg, bb] = [bg.r, bg.g, bg.b].map((c) => Math.round(c * 255));
  let lit = 0, sum = 0;
  for (let i = 0; i < rgba.length; i += 4) {
    if (Math.abs(rgba[i] - br) + Math.abs(rgba[i + 1] - bgg) + Math.abs(rgba[i + 2] - bb) > 6) ++lit;
    sum = (sum * 31 + rgba[i] + 7 * rgba[i + 1] + 13 * rgba[i + 2]) >>> 0;
  }
  return { lit, sum, width: w, height: h };
};

resize();
poll();
