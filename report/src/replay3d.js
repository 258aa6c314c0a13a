// 3D attitude replay with three.js: the spacecraft in the inertial frame N,
// its body axes, its reaction-wheel axes (discs spinning with the wheel
// speed sign) and its thrusters (plumes while firing), driven by a timeline.
import {
  WebGLRenderer, Scene, PerspectiveCamera, AmbientLight, DirectionalLight, Group, Mesh, MeshStandardMaterial,
  MeshBasicMaterial, BoxGeometry, CylinderGeometry, ConeGeometry, ArrowHelper, Vector3, Quaternion, Color,
  BufferGeometry, LineBasicMaterial, Line, Float32BufferAttribute, CanvasTexture, SpriteMaterial, Sprite,
  EdgesGeometry, LineSegments, GridHelper, SphereGeometry, LineDashedMaterial,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { indexedKeys, alignSeries, isNumArray, sampleIndex, el, fmt } from './data.js';
import { attitudeSamples, rendererQuat, referenceQuat } from './attitude.js';
import { PALETTE, AXIS_COLORS, setMarkerTime } from './plots.js';

function label(text, color, size) {
  const c = document.createElement('canvas');
  c.width = 128;
  c.height = 64;
  const g = c.getContext('2d');
  g.font = 'bold 40px sans-serif';
  g.fillStyle = color;
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, 64, 32);
  const s = new Sprite(new SpriteMaterial({ map: new CanvasTexture(c), depthTest: false, transparent: true }));
  s.scale.set(size * 2, size, 1);
  return s;
}

function vec3(a) {
  if (!Array.isArray(a) || a.length < 3) return null;
  const v = new Vector3(Number(a[0]), Number(a[1]), Number(a[2]));
  return Number.isFinite(v.x) && Number.isFinite(v.y) && Number.isFinite(v.z) ? v : null;
}

function line(a, b, color, opacity = 1) {
  const g = new BufferGeometry();
  g.setAttribute('position', new Float32BufferAttribute([a.x, a.y, a.z, b.x, b.y, b.z], 3));
  return new Line(g, new LineBasicMaterial({ color, transparent: opacity < 1, opacity }));
}

// no spread of long arrays into Math.max (argument-count limits)
function maxAbs(a) {
  let m = 0;
  if (a) for (const v of a) if (typeof v === 'number' && Math.abs(v) > m) m = Math.abs(v);
  return m;
}

function webglAvailable() {
  try {
    const c = document.createElement('canvas');
    return !!(window.WebGLRenderingContext && (c.getContext('webgl2') || c.getContext('webgl')));
  } catch (e) {
    return false;
  }
}

// opts.live: no timeline; returns { show(t, q_BN, wheel_rpm[], thruster_level[]) } for
// the live view (live.js), which poses the same scene with each new frame.
export function buildReplay(root, D, status, opts = {}) {
  const att = attitudeSamples(D.attitude);
  const geom = D.geometry || {};
  const wheelAxes = [];
  const wheelPos = [];
  const wpos = Array.isArray(geom.wheel_positions_B) ? geom.wheel_positions_B : [];
  (Array.isArray(geom.wheel_axes_B) ? geom.wheel_axes_B : []).forEach((a, i) => {
    const v = vec3(a);
    if (!v || !(v.length() > 0)) return;
    wheelAxes.push(v.normalize());
    wheelPos.push(vec3(wpos[i]));
  });
  const wheelNames = wheelAxes.map((_, i) => (Array.isArray(geom.wheel_names) && typeof geom.wheel_names[i] === 'string' && geom.wheel_names[i]
    ? geom.wheel_names[i] : 'w' + i));
  const thrusters = (Array.isArray(geom.thrusters) ? geom.thrusters : [])
    .map((th, i) => (th && typeof th === 'object' ? { r: vec3(th.r_B), d: vec3(th.dir_B), name: typeof th.name === 'string' && th.name ? th.name : 't' + i } : {}))
    .filter((th) => th.r && th.d && th.d.length() > 0)
    .map((th) => ({ r: th.r, d: th.d.normalize(), name: th.name }));

  const card = el('div', { class: 'card wide' });
  root.appendChild(card);
  if (!att.t.length && !opts.live) card.appendChild(el('p', { class: 'absent', text: 'No attitude history in this run: the spacecraft is shown at the identity attitude.' }));
  if (!webglAvailable()) {
    card.appendChild(el('p', { class: 'absent', text: 'This browser offers no WebGL: the 3D replay cannot be shown.' }));
    status.replay = 'no-webgl';
    return;
  }

  // --- scene ---------------------------------------------------------------
  let hx = 0.5;
  let hy = 0.5;
  let hz = 0.5;
  // the bus: thrusters on its faces (0.9 of their offsets), wheels inside it
  const pts = thrusters.map((t) => t.r.clone().multiplyScalar(0.9)).concat(wheelPos.filter(Boolean).map((p) => p.clone().multiplyScalar(1.15)));
  if (pts.length) {
    hx = Math.max(0.2, ...pts.map((p) => Math.abs(p.x)));
    hy = Math.max(0.2, ...pts.map((p) => Math.abs(p.y)));
    hz = Math.max(0.2, ...pts.map((p) => Math.abs(p.z)));
    const m = Math.max(hx, hy, hz);
    hx = Math.max(hx, 0.35 * m);
    hy = Math.max(hy, 0.35 * m);
    hz = Math.max(hz, 0.35 * m);
  }
  const S = Math.max(hx, hy, hz); // characteristic size [m]
  const scene = new Scene();
  scene.background = new Color('#0e1726');
  scene.add(new AmbientLight(0xffffff, 0.55));
  const sun = new DirectionalLight(0xffffff, 1.6);
  sun.position.set(3, 2, 4);
  scene.add(sun);
  const grid = new GridHelper(8 * S, 16, 0x2a3a55, 0x1b2740);
  grid.rotation.x = Math.PI / 2; // the n1-n2 plane
  grid.position.z = -2.2 * S;
  scene.add(grid);

  // inertial axes
  const NL = 3.2 * S;
  ['n1', 'n2', 'n3'].forEach((name, i) => {
    const d = new Vector3(i === 0 ? 1 : 0, i === 1 ? 1 : 0, i === 2 ? 1 : 0);
    scene.add(line(new Vector3(0, 0, 0), d.clone().multiplyScalar(NL), AXIS_COLORS[i], 0.45));
    const l = label(name, '#8fa3bf', 0.3 * S);
    l.position.copy(d.clone().multiplyScalar(NL * 1.07));
    scene.add(l);
  });

  const body = new Group();
  scene.add(body);
  const bus = new Mesh(new BoxGeometry(2 * hx, 2 * hy, 2 * hz),
    new MeshStandardMaterial({ color: 0xb8c4d6, metalness: 0.2, roughness: 0.6, transparent: true, opacity: 0.28, depthWrite: false }));
  body.add(bus);
  body.add(new LineSegments(new EdgesGeometry(bus.geometry), new LineBasicMaterial({ color: 0xd0d8e8 })));
  // a solar array along +b3 side so the attitude reads at a glance
  const panel = new Mesh(new BoxGeometry(0.04 * S, 2.6 * hy, 1.2 * hz), new MeshStandardMaterial({ color: 0x23407a, metalness: 0.5, roughness: 0.4 }));
  panel.position.set(-hx - 0.02 * S, 0, 0);
  body.add(panel);

  const BL = 2.3 * S;
  ['b1', 'b2', 'b3'].forEach((name, i) => {
    const d = new Vector3(i === 0 ? 1 : 0, i === 1 ? 1 : 0, i === 2 ? 1 : 0);
    body.add(new ArrowHelper(d, new Vector3(0, 0, 0), BL, new Color(AXIS_COLORS[i]).getHex(), 0.18 * S, 0.09 * S));
    const l = label(name, AXIS_COLORS[i], 0.3 * S);
    l.position.copy(d.clone().multiplyScalar(BL * 1.1));
    body.add(l);
  });

  // wheels: disc on its spin axis at 0.55 S along it, with a rim marker
  const series = D.series || {};
  const t = D.t;
  const wheelSpeedKeys = indexedKeys(series, 'wheel_speed_rpm_');
  const wheelSpeeds = wheelAxes.map((_, i) => {
    const k = wheelSpeedKeys.find((w) => w.index === i) || wheelSpeedKeys[i];
    return k ? alignSeries(series[k.key], t.length) : null;
  });
  const maxRpm = opts.maxRpm || wheelSpeeds.reduce((m, s) => Math.max(m, maxAbs(s)), 1);
  const spinners = wheelAxes.map((a, i) => {
    const color = PALETTE[(i + 3) % PALETTE.length];
    const holder = new Group();
    holder.quaternion.setFromUnitVectors(new Vector3(0, 1, 0), a);
    // at its position in B when given and inside the drawn bus, else along its axis
    const p = wheelPos[i];
    if (p && Math.abs(p.x) <= hx && Math.abs(p.y) <= hy && Math.abs(p.z) <= hz && p.length() > 0.05 * S) holder.position.copy(p);
    else holder.position.copy(a.clone().multiplyScalar(0.55 * Math.min(hx, hy, hz)));
    const spin = new Group();
    holder.add(spin);
    const disc = new Mesh(new CylinderGeometry(0.2 * S, 0.2 * S, 0.05 * S, 32), new MeshStandardMaterial({ color, metalness: 0.4, roughness: 0.4 }));
    spin.add(disc);
    const mark = new Mesh(new BoxGeometry(0.06 * S, 0.07 * S, 0.06 * S), new MeshBasicMaterial({ color: 0xffffff }));
    mark.position.set(0.17 * S, 0, 0);
    spin.add(mark);
    body.add(holder);
    body.add(new ArrowHelper(a, new Vector3(0, 0, 0), 1.35 * S, new Color(color).getHex(), 0.1 * S, 0.05 * S));
    holder.name = 'wheel:' + wheelNames[i];
    const l = label(wheelNames[i], color, 0.22 * S);
    l.position.copy(a.clone().multiplyScalar(1.45 * S));
    body.add(l);
    return { spin, disc, color: new Color(color), angle: 0, name: wheelNames[i] };
  });

  // thrusters: nozzle at r_B, plume along -dir_B scaled with the firing level
  const forceKeys = indexedKeys(series, 'thruster_force_');
  const onKeys = indexedKeys(series, 'thruster_on_time_');
  const level = thrusters.map((_, i) => {
    const fk = forceKeys.find((k) => k.index === i);
    const ok = onKeys.find((k) => k.index === i);
    const src = fk || ok;
    if (!src) return null;
    const y = alignSeries(series[src.key], t.length);
    const mx = Math.max(1e-300, maxAbs(y));
    return y.map((v) => (v === null ? 0 : Math.min(1, Math.abs(v) / mx)));
  });
  const plumes = thrusters.map((th, i) => {
    const g = new Group();
    g.position.copy(th.r);
    g.quaternion.setFromUnitVectors(new Vector3(0, 1, 0), th.d.clone().negate()); // +y of g = exhaust
    const nozzle = new Mesh(new ConeGeometry(0.09 * S, 0.2 * S, 16, 1, true), new MeshStandardMaterial({ color: 0xc9a46a, metalness: 0.6, roughness: 0.35, side: 2 }));
    nozzle.rotation.x = Math.PI; // opening towards the exhaust
    nozzle.position.y = 0.1 * S;
    g.add(nozzle);
    const plumeGeom = new ConeGeometry(0.13 * S, 1, 20, 1, true);
    plumeGeom.translate(0, -0.5, 0);
    plumeGeom.rotateX(Math.PI); // apex at the nozzle, widening along +y
    const plume = new Mesh(plumeGeom, new MeshBasicMaterial({ color: 0xffa23a, transparent: true, opacity: 0.75, side: 2, depthWrite: false }));
    plume.position.y = 0.2 * S;
    plume.visible = false;
    plume.name = 'plume:' + th.name;
    g.name = 'thruster:' + th.name;
    g.add(plume);
    body.add(g);
    return { plume, level: level[i] };
  });

  const extras = sceneExtras(scene, body, D, S);

  // --- renderer, camera, controls ----------------------------------------------
  let renderer;
  try {
    renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    card.appendChild(el('p', { class: 'absent', text: 'WebGL context could not be created: ' + e.message }));
    status.replay = 'no-webgl';
    return;
  }
  const H = 440;
  const width = () => Math.max(280, Math.floor(card.getBoundingClientRect().width) - 24);
  renderer.setPixelRatio(Math.min(2, window.devicePixelRatio || 1));
  renderer.setSize(width(), H);
  const view = el('div', { class: 'replay-view' });
  view.appendChild(renderer.domElement);
  const camera = new PerspectiveCamera(40, width() / H, 0.01 * S, 200 * S);
  camera.up.set(0, 0, 1);
  camera.position.set(6.4 * S, 4.9 * S, 3.6 * S);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.set(0, 0, 0);
  controls.update();

  status.sceneObjects = extras.names(); // for the browser tests
  if (opts.live) return liveScene(card, view, renderer, scene, camera, controls, body, spinners, plumes, maxRpm, S, status, width, H);

  // --- timeline ----------------------------------------------------------------
  const t0 = att.t.length ? att.t[0] : t.length ? t[0] : 0;
  const t1 = att.t.length ? att.t[att.t.length - 1] : t.length ? t[t.length - 1] : 0;
  const span = Math.max(t1 - t0, 0);
  const niceSpeeds = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000];
  const autoSpeed = niceSpeeds.find((s) => span / s <= 40) || niceSpeeds[niceSpeeds.length - 1];
  const play = el('button', { class: 'play', text: '\u25b6 play' });
  const slider = el('input', { type: 'range', min: '0', max: '10000', value: '0', step: '1', class: 'timeline' });
  const speed = el('select', null, ...niceSpeeds.map((s) => {
    const o = el('option', { value: String(s), text: s + '\u00d7' });
    if (s === autoSpeed) o.selected = true;
    return o;
  }));
  const readout = el('div', { class: 'readout' });
  const track = el('span', { class: 'timeline-track' }, slider);
  const burn = extras.burn;
  if (burn && span > 0) {
    // the main-engine burn on the timeline
    const a = Math.max(0, Math.min(1, (burn.t0 - t0) / span));
    const b = Math.max(0, Math.min(1, (burn.t1 - t0) / span));
    if (b > a) track.appendChild(el('span', { class: 'burn-band', title: `burn ${burn.thruster} ${fmt(burn.t0)} to ${fmt(burn.t1)} s`,
      style: `left:${(100 * a).toFixed(2)}%;width:${(100 * (b - a)).toFixed(2)}%` }));
  }
  card.appendChild(el('div', { class: 'controls' }, play, track, el('label', null, ' speed ', speed)));
  card.appendChild(view);
  card.appendChild(readout);
  card.appendChild(el('p', { class: 'note', text:
    'Inertial frame N (faint axes n1 n2 n3); body axes b1 (red), b2 (green), b3 (blue); the attitude reference R the flight software tracks ' +
    '(dashed r1 r2 r3, from the recorded sigma_BR: on the body axes when the error is zero); the Sun vector (yellow); wheel spin axes, named ' +
    'as in the scenario, with discs that turn with the sign of the wheel speed and brighten with its magnitude; thruster plumes (orange) along ' +
    '-dir_B while a thruster fires, length proportional to the force (or on-time); fields of view: the coarse sun sensors (pale yellow, ' +
    'their half angle) and the star tracker along its boresight (blue, drawn with a 10 deg half angle: the model has no field-of-view limit; ' +
    'red: its Sun exclusion cone when set). ' + (extras.orbit ? 'Inset: the central body, the trajectory (grey), the burn arc (orange) and the ' +
    'spacecraft (white), seen along the orbit normal. ' : '') + (burn ? 'The burn window is the orange band on the timeline. ' : '') +
    'Drag to orbit, wheel to zoom. The replay time is the dashed orange line on the time plots; click a plot to jump there.' }));

  const pe = isNumArray(series.pointing_error_deg) ? alignSeries(series.pointing_error_deg, t.length) : null;
  const qa = new Quaternion();
  const qb = new Quaternion();
  let tNow = t0;
  let playing = false;

  const setTime = (x) => {
    tNow = Math.min(t1, Math.max(t0, x));
    if (att.t.length) {
      const i = sampleIndex(att.t, tNow);
      const j = Math.min(i + 1, att.t.length - 1);
      qa.fromArray(att.q[i]);
      if (j !== i && att.t[j] > att.t[i]) {
        qb.fromArray(att.q[j]);
        qa.slerp(qb, Math.min(1, Math.max(0, (tNow - att.t[i]) / (att.t[j] - att.t[i]))));
      }
      body.quaternion.copy(qa);
    }
    const k = t.length ? sampleIndex(t, tNow) : -1;
    const parts = [`t = ${fmt(tNow, 6)} s`];
    if (pe && k >= 0) parts.push(`pointing error ${fmt(pe[k])} deg`);
    spinners.forEach((w, i) => {
      const s = wheelSpeeds[i];
      const v = s && k >= 0 ? s[k] : null;
      w.speed = v === null ? 0 : v;
      const mag = Math.min(1, Math.abs(w.speed) / maxRpm);
      w.disc.material.color.copy(w.color).multiplyScalar(0.45 + 0.75 * mag);
      if (v !== null) parts.push(`${w.name} ${fmt(v)} rpm`);
    });
    let firing = 0;
    plumes.forEach((p) => {
      const lv = p.level && k >= 0 ? p.level[k] : 0;
      p.plume.visible = lv > 0;
      if (lv > 0) { firing++; p.plume.scale.set(1, Math.max(0.15, lv) * 1.2 * S, 1); }
    });
    if (plumes.length) parts.push(`${firing}/${plumes.length} thrusters firing`);
    if (burn) parts.push(tNow >= burn.t0 && tNow <= burn.t1 ? `burn (${burn.thruster}) on` : `burn (${burn.thruster}) ${fmt(burn.t0)} to ${fmt(burn.t1)} s`);
    extras.update(tNow, k);
    readout.textContent = parts.join('   \u00b7   ');
    if (span > 0) slider.value = String(Math.round(((tNow - t0) / span) * 10000));
    setMarkerTime(tNow);
  };
  window.addEventListener('kestrel:time', (e) => setTime(Number(e.detail)));
  slider.addEventListener('input', () => setTime(t0 + (Number(slider.value) / 10000) * span));
  play.addEventListener('click', () => {
    if (!playing && tNow >= t1) setTime(t0);
    playing = !playing;
    play.textContent = playing ? '\u275a\u275a pause' : '\u25b6 play';
  });

  let last = performance.now();
  const frame = (now) => {
    const dtReal = Math.min(0.1, Math.max(0, (now - last) / 1000));
    last = now;
    if (playing) {
      setTime(tNow + dtReal * Number(speed.value));
      if (tNow >= t1) { playing = false; play.textContent = '\u25b6 play'; }
      for (const w of spinners) {
        w.angle += Math.sign(w.speed) * (0.5 + 3 * Math.min(1, Math.abs(w.speed) / maxRpm)) * dtReal * 2 * Math.PI * (w.speed ? 1 : 0);
        w.spin.rotation.y = w.angle;
      }
    }
    controls.update();
    renderAll(renderer, scene, camera);
    requestAnimationFrame(frame);
  };
  window.addEventListener('resize', () => {
    renderer.setSize(width(), H);
    camera.aspect = width() / H;
    camera.updateProjectionMatrix();
  });
  setTime(t0);
  renderAll(renderer, scene, camera);
  requestAnimationFrame(frame);
  status.replay = 'ok';
  status.replayFrames = att.t.length;
}

// The live view's use of the scene: posed by show() with each frame, the
// wheels turning with their speed's sign, plumes scaled by the level (force
// relative to the largest seen, or 1 for an on-time > 0).
function liveScene(card, view, renderer, scene, camera, controls, body, spinners, plumes, maxRpm, S, status, width, H) {
  const readout = el('div', { class: 'readout' });
  card.appendChild(view);
  card.appendChild(readout);
  card.appendChild(el('p', { class: 'note', text:
    'Inertial frame N (faint axes n1 n2 n3); body axes b1 (red), b2 (green), b3 (blue); wheel discs turn with the sign of the wheel ' +
    'speed and brighten with its magnitude; thruster plumes (orange) along -dir_B. Drag to orbit, wheel to zoom.' }));
  let fmax = 1e-300;
  const show = (t, q, speeds, levels) => {
    const qr = rendererQuat(q);  // scalar-first passive q_BN -> the renderer's rotation (attitude.js)
    if (qr) body.quaternion.copy(new Quaternion().fromArray(qr));
    const parts = [`t = ${fmt(t, 6)} s`];
    spinners.forEach((w, i) => {
      const v = speeds[i];
      w.speed = v === null || v === undefined ? 0 : v;
      const mag = Math.min(1, Math.abs(w.speed) / maxRpm);
      w.disc.material.color.copy(w.color).multiplyScalar(0.45 + 0.75 * mag);
      parts.push(`${w.name} ${fmt(v)} rpm`);
    });
    let firing = 0;
    plumes.forEach((p, i) => {
      const f = Math.abs(levels[i] || 0);
      fmax = Math.max(fmax, f);
      const lv = Math.min(1, f / fmax);
      p.plume.visible = lv > 0;
      if (lv > 0) { firing++; p.plume.scale.set(1, Math.max(0.15, lv) * 1.2 * S, 1); }
    });
    if (plumes.length) parts.push(`${firing}/${plumes.length} thrusters firing`);
    readout.textContent = parts.join('   \u00b7   ');
  };
  // at most 10 drawings a second: the page shares the machine with the run
  // (software WebGL in a headless or GPU-less browser costs a core at 60 Hz)
  let last = performance.now();
  const frame = (now) => {
    requestAnimationFrame(frame);
    if (now - last < 100) return;
    const dtReal = Math.min(0.2, Math.max(0, (now - last) / 1000));
    last = now;
    for (const w of spinners) {
      w.angle += Math.sign(w.speed || 0) * (0.5 + 3 * Math.min(1, Math.abs(w.speed || 0) / maxRpm)) * dtReal * 2 * Math.PI;
      w.spin.rotation.y = w.angle;
    }
    controls.update();
    renderAll(renderer, scene, camera);
  };
  window.addEventListener('resize', () => {
    renderer.setSize(width(), H);
    camera.aspect = width() / H;
    camera.updateProjectionMatrix();
  });
  renderAll(renderer, scene, camera);
  requestAnimationFrame(frame);
  status.replay = 'ok';
  return { show };
}

// Draws the scene and, when there is one, the orbit inset (scene.userData.inset).
function renderAll(renderer, scene, camera) {
  renderer.render(scene, camera);
  if (scene.userData.inset) scene.userData.inset(renderer);
}

function unitVec(a) {
  const v = vec3(a);
  return v && v.length() > 0 ? v.normalize() : null;
}

// A cone of half angle `half` [rad] and slant length L along `axis` (B),
// apex at the origin: a sensor's field of view.
function fovCone(axis, half, L, color, opacity, name) {
  const h = L * Math.cos(half);
  const r = L * Math.sin(half);
  const g = new ConeGeometry(r, h, 32, 1, true);
  g.translate(0, -h / 2, 0);
  g.rotateX(Math.PI); // apex at the origin, opening along +y
  const m = new Mesh(g, new MeshBasicMaterial({ color, transparent: true, opacity, side: 2, depthWrite: false }));
  m.quaternion.setFromUnitVectors(new Vector3(0, 1, 0), axis);
  m.name = name;
  return m;
}

// What a reference visualization shows around the spacecraft, from the run
// data: the Sun vector (geometry.sun, the Sun's position in N over the run,
// less the spacecraft's r_BN_N when recorded), the attitude reference frame
// R (from the recorded tracking error sigma_BR), the fields of view of the
// star tracker and of the coarse sun sensors (geometry.sensors), and for an
// orbit (geometry.central_body with r_BN_N recorded) an inset with the
// central body, the trajectory, the burn arc and the spacecraft's position.
// Returns { update(tNow, k), names(), burn }.
function sceneExtras(scene, body, D, S) {
  const geom = D.geometry || {};
  const series = D.series || {};
  const t = D.t || [];
  const n = t.length;
  const col = (k) => (isNumArray(series[k]) ? alignSeries(series[k], n) : null);
  const rN = ['x', 'y', 'z'].map((a) => col(`r_BN_N_${a}`));
  const hasR = rN.every(Boolean);
  const sBR = ['x', 'y', 'z'].map((a) => col(`sigma_BR_${a}`));
  const hasRef = sBR.every(Boolean);
  const updates = [];
  const insetScenes = [];

  // --- Sun vector, in N ---------------------------------------------------------
  const sun = geom.sun && Array.isArray(geom.sun.t) && Array.isArray(geom.sun.r_N) ? geom.sun : null;
  const sunT = [];
  const sunR = [];
  if (sun) for (let i = 0; i < Math.min(sun.t.length, sun.r_N.length); i++) {
    const v = vec3(sun.r_N[i]);
    if (v && typeof sun.t[i] === 'number' && (!sunT.length || sun.t[i] > sunT[sunT.length - 1])) { sunT.push(sun.t[i]); sunR.push(v); }
  }
  const sunAt = (tNow, k) => {
    if (!sunR.length) return null;
    const i = sampleIndex(sunT, tNow);
    const p = sunR[i].clone();
    if (i + 1 < sunR.length && tNow > sunT[i]) p.lerp(sunR[i + 1], Math.min(1, (tNow - sunT[i]) / (sunT[i + 1] - sunT[i])));
    if (hasR && k >= 0 && rN.every((c) => c[k] !== null)) p.sub(new Vector3(rN[0][k], rN[1][k], rN[2][k]));
    return p.length() > 0 ? p.normalize() : null;
  };
  if (sunR.length) {
    const d0 = sunAt(t.length ? t[0] : 0, t.length ? 0 : -1) || new Vector3(1, 0, 0);
    const arrow = new ArrowHelper(d0, new Vector3(0, 0, 0), 2.6 * S, 0xffd23f, 0.25 * S, 0.14 * S);
    arrow.name = 'sun-vector';
    scene.add(arrow);
    const l = label('Sun', '#ffd23f', 0.32 * S);
    l.name = 'sun-label';
    l.position.copy(d0.clone().multiplyScalar(2.85 * S));
    scene.add(l);
    updates.push((tNow, k) => {
      const d = sunAt(tNow, k);
      if (!d) return;
      arrow.setDirection(d);
      l.position.copy(d.clone().multiplyScalar(2.85 * S));
    });
  }

  // --- the attitude reference frame R, in N --------------------------------
  if (hasRef) {
    const ref = new Group();
    ref.name = 'reference-frame';
    ['r1', 'r2', 'r3'].forEach((nm, i) => {
      const d = new Vector3(i === 0 ? 1 : 0, i === 1 ? 1 : 0, i === 2 ? 1 : 0);
      const g = new BufferGeometry();
      g.setAttribute('position', new Float32BufferAttribute([0, 0, 0, ...d.clone().multiplyScalar(2.7 * S).toArray()], 3));
      const ln = new Line(g, new LineDashedMaterial({ color: AXIS_COLORS[i], dashSize: 0.12 * S, gapSize: 0.08 * S }));
      ln.computeLineDistances();
      ref.add(ln);
      const l = label(nm, AXIS_COLORS[i], 0.26 * S);
      l.position.copy(d.clone().multiplyScalar(2.85 * S));
      ref.add(l);
    });
    scene.add(ref);
    updates.push((tNow, k) => {
      if (k < 0) return;
      const s = [sBR[0][k], sBR[1][k], sBR[2][k]];
      const q = referenceQuat(body.quaternion.toArray(), s);
      ref.visible = !!q;
      if (q) ref.quaternion.fromArray(q);
    });
  }

  // --- fields of view, in B ---------------------------------------------------
  const sens = geom.sensors && typeof geom.sensors === 'object' ? geom.sensors : {};
  if (sens.css && Array.isArray(sens.css.normals_B)) {
    const fov = (Number(sens.css.fov_deg) > 0 ? Math.min(90, Number(sens.css.fov_deg)) : 90) * Math.PI / 180;
    sens.css.normals_B.forEach((nv, i) => {
      const a = unitVec(nv);
      if (a) body.add(fovCone(a, Math.min(fov, 89.5 * Math.PI / 180), 0.9 * S, 0xffe680, 0.07, `fov:css:${i}`));
    });
  }
  if (sens.star_tracker) {
    const a = unitVec(sens.star_tracker.boresight_B) || new Vector3(0, 0, 1);
    // the model has no field-of-view limit: the cone marks the boresight with a typical 10 deg half angle
    body.add(fovCone(a, (10 * Math.PI) / 180, 3.4 * S, 0x5fd3ff, 0.22, 'fov:star_tracker'));
    const ex = Number(sens.star_tracker.sun_exclusion_deg);
    if (ex > 0) body.add(fovCone(a, Math.min(ex, 89.5) * Math.PI / 180, 1.6 * S, 0xff5040, 0.06, 'fov:star_tracker_sun_exclusion'));
  }

  // --- burn window -------------------------------------------------------------
  const b = geom.burn && typeof geom.burn === 'object' ? geom.burn : null;
  const burn = b && Number.isFinite(b.start) && Number.isFinite(b.duration) && b.duration > 0
    ? { thruster: typeof b.thruster === 'string' ? b.thruster : '', t0: b.start, t1: b.start + b.duration } : null;

  // --- the orbit inset: central body, trajectory, burn arc, position -----------
  const cb = geom.central_body && typeof geom.central_body === 'object' ? geom.central_body : null;
  let inset = null;
  if (cb && hasR) {
    const pts = [];
    let E = Number(cb.radius) > 0 ? Number(cb.radius) : 0;
    for (let k = 0; k < n; k++) {
      if (rN.some((c) => c[k] === null)) continue;
      const p = new Vector3(rN[0][k], rN[1][k], rN[2][k]);
      E = Math.max(E, p.length());
      pts.push([k, p]);
    }
    if (pts.length >= 2 && E > 0) {
      const os = new Scene();
      os.background = new Color('#0a1220');
      os.add(new AmbientLight(0xffffff, 0.5));
      const light = new DirectionalLight(0xffffff, 1.4);
      os.add(light);
      const R = Number(cb.radius) > 0 ? Number(cb.radius) / E : 0.02;
      const planet = new Mesh(new SphereGeometry(R, 48, 24), new MeshStandardMaterial({ color: cb.name === 'Mars' ? 0xc1623f : 0x3a6fb0, roughness: 0.9 }));
      planet.name = 'central-body';
      os.add(planet);
      const tl = label(String(cb.name || 'central body'), '#9fb4d0', 0.12);
      tl.position.set(0, 0, R + 0.1);
      os.add(tl);
      const line = (sel, color, name) => {
        const xs = pts.filter(([k]) => sel(t[k])).flatMap(([, p]) => [p.x / E, p.y / E, p.z / E]);
        if (xs.length < 6) return;
        const g = new BufferGeometry();
        g.setAttribute('position', new Float32BufferAttribute(xs, 3));
        const l = new Line(g, new LineBasicMaterial({ color }));
        l.name = name;
        os.add(l);
      };
      line(() => true, 0x8fa3bf, 'trajectory');
      if (burn) line((x) => x >= burn.t0 && x <= burn.t1, 0xff8c1a, 'burn-arc');
      const sc = new Mesh(new SphereGeometry(0.035, 16, 8), new MeshBasicMaterial({ color: 0xffffff }));
      sc.name = 'spacecraft-position';
      os.add(sc);
      const sunLine = new ArrowHelper(new Vector3(1, 0, 0), new Vector3(0, 0, 0), 1.35, 0xffd23f, 0.08, 0.05);
      sunLine.name = 'inset-sun';
      os.add(sunLine);
      // look along the orbit normal (r x v of the first samples)
      const p0 = pts[0][1];
      const p1 = pts[Math.min(pts.length - 1, Math.max(1, Math.floor(pts.length / 8)))][1];
      const h = p0.clone().cross(p1);
      const nrm = h.length() > 0 ? h.normalize() : new Vector3(0, 0, 1);
      const cam = new PerspectiveCamera(40, 1, 0.01, 100);
      cam.up.copy(Math.abs(nrm.z) < 0.9 ? new Vector3(0, 0, 1) : new Vector3(0, 1, 0));
      cam.position.copy(nrm.clone().multiplyScalar(3.3));
      cam.lookAt(0, 0, 0);
      light.position.copy(cam.position);
      updates.push((tNow, k) => {
        if (k >= 0 && rN.every((c) => c[k] !== null)) sc.position.set(rN[0][k] / E, rN[1][k] / E, rN[2][k] / E);
        const d = sunAt(tNow, -1);
        if (d) { sunLine.setDirection(d); light.position.copy(d.clone().multiplyScalar(5)); }
      });
      insetScenes.push(os);
      inset = (renderer) => {
        const size = renderer.getSize(new Vector3());
        const w = Math.round(Math.min(0.34 * size.x, 0.55 * size.y));
        renderer.setScissorTest(true);
        renderer.setViewport(size.x - w - 8, 8, w, w);
        renderer.setScissor(size.x - w - 8, 8, w, w);
        renderer.render(os, cam);
        renderer.setScissorTest(false);
        renderer.setViewport(0, 0, size.x, size.y);
      };
      scene.userData.inset = inset;
    }
  }

  const names = () => {
    const out = [];
    for (const s of [scene, ...insetScenes]) s.traverse((o) => { if (o.name) out.push(o.name); });
    return out;
  };
  return { update: (tNow, k) => updates.forEach((f) => f(tNow, k)), names, burn, orbit: !!inset };
}
