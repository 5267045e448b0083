// The page: reads its address (the keys of `srt render`'s options), picks WebGPU or the CPU
// tracer in a worker, keeps the controls and the picture in step, and loads dropped models.
// The picture is always srt's: srt-gpu's passes on WebGPU, or srt-trace's exact CPU tracer.
import init, { GpuPage, page_settings, scene_names } from './srt_web.js';

const $ = (id) => document.getElementById(id);
const canvas = $('canvas');
const status = $('status');

// What the page shows; null means "the scene's own value".
const state = {
  scene: 'teaser',
  model: null,            // { name, bytes } of a dropped model
  time: null,
  beta: null,             // [x, y, z] for every object, or null
  observerBeta: null,
  effects: null,
  colour: null,
  exposure: null,
  projection: null,       // 'equirectangular', 'fisheye:FOV', …
  set: [],                // the address's `set=KEY=VALUE` entries, in order
  method: 'auto',
  split: false,
  playing: false,
  rate: 1,
};
let settings;             // page_settings of the address
let info = null;          // the scene's own values (JSON from Rust)
let gpu = null;           // GpuPage, when WebGPU draws
let worker = null;        // the CPU tracer's worker
let backend = 'cpu';      // 'webgpu' or 'cpu'
let firstFrameDone = false;
let dirty = true;
let busy = false;

function showError(message) {
  status.textContent = message;
  status.className = 'error';
  document.title = `srt error: ${message}`;
}

function showNote(message) {
  status.textContent = message;
  status.className = '';
}

function errorText(error) {
  return String(error && error.message !== undefined ? error.message : error);
}

// The address of the current state, in the keys of `srt render`'s options.
function query() {
  const q = new URLSearchParams();
  if (!state.model) q.set('scene', state.scene);
  if (state.time !== null) q.set('time', String(state.time));
  if (state.beta) q.set('beta', state.beta.join(','));
  if (state.observerBeta) q.set('observer_beta', state.observerBeta.join(','));
  if (state.effects) q.set('effects', state.effects);
  if (state.colour) q.set('colour', state.colour);
  if (state.exposure !== null) q.set('exposure', String(state.exposure));
  if (state.projection) q.set('projection', state.projection);
  for (const entry of state.set) q.append('set', entry);
  q.set('method', state.method);
  if (state.split) q.set('split', '1');
  return q.toString();
}

// ---- the CPU tracer's worker, as promises
let nextId = 0;
const pending = new Map();
function workerCall(message, transfer = []) {
  if (!worker) {
    worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    worker.onmessage = (event) => {
      const reply = event.data;
      const waiting = pending.get(reply.id);
      pending.delete(reply.id);
      if (!waiting) return;
      if (reply.error !== undefined) waiting.reject(new Error(reply.error));
      else waiting.resolve(reply);
    };
    worker.onerror = (event) => showError(`the CPU tracer's worker failed: ${event.message}`);
    if (state.model) {
      // A worker started after a model was dropped loads it first.
      const bytes = state.model.bytes.slice();
      workerCall({ kind: 'model', name: state.model.name, bytes }, [bytes.buffer]);
    }
  }
  const id = nextId++;
  return new Promise((resolve, reject) => {
    pending.set(id, { resolve, reject });
    worker.postMessage({ ...message, id }, transfer);
  });
}

// ---- sizes
function canvasSize() {
  if (settings.width !== null) return [settings.width, settings.height];
  const cssWidth = Math.max(320, Math.floor($('stage').clientWidth));
  const cssHeight = Math.round(cssWidth * 9 / 16);
  // WebGPU draws every device pixel; the CPU tracer draws at most 480 pixels across.
  const scale = backend === 'webgpu' ? (window.devicePixelRatio || 1) : Math.min(1, 480 / cssWidth);
  return [Math.max(1, Math.round(cssWidth * scale)), Math.max(1, Math.round(cssHeight * scale))];
}

function sizeCanvas() {
  const [width, height] = canvasSize();
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  if (settings.width !== null) {
    canvas.style.width = `${settings.width}px`;
    canvas.style.height = `${settings.height}px`;
  }
  return [width, height];
}

// ---- drawing
async function drawOnce() {
  const [width, height] = sizeCanvas();
  $('split-labels').style.height = `${canvas.clientHeight}px`;
  const shown = query();
  let started = performance.now();
  let drawnBy = backend;
  let note = '';
  let weighed = false;
  if (backend === 'webgpu') {
    gpu.set_query(shown);
    gpu.resize(width, height);
    // `auto` on a software adapter: the faster of WebGPU and the CPU tracer draws, both at the
    // canvas's size (the rule of the viewer's panes, srt-gpu's exact_path).
    weighed = settings.backend === 'auto' && gpu.weighs();
    let path = 'webgpu';
    if (weighed) {
      if (gpu.wants_cpu_measure()) {
        const asked = performance.now();
        const reply = await workerCall({ kind: 'measure', query: shown, width, height });
        gpu.measured_cpu(reply.seconds, (performance.now() - asked) / 1000);
      }
      path = gpu.next_path();
      // For tests: the path chosen and the times it was chosen on.
      document.body.dataset.choice = JSON.stringify({ path, ...JSON.parse(gpu.path_times()) });
      started = performance.now();
    }
    const reason = path === 'webgpu' ? gpu.draw() : undefined;
    if (path === 'cpu' || reason !== undefined) {
      if (reason !== undefined) {
        note = `${reason}: drawn by the CPU tracer`;
        weighed = false;
      }
      await drawWithCpu(width, height, true);
      drawnBy = 'cpu';
    } else {
      try {
        await gpu.finished();
      } catch (error) {
        throw new Error(gpu.errors() || errorText(error));
      }
      const late = gpu.errors();
      if (late !== undefined) throw new Error(late);
      if (overlay) overlay.hidden = true;
    }
  } else {
    await drawWithCpu(width, height, false);
  }
  const ms = performance.now() - started;
  let text = rendererText(drawnBy, width, height, ms);
  if (weighed) {
    gpu.drawn(drawnBy, ms / 1000);
    const times = JSON.parse(gpu.path_times());
    const time = (value) => (value === null ? 'not yet timed' : `${value.toFixed(0)} ms`);
    text += `; the faster draws: WebGPU ${time(times.webgpu_ms)}, CPU ${time(times.cpu_ms)}`;
    // For tests: both paths' running times and the last frame's path.
    document.body.dataset.paths = JSON.stringify(times);
  }
  $('renderer').textContent = text;
  if (note) showNote(note);
  // For tests and embedding pages: what the last frame shows, and how many were drawn.
  document.body.dataset.query = shown;
  document.body.dataset.drawnBy = drawnBy;
  document.body.dataset.frameMs = String(ms);
  document.body.dataset.frames = String(Number(document.body.dataset.frames || 0) + 1);
  return drawnBy;
}

// A CPU frame on the canvas: on a 2D context, or, where WebGPU holds the canvas, on a
// canvas laid over it.
async function drawWithCpu(width, height, overGpu) {
  const reply = await workerCall({ kind: 'render', query: query(), width, height });
  const target = overGpu ? overlayCanvas(width, height) : canvas;
  const image = new ImageData(new Uint8ClampedArray(reply.pixels.buffer), width, height);
  target.getContext('2d').putImageData(image, 0, 0);
}

let overlay = null;
function overlayCanvas(width, height) {
  if (!overlay) {
    overlay = document.createElement('canvas');
    overlay.style.position = 'absolute';
    overlay.style.left = '0';
    overlay.style.top = '0';
    $('stage').appendChild(overlay);
  }
  overlay.width = width;
  overlay.height = height;
  overlay.style.width = `${canvas.clientWidth}px`;
  overlay.style.height = `${canvas.clientHeight}px`;
  overlay.hidden = false;
  return overlay;
}

function rendererText(drawnBy, width, height, ms) {
  const what = drawnBy === 'webgpu'
    ? `WebGPU (${gpu.adapter()})`
    : 'the exact CPU tracer (in a Web Worker)';
  return `${width}×${height}, drawn by ${what} in ${ms.toFixed(0)} ms`;
}

async function frameLoop(now) {
  if (state.playing) {
    const dt = lastTick === null ? 0 : (now - lastTick) / 1000;
    setTime(clockValue() + dt * state.rate);
  }
  lastTick = now;
  if (dirty && !busy) {
    dirty = false;
    busy = true;
    try {
      const drawnBy = await drawOnce();
      if (!firstFrameDone) {
        firstFrameDone = true;
        // Shown once the browser has composited the frame.
        await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
        document.title = `srt ready (${drawnBy})`;
      }
    } catch (error) {
      showError(errorText(error));
    } finally {
      busy = false;
    }
  }
  requestAnimationFrame(frameLoop);
}
let lastTick = null;

function redraw() {
  dirty = true;
}

// ---- controls
function clockValue() {
  return state.time !== null ? state.time : info.time;
}

function setTime(time) {
  const slider = $('time');
  const low = Number(slider.min);
  const high = Number(slider.max);
  state.time = time > high ? low + (time - high) : time;
  showControls();
  redraw();
}

function betaFromControls() {
  const speed = Number($('speed').value);
  const around = Number($('azimuth').value) * Math.PI / 180;
  const up = Number($('elevation').value) * Math.PI / 180;
  const round = (x) => Math.round(x * 1e6) / 1e6;
  return [speed * Math.cos(up) * Math.cos(around), speed * Math.sin(up), speed * Math.cos(up) * Math.sin(around)].map(round);
}

function setVelocityControls(beta) {
  const speed = Math.hypot(...beta);
  $('speed').value = String(Math.min(speed, 0.999));
  if (speed > 0) {
    $('azimuth').value = String(Math.round(Math.atan2(beta[2], beta[0]) * 180 / Math.PI));
    $('elevation').value = String(Math.round(Math.asin(beta[1] / speed) * 180 / Math.PI));
  }
}

function showControls() {
  const beta = state.beta || info.beta;
  $('speed-value').textContent = `${Math.hypot(...beta).toFixed(3)} c`;
  $('azimuth-value').textContent = `${$('azimuth').value}°`;
  $('elevation-value').textContent = `${$('elevation').value}°`;
  $('beta-value').textContent = state.beta
    ? `β = (${state.beta.map((x) => x.toFixed(3)).join(', ')}) for every object`
    : 'each object moves as the scene says';
  $('time-value').textContent = clockValue().toFixed(2);
  $('time').value = String(clockValue());
  $('set-velocity').checked = state.beta !== null;
  $('velocity').disabled = info.observer_moves;
  $('effects').value = state.effects || info.effects;
  $('colour').value = state.colour || info.colour;
  $('method').value = state.method;
  $('split').checked = state.split;
  $('split-labels').hidden = !state.split;
  $('play').textContent = state.playing ? 'Pause' : 'Play';
}

// The scene's own values, from whichever renderer holds the scene.
async function loadInfo() {
  if (gpu) {
    gpu.set_query(query());
    info = JSON.parse(gpu.info());
  } else {
    info = JSON.parse((await workerCall({ kind: 'info', query: query() })).info);
  }
  const slider = $('time');
  slider.min = String(Math.floor(info.time - 10));
  slider.max = String(Math.ceil(info.time + 10));
  setVelocityControls(state.beta || info.beta);
  if (info.warnings.length) showNote(info.warnings.join('\n'));
  showControls();
}

async function changeScene(name) {
  state.scene = name;
  state.model = null;
  state.time = null;
  state.beta = null;
  await loadInfo();
  redraw();
}

async function loadModel(file) {
  const bytes = new Uint8Array(await file.arrayBuffer());
  try {
    let warnings;
    if (gpu) {
      warnings = gpu.load_model(file.name, bytes);
      if (worker) {
        const copy = bytes.slice();
        await workerCall({ kind: 'model', name: file.name, bytes: copy }, [copy.buffer]);
      }
    } else {
      const copy = bytes.slice();
      warnings = (await workerCall({ kind: 'model', name: file.name, bytes: copy }, [copy.buffer])).warnings;
    }
    state.model = { name: file.name, bytes };
    state.time = null;
    state.beta = null;
    const option = document.createElement('option');
    option.value = `model:${file.name}`;
    option.textContent = `${file.name} (dropped)`;
    $('scene').appendChild(option);
    $('scene').value = option.value;
    await loadInfo();
    showNote(warnings ? `${file.name} loaded, with warnings:\n${warnings}` : `${file.name} loaded`);
    redraw();
  } catch (error) {
    // The scene shown before stays.
    showError(errorText(error));
  }
}

function wireControls() {
  const select = $('scene');
  for (const name of scene_names()) {
    const option = document.createElement('option');
    option.value = name;
    option.textContent = name;
    select.appendChild(option);
  }
  select.value = state.scene;
  select.addEventListener('change', () => {
    if (!select.value.startsWith('model:')) changeScene(select.value).catch((e) => showError(errorText(e)));
  });
  $('model').addEventListener('change', (event) => {
    if (event.target.files.length) loadModel(event.target.files[0]);
  });
  $('set-velocity').addEventListener('change', (event) => {
    state.beta = event.target.checked ? betaFromControls() : null;
    showControls();
    redraw();
  });
  for (const id of ['speed', 'azimuth', 'elevation']) {
    $(id).addEventListener('input', () => {
      state.beta = betaFromControls();
      showControls();
      redraw();
    });
  }
  $('effects').addEventListener('change', (e) => { state.effects = e.target.value; redraw(); });
  $('colour').addEventListener('change', (e) => { state.colour = e.target.value; redraw(); });
  $('time').addEventListener('input', (e) => { state.playing = false; setTime(Number(e.target.value)); });
  $('play').addEventListener('click', () => { state.playing = !state.playing; showControls(); });
  $('rate').addEventListener('change', (e) => { state.rate = Number(e.target.value); });
  $('method').addEventListener('change', (e) => { state.method = e.target.value; redraw(); });
  $('split').addEventListener('change', (e) => { state.split = e.target.checked; showControls(); redraw(); });
  const stage = $('stage');
  window.addEventListener('dragover', (event) => { event.preventDefault(); stage.classList.add('dragging'); });
  window.addEventListener('dragleave', () => stage.classList.remove('dragging'));
  window.addEventListener('drop', (event) => {
    event.preventDefault();
    stage.classList.remove('dragging');
    if (event.dataTransfer.files.length) loadModel(event.dataTransfer.files[0]);
  });
  window.addEventListener('resize', redraw);
}

async function main() {
  await init();
  settings = JSON.parse(page_settings(location.search));
  if (settings.embed) document.body.classList.add('embed');
  // The address's values seed the state (they are checked again by the renderer).
  const params = new URLSearchParams(location.search);
  if (settings.scene) state.scene = settings.scene;
  if (params.has('time')) state.time = Number(params.get('time'));
  if (params.has('beta')) state.beta = params.get('beta').split(',').map(Number);
  if (params.has('observer_beta')) state.observerBeta = params.get('observer_beta').split(',').map(Number);
  if (params.has('effects')) state.effects = params.get('effects');
  if (params.has('colour')) state.colour = params.get('colour');
  if (params.has('exposure')) state.exposure = Number(params.get('exposure'));
  if (params.has('projection')) state.projection = params.get('projection');
  state.set = params.getAll('set');
  state.method = settings.method;
  state.split = settings.split;

  if (settings.backend !== 'cpu') {
    if (!navigator.gpu) {
      if (settings.backend === 'webgpu') throw new Error('this browser has no WebGPU (navigator.gpu is missing)');
    } else {
      sizeCanvas();
      try {
        gpu = await GpuPage.create(canvas);
        backend = 'webgpu';
      } catch (error) {
        if (settings.backend === 'webgpu') throw error;
        showNote(`WebGPU is not available (${errorText(error)}): the exact CPU tracer draws instead`);
      }
    }
  }
  if (!gpu && (state.method === 'polygon' || state.method === 'image-based' || state.split)) {
    throw new Error(`the ${state.split ? 'split view' : state.method + ' method'} needs WebGPU`);
  }
  wireControls();
  await loadInfo();
  requestAnimationFrame(frameLoop);
}

main().catch((error) => showError(errorText(error)));
