// The review page: three.js shows the export's scenes (GLB), the rest is plain DOM.
// Served by `tactcad watch`, it polls /state and on a change reads its data (/data) and only
// the scenes (/scene/<sha256>) and sheets (/sheet/<sha256>) whose bytes changed, keeping the
// camera, the scene, the hidden parts and the sheets' zoom.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

const $ = (id) => document.getElementById(id);
const review = window.__review = { ready: false, frames: 0, firstFrameMs: null, scene: null,
                                   instances: [], sha256: null, shownSha256: null, updates: 0, refusal: null };
const hidden = new Set();          // instance names the reviewer hid (kept across updates)
let highlighted = null;  // the instance name highlighted (kept across updates)
const HIGHLIGHT = 0x806000;  // its emissive colour
let DATA = null;
let SCENES = {};  // scene name -> its GLB: base64 text in this file, bytes once fetched under watch
const LIVE = location.protocol.startsWith('http');  // served by `tactcad watch`
const fetched = new Map();  // sha256 -> GLB bytes fetched under watch
let shown = { name: null, digest: null };  // the scene in the 3D view and its GLB's sha256
let sceneCalls = 0;  // showScene's calls: only the last one may put its scene in the view
let model = null, box = new THREE.Box3();

// --- the 3D view -------------------------------------------------------------------------
const host = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
renderer.localClippingEnabled = true;
host.prepend(renderer.domElement);
const world = new THREE.Scene();
world.background = new THREE.Color(0xf4f5f7);
world.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 2.0));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
sun.position.set(1, 2, 1.5);
world.add(sun);
const camera = new THREE.PerspectiveCamera(35, 1, 1e-4, 100);
const controls = new OrbitControls(camera, renderer.domElement);
controls.addEventListener('change', render);
const clip = new THREE.Plane(new THREE.Vector3(1, 0, 0), 0);

// the camera, for tests and the watch benchmark: [position, target], metres
review.view = () => [camera.position.toArray(), controls.target.toArray()];
// the geometries and textures held on the GPU, for tests: they must not grow with updates
review.gpu = () => ({ ...renderer.info.memory });
// the instances drawn highlighted, for tests
review.lit = () => (model ? instances(model).filter((m) => m.material.emissive.getHex())
                                             .map((m) => m.name) : []);

function render() {
  renderer.render(world, camera);
  review.frames += 1;
  if (review.firstFrameMs === null && model) review.firstFrameMs = performance.now();
}

function resize() {
  const w = host.clientWidth, h = host.clientHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  render();
}
new ResizeObserver(resize).observe(host);

function visibleBox() {
  const b = new THREE.Box3();
  if (model) model.traverse((o) => { if (o.isMesh && o.visible) b.expandByObject(o); });
  return b.isEmpty() ? box.clone() : b;
}

function fit() {  // isometric, the visible parts fitted
  const b = visibleBox();
  if (b.isEmpty()) return;
  const sphere = b.getBoundingSphere(new THREE.Sphere());
  const dist = sphere.radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.05;
  const dir = new THREE.Vector3(1, 0.8, 1).normalize();
  camera.position.copy(sphere.center).addScaledVector(dir, dist);
  camera.near = dist / 100; camera.far = dist * 100;
  camera.updateProjectionMatrix();
  controls.target.copy(sphere.center);
  controls.update();
  render();
}

function applyClip() {
  const axis = $('clip-axis').value;
  $('clip-pos').disabled = $('clip-flip').disabled = !axis;
  if (!axis) { renderer.clippingPlanes = []; render(); return; }
  const i = 'xyz'.indexOf(axis);
  const lo = box.min.getComponent(i), hi = box.max.getComponent(i);
  const at = lo + (hi - lo) * $('clip-pos').value / 1000;
  const n = new THREE.Vector3().setComponent(i, $('clip-flip').checked ? 1 : -1);
  clip.normal.copy(n);
  clip.constant = -n.getComponent(i) * at;
  renderer.clippingPlanes = [clip];
  render();
}
for (const id of ['clip-axis', 'clip-pos', 'clip-flip']) $(id).addEventListener('input', applyClip);
$('fit').addEventListener('click', fit);

function base64Bytes(text) {
  const bin = atob(text);
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out.buffer;
}

function instances(root) {
  const out = [];
  root.traverse((o) => { if (o.isMesh) out.push(o); });
  return out;
}

// a text written only when it changes: each write repaints the page, and with software
// WebGL every repaint composites the 3D canvas again
function setText(node, text) { if (node.textContent !== text) node.textContent = text; }

async function sceneBytes(name, digest) {
  if (SCENES[name]) return typeof SCENES[name] === 'string' ? base64Bytes(SCENES[name]) : SCENES[name];
  if (!LIVE || !digest) return null;
  if (!fetched.has(digest)) {
    const r = await fetch(`/scene/${digest}`, { cache: 'no-store' });
    if (!r.ok) { setText($('status'), `scene ${name}: ${r.status}`); return null; }
    fetched.set(digest, await r.arrayBuffer());
  }
  return fetched.get(digest);
}

async function showScene(name, keepView) {
  const digest = (DATA.scene_sha256 || {})[name] || null;
  if (digest && name === shown.name && digest === shown.digest) {
    review.shownSha256 = DATA.manifest.design.sha256;  // the same bytes: the view stays as it is
    return;
  }
  shown = { name, digest };  // shown or on its way: a second call for the same bytes ends above
  // a fetch or parse finishing after a later call's (a bigger scene, two updates in quick
  // succession) must not replace that call's scene
  const call = ++sceneCalls;
  const bytes = await sceneBytes(name, digest);
  if (call !== sceneCalls) return;
  if (!bytes) { shown = { name: null, digest: null }; return; }
  new GLTFLoader().parse(bytes, '', (gltf) => {
    if (call !== sceneCalls) { dispose(gltf.scene); return; }
    if (model) { world.remove(model); dispose(model); }
    model = gltf.scene;
    for (const m of instances(model)) {
      m.material = m.material.clone();  // own material: highlighting one instance only
      m.material.side = THREE.DoubleSide;  // a section shows the inside faces
      m.material.emissive.setHex(emissiveOf(m));
      m.visible = !hidden.has(m.name);
      m.userData.rest = m.position.clone();  // as placed: the explosion adds to it
      m.userData.color = m.material.color.clone();  // as the STEP colours it: a step greys it
    }
    world.add(model);
    box = new THREE.Box3().setFromObject(model);
    review.scene = name;
    review.shownSha256 = DATA.manifest.design.sha256;  // the design the 3D view now shows
    review.instances = instances(model).map((m) => m.name);
    buildTree();
    applyStep();
    if (keepView) applyClip(); else { fit(); applyClip(); }
    review.ready = true;
  }, (err) => {
    if (call !== sceneCalls) return;
    shown = { name: null, digest: null };
    setText($('status'), `scene ${name}: ${err.message || err}`);
  });
}

// the GPU buffers of a scene no longer shown (removing it from the world keeps them)
function dispose(root) {
  root.traverse((o) => {
    if (o.geometry) o.geometry.dispose();
    for (const m of [o.material].flat()) {
      if (!m) continue;
      for (const v of Object.values(m)) if (v && v.isTexture) v.dispose();
      m.dispose();
    }
  });
}

// --- the part tree: sub-assembly -> instances ------------------------------------------------
function buildTree() {
  const tree = $('tree');
  tree.replaceChildren();
  const groups = new Map();
  for (const m of instances(model)) {
    const g = m.userData.group || 'parts';
    if (!groups.has(g)) groups.set(g, []);
    groups.get(g).push(m);
  }
  for (const [group, members] of groups) {
    const det = document.createElement('details');
    det.open = true;
    const sum = document.createElement('summary');
    const all = document.createElement('input');
    all.type = 'checkbox';
    all.checked = members.some((m) => m.visible);
    all.addEventListener('click', (e) => e.stopPropagation());
    all.addEventListener('change', () => {
      for (const m of members) setVisible(m, all.checked);
      buildTree();
    });
    sum.append(all, ` ${group} (${members.length})`);
    det.append(sum);
    for (const m of members) {
      const row = document.createElement('label');
      row.dataset.instance = m.name;
      if (m.name === highlighted) row.classList.add('hl');
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = m.visible;
      box.addEventListener('change', () => setVisible(m, box.checked));
      const name = document.createElement('span');
      name.className = 'instance';
      name.textContent = ` ${m.name} `;
      const part = document.createElement('span');
      part.className = 'part';
      part.textContent = m.userData.part || '';
      row.append(box, name, part);
      name.addEventListener('click', (e) => { e.preventDefault(); highlight(m.name); });
      det.append(row);
    }
    tree.append(det);
  }
}

function setVisible(mesh, on) {
  mesh.visible = on;
  if (on) hidden.delete(mesh.name); else hidden.add(mesh.name);
  render();
}

function highlight(name) {
  highlighted = highlighted === name ? null : name;
  for (const m of instances(model)) {
    m.material.emissive.setHex(emissiveOf(m));
  }
  for (const row of $('tree').querySelectorAll('label')) {
    row.classList.toggle('hl', row.dataset.instance === highlighted);
  }
  render();
}

// --- the build book: a step's new parts lit in its scene, moved apart by the slider ----------
const STEP_LIT = 0x800080;  // emissive of a step's new parts (the book's pictures: magenta)
let step = null;            // the build-book step shown in the 3D view, or null
// the step shown and the positions of named instances (mm, their parent's frame), for tests
review.step = () => (step ? step.key : null);
review.positions = (names) => Object.fromEntries((model ? instances(model) : [])
  .filter((m) => names.includes(m.name)).map((m) => [m.name, m.position.toArray()]));

const STEP_EARLIER = 0xb8b8b8;  // colour of the parts placed before the shown step (the book's grey)
// where each instance stands in the shown step: 'new' (its parts lit), 'later' (placed by a
// later step: not shown yet), 'earlier' (placed before, or by no step: grey), or '' (no step)
review.stepRoles = () => Object.fromEntries((model ? instances(model) : [])
  .map((m) => [m.name, stepRole(m)]));
review.visible = () => (model ? instances(model).filter((m) => m.visible).map((m) => m.name) : []);

// made once per book (showBook): part -> index of the first step that places it; step key -> index
let firstStep = new Map();
let stepIndex = new Map();

function stepRole(m) {
  if (!step || step.scene !== review.scene) return '';
  const first = firstStep.has(m.userData.part) ? firstStep.get(m.userData.part) : -1;
  const now = stepIndex.get(step.key);
  return first === now ? 'new' : first > now ? 'later' : 'earlier';
}

function emissiveOf(m, role = stepRole(m)) {
  if (m.name === highlighted) return HIGHLIGHT;
  return role === 'new' ? STEP_LIT : 0;
}

function applyStep() {  // the shown step on the model in the view: colours, visibility, explosion
  if (!model) return;
  const t = step && step.scene === shown.name ? Number($('explode').value) / 100 : 0;
  const moves = (step && step.explode) || {};
  for (const m of instances(model)) {
    const role = stepRole(m);
    m.material.emissive.setHex(emissiveOf(m, role));
    if (m.userData.color) {
      if (role === 'earlier') m.material.color.setHex(STEP_EARLIER);
      else m.material.color.copy(m.userData.color);
    }
    m.visible = !hidden.has(m.name) && role !== 'later';
    const d = moves[m.name];
    if (m.userData.rest) m.position.copy(m.userData.rest);
    if (d && t) m.position.add(new THREE.Vector3(d[0], d[1], d[2]).multiplyScalar(t));
  }
  render();
}

function chooseStep(key) {
  step = (DATA.book || []).find((s) => s.key === key) || null;
  const slider = $('explode');
  slider.disabled = !step || !Object.keys(step.explode || {}).length;
  if (!step) slider.value = 0;
  if (step && step.scene !== $('scene-select').value) {
    $('scene-select').value = step.scene;
    showScene(step.scene, false);  // its parse applies the step
  } else applyStep();
}
$('step-select').addEventListener('change', (e) => chooseStep(e.target.value));
$('explode').addEventListener('input', applyStep);

function showBook() {
  const book = DATA.book || [];
  firstStep = new Map();
  stepIndex = new Map(book.map((s, k) => [s.key, k]));
  book.forEach((s, k) => {
    for (const part of s.highlight || []) if (!firstStep.has(part)) firstStep.set(part, k);
  });
  $('step-tools').hidden = $('nav-build').hidden = $('build').hidden = !book.length;
  const sel = $('step-select');
  const keep = sel.value;
  const none = el('option', '(none)');
  none.value = '';
  sel.replaceChildren(none, ...book.map((s, k) => {
    const o = el('option', `${k + 1}. ${s.title}`);
    o.value = s.key;
    return o;
  }));
  sel.value = book.some((s) => s.key === keep) ? keep : '';
  step = book.find((s) => s.key === sel.value) || null;
  const list = el('ol');
  for (const s of book) {
    const item = el('li');
    item.dataset.step = s.key;
    const show = el('button', 'show in 3D');
    show.addEventListener('click', () => { sel.value = s.key; chooseStep(s.key); $('viewer').scrollIntoView(); });
    item.append(el('strong', s.title), ' ', show,
      el('div', s.parts.map((p) => `${p.part} × ${p.quantity}`).join(', '), 'meta'),
      el('div', `Tools: ${s.tools.join(', ') || 'none'}`, 'meta'));
    const notes = el('ul');
    for (const n of s.notes) notes.append(el('li', n));
    item.append(notes);
    list.append(item);
  }
  $('build-body').replaceChildren(list);
}

// --- drawings, tables, provenance ------------------------------------------------------------
function el(tag, text, cls) {
  const e = document.createElement(tag);
  if (text !== undefined && text !== null) e.textContent = text;
  if (cls) e.className = cls;
  return e;
}

function fmt(v) {
  if (typeof v === 'number') return Number.isInteger(v) ? String(v) : v.toPrecision(4);
  if (Array.isArray(v)) return v.map(fmt).join('; ');
  if (v && typeof v === 'object') return JSON.stringify(v);
  return v === null || v === undefined ? '' : String(v);
}

function table(columns, rows, labels) {
  const t = el('table');
  const head = el('tr');
  for (const c of columns) head.append(el('th', (labels && labels[c]) || c));
  t.append(head);
  for (const r of rows) {
    const tr = el('tr');
    for (const c of columns) {
      const v = r[c];
      tr.append(el('td', fmt(v), typeof v === 'number' ? 'num' : ''));
    }
    t.append(tr);
  }
  return t;
}

function zoomable(pane, img) {
  let s = 1, x = 0, y = 0, drag = null;
  const apply = () => { img.style.transform = `translate(${x}px, ${y}px) scale(${s})`; };
  pane.addEventListener('wheel', (e) => {
    e.preventDefault();
    const r = pane.getBoundingClientRect();
    const px = e.clientX - r.left, py = e.clientY - r.top;
    const k = Math.exp(-e.deltaY * 0.0015);
    const ns = Math.min(40, Math.max(0.5, s * k));
    x = px - (px - x) * ns / s; y = py - (py - y) * ns / s; s = ns;
    apply();
  }, { passive: false });
  pane.addEventListener('pointerdown', (e) => { drag = [e.clientX - x, e.clientY - y]; pane.setPointerCapture(e.pointerId); });
  pane.addEventListener('pointermove', (e) => { if (drag) { x = e.clientX - drag[0]; y = e.clientY - drag[1]; apply(); } });
  pane.addEventListener('pointerup', () => { drag = null; });
  pane.addEventListener('dblclick', () => { pane.parentElement.classList.toggle('big'); s = 1; x = y = 0; apply(); });
}

// a sheet's image: inline in this file, fetched by its sha256 under watch
const sheetSource = (sheet) => (sheet.svg_base64 ? 'data:image/svg+xml;base64,' + sheet.svg_base64
                                                  : `/sheet/${sheet.sha256}`);

function sheetCard() {
  const card = el('div', null, 'sheet');
  const h = el('h3');
  h.append(el('span'), el('span', null, 'part'));
  const pane = el('div', null, 'pane');
  const img = el('img');
  pane.append(img);
  zoomable(pane, img);
  card.append(h, pane);
  return card;
}

function fillCard(card, sheet) {  // the image is set again only when its bytes changed
  const [title, path] = card.querySelectorAll('h3 span');
  setText(title, sheet.title);
  setText(path, sheet.path);
  card.dataset.sheet = sheet.path;
  const img = card.querySelector('img');
  img.alt = sheet.title;
  if (card.dataset.sha256 !== sheet.sha256) {
    card.dataset.sha256 = sheet.sha256;
    img.src = sheetSource(sheet);
  }
  return card;
}

// a card is kept, with its zoom, for a sheet of the same bytes (else of the same path), so an
// update fetches only the sheets that changed
function showSheets() {
  const host = $('sheets');
  const spare = [...host.children];
  const take = (keep) => { const i = spare.findIndex(keep); return i < 0 ? null : spare.splice(i, 1)[0]; };
  const cards = DATA.sheets.map((sheet) => fillCard(
    take((c) => c.dataset.sha256 === sheet.sha256) || take((c) => c.dataset.sheet === sheet.path)
    || sheetCard(), sheet));
  if (cards.length !== host.children.length || cards.some((c, i) => host.children[i] !== c)) {
    host.replaceChildren(...cards);
  }
}

function showTables() {
  $('bom-table').replaceChildren(table(DATA.bom.columns, DATA.bom.rows));
  // one rated full-scale force for the design (every record carries the same); each
  // element's own limit is its yield-limited force
  // the columns the records have, in this order; a product's own figures (a die's beams)
  // after them under their own names
  // a die's records are its rows (row, role), each with its own rated force
  const known = ['element', 'row', 'role', 'part_name', 'arm_length_mm', 'stiffness_N_per_mm', 'yield_limited_force_N',
                 'tip_deflection_mm_at_full_scale', 'rated_force_N', 'stress_MPa_per_N', 'stress_MPa_at_full_scale',
                 'stress_MPa_at_rated_force',
                 'yield_safety_factor_at_full_scale', 'gauge_strain_at_full_scale', 'model'];
  const present = new Set(DATA.elements.flatMap((r) => Object.keys(r)));
  const cols = [...known.filter((c) => present.has(c) || !DATA.elements.length),
                ...[...present].filter((c) => !known.includes(c) && c !== 'warnings' && c !== 'full_scale_force_N').sort()];
  const labels = { element: 'element', row: 'row', role: 'role', part_name: 'part', arm_length_mm: 'arm length (mm)',
                   rated_force_N: 'rated force of its row (N)',
                   stress_MPa_at_rated_force: 'root stress at its rated force (MPa)',
                   stiffness_N_per_mm: 'K (N/mm)', yield_limited_force_N: 'yield-limited force (N)',
                   tip_deflection_mm_at_full_scale: 'δ at rated full scale (mm)',
                   stress_MPa_per_N: 'stress (MPa/N)', stress_MPa_at_full_scale: 'stress at rated full scale (MPa)',
                   yield_safety_factor_at_full_scale: 'yield safety factor at rated full scale',
                   gauge_strain_at_full_scale: 'gauge strain at rated full scale', model: 'model',
                   strength_over_stress_at_rating: 'strength of etched silicon / root stress at its rated force' };
  const box = $('elements-table');
  const rated = DATA.elements.length && DATA.elements[0].full_scale_force_N != null
    ? DATA.elements[0].full_scale_force_N : (DATA.full_scale_force_N ?? null);
  box.replaceChildren(...(rated == null ? [] : [el('p', `rated full-scale force ${fmt(rated)} N (the design's)`)]),
                      table(cols, DATA.elements, labels));
  const warned = DATA.elements.filter((r) => r.warnings && r.warnings.length);
  for (const r of warned) box.append(el('p', `${r.element != null ? `element ${r.element}` : `row ${r.row} (${r.role})`}: ${r.warnings.join('; ')}`, 'warn'));
  showVerification();
  showBudget();
  showAtlas();
  showChecks();
  showProvenance();
}

function showData(value) {  // any JSON: a list of records as a table, an object as a list
  if (Array.isArray(value) && value.length && value.every((r) => r && typeof r === 'object' && !Array.isArray(r))) {
    const cols = [...new Set(value.flatMap((r) => Object.keys(r)))];
    return table(cols, value);
  }
  if (value && typeof value === 'object' && !Array.isArray(value)) {
    const dl = el('div');
    for (const [k, v] of Object.entries(value)) {
      dl.append(el('h3', k));
      dl.append(showData(v));
    }
    return dl;
  }
  return el('p', fmt(value));
}

// the matrix's columns as tactcad verify prints them (the page's data comes with sorted keys)
const VERIFY_COLUMNS = ['requirement', 'verdict', 'target', 'predicted', 'margin', 'binds', 'model'];

// a row the closed form leaves undecided and verify's climb decides (review_page.UNDECIDED_CLIMBS)
const UNDECIDED_CLIMBS = 'UNDECIDED at closed form; decided by `tactcad verify`';

function decidedRow(row, checks) {  // the row with the verdict `tactcad check` climbed to, if any
  const found = checks.find((r) => r.check === 'requirement' && r.subject === row.requirement);
  if (!found || row.verdict !== UNDECIDED_CLIMBS) return row;
  const said = found.status || (found.passed ? 'pass' : 'fail');
  const level = (/\(error [^,)]*, ([\w-]+)\)/.exec(found.detail || '') || [])[1] || 'the ladder';
  const verdict = said === 'undecided' ? `UNDECIDED up to ${level} (tactcad check)`
    : `${said.toUpperCase()} at ${level} (tactcad check); undecided at closed form`;
  return { ...row, verdict };
}

function checksOfThisDesign() {  // review/checks.js's results when they are this design's
  const c = window.TACTCAD_CHECKS;
  return c && c.design_sha256 === DATA.manifest.design.sha256 ? c.checks || [] : [];
}

function showVerification() {  // the manifest's verification matrix, when the export has one
  const v = DATA.manifest.verification;
  $('verification').hidden = $('nav-verification').hidden = v === undefined || v === null;
  const key = v ? Object.keys(v).find((k) => k.startsWith('verification matrix')) : undefined;
  const checks = checksOfThisDesign();
  const rows = (key ? v[key] : []).map((r) => decidedRow(r, checks));
  if (key && rows.length && rows.every((r) => 'verdict' in r)) {  // the matrix first, in order
    const rest = Object.fromEntries(Object.entries(v).filter(([k]) => k !== key));
    $('verification-body').replaceChildren(el('h3', key), table(VERIFY_COLUMNS, rows), showData(rest));
  } else {
    $('verification-body').replaceChildren(v ? showData(v) : el('p', ''));
  }
  const unmet = (v && v['requirements not met']) || [];
  setText($('unmet'), unmet.length ? `Requirements not met: ${unmet.join(', ')} (see Verification)` : '');
  $('unmet').classList.toggle('shown', unmet.length > 0);
}

function showTableSection(t, id) {  // a section of one table (title, columns, rows) or hidden
  // a section that does not apply to the product is its one line (title) without a table
  $(id).hidden = $(`nav-${id}`).hidden = !t;
  $(`${id}-body`).replaceChildren(...(t ? [el('p', t.title),
    ...(t.rows.length ? [table(t.columns, t.rows)] : [])] : []));
}

function showBudget() {  // the K_obj error budget, the tissue coupling, the grasp: one table each
  showTableSection(DATA.kobj_budget, 'budget');
  showTableSection(DATA.tissue_coupling, 'tissue');
  showTableSection(DATA.grasp, 'grasp');
}

// the atlas's figure: each judged point over rated force (x) and K_obj span (y), both
// logarithmic; designed points coloured by product and material, the front ringed, refused
// points grey crosses. Hover: the point's figures; click: its design command, copied.
const ATLAS_COLOURS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#17becf'];
const SVG_NS = 'http://www.w3.org/2000/svg';

function svgEl(tag, attrs, text) {
  const e = document.createElementNS(SVG_NS, tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
}

function logAxis(values, from, to) {  // value -> pixel on a log scale padded by 5 %
  const logs = values.map(Math.log10);
  let lo = Math.min(...logs), hi = Math.max(...logs);
  if (!(hi > lo)) { lo -= 0.5; hi += 0.5; }
  const pad = 0.05 * (hi - lo);
  lo -= pad; hi += pad;
  const at = (v) => from + (Math.log10(v) - lo) / (hi - lo) * (to - from);
  const ticks = [];  // decades, and 2 and 5 between them on a short axis
  const steps = hi - lo < 2.5 ? [1, 2, 5] : [1];
  for (let d = Math.floor(lo); d <= Math.ceil(hi); d++) {
    for (const m of steps) {
      const t = m * 10 ** d;
      if (Math.log10(t) >= lo && Math.log10(t) <= hi) ticks.push(Number(t.toPrecision(1)));
    }
  }
  return { at, ticks };
}

function atlasPlot(a, picked) {
  const W = 720, H = 440, L = 70, R = 20, T = 15, B = 50;
  const svg = svgEl('svg', { id: 'atlas-plot', viewBox: `0 0 ${W} ${H}`, role: 'img',
                             'aria-label': 'design atlas: K_obj span against rated force' });
  const marked = a.design ? [a.design] : [];
  const x = logAxis([...a.points, ...marked].map((p) => p.force_N), L, W - R);
  const y = logAxis([...a.points, ...marked].map((p) => p.span), H - B, T);
  svg.append(svgEl('rect', { x: L, y: T, width: W - L - R, height: H - T - B, fill: 'none', stroke: '#999' }));
  for (const t of x.ticks) {
    svg.append(svgEl('line', { x1: x.at(t), x2: x.at(t), y1: T, y2: H - B, stroke: '#eee' }));
    svg.append(svgEl('text', { x: x.at(t), y: H - B + 16, 'text-anchor': 'middle', 'font-size': 11 }, String(t)));
  }
  for (const t of y.ticks) {
    svg.append(svgEl('line', { x1: L, x2: W - R, y1: y.at(t), y2: y.at(t), stroke: '#eee' }));
    svg.append(svgEl('text', { x: L - 6, y: y.at(t) + 4, 'text-anchor': 'end', 'font-size': 11 }, String(t)));
  }
  svg.append(svgEl('text', { x: (L + W - R) / 2, y: H - 12, 'text-anchor': 'middle', 'font-size': 12 }, 'rated full-scale force (N)'));
  svg.append(svgEl('text', { x: 16, y: (T + H - B) / 2, 'text-anchor': 'middle', 'font-size': 12,
                             transform: `rotate(-90 16 ${(T + H - B) / 2})` }, 'K_obj span, high / low'));
  const pick = (p) => () => {
    setText(picked, `${p.title}`);
    if (navigator.clipboard) navigator.clipboard.writeText(p.command).catch(() => {});
  };
  // refused first, so the designed points and the front lie on top
  for (const p of [...a.points].sort((u, v) => u.feasible - v.feasible)) {
    const cx = x.at(p.force_N), cy = y.at(p.span);
    const mark = p.feasible
      ? svgEl('circle', { cx, cy, r: p.front ? 5 : 3.5, fill: ATLAS_COLOURS[p.group % ATLAS_COLOURS.length],
                          stroke: p.front ? '#000' : 'none', 'stroke-width': p.front ? 1.5 : 0 })
      : svgEl('path', { d: `M${cx - 3} ${cy - 3}L${cx + 3} ${cy + 3}M${cx - 3} ${cy + 3}L${cx + 3} ${cy - 3}`,
                        stroke: '#bbb', 'stroke-width': 1.2, class: 'refused' });
    mark.append(svgEl('title', {}, p.title));
    mark.addEventListener('click', pick(p));
    svg.append(mark);
  }
  for (const d of marked) {  // the project's own targets: a star on top
    const cx = x.at(d.force_N), cy = y.at(d.span);
    const star = [...Array(10).keys()].map((i) => {
      const r = i % 2 ? 3.5 : 9, t = Math.PI / 2 + i * Math.PI / 5;
      return `${(cx + r * Math.cos(t)).toFixed(1)},${(cy - r * Math.sin(t)).toFixed(1)}`;
    }).join(' ');
    const mark = svgEl('polygon', { points: star, fill: '#ffd33d', stroke: '#000', 'stroke-width': 1, class: 'this-design' });
    mark.append(svgEl('title', {}, d.title));
    svg.append(mark);
  }
  return svg;
}

function atlasLegend(a) {
  const legend = el('p');
  a.groups.forEach((g, i) => {
    const dot = el('span', '\u25cf ');
    dot.style.color = ATLAS_COLOURS[i % ATLAS_COLOURS.length];
    legend.append(dot, `${g} \u00b7 `);
  });
  legend.append('\u2715 refused \u00b7 \u25ef Pareto front (ringed)');
  if (a.design) legend.append(' \u00b7 \u2605 this design');
  return legend;
}

function showAtlas() {  // the jaw's design atlas, when the project's folder has one
  const a = DATA.atlas;
  $('atlas').hidden = $('nav-atlas').hidden = !a;
  if (!a) { $('atlas-body').replaceChildren(); return; }
  const parts = [el('p', a.title), el('p', a.note, 'meta')];
  if (a.points.length) {
    const picked = el('div', 'Click a point: its figures here, its design command copied.');
    picked.id = 'atlas-picked';
    parts.push(atlasLegend(a), atlasPlot(a, picked), picked);
  }
  if (a.front) parts.push(el('h3', a.front.title), table(a.front.columns, a.front.rows));
  $('atlas-body').replaceChildren(...parts);
}

function showChecks() {
  const c = window.TACTCAD_CHECKS;
  const body = $('checks-body');
  if (!c || c.design_sha256 !== DATA.manifest.design.sha256) {
    body.replaceChildren(el('p', 'Not run on this export yet: `tactcad check --out <this export>` adds its results here.'));
    return;
  }
  // an undecided requirement passes the checks but is not shown as a pass; an info one
  // (reported, not judged: a requirement the lab never stated) is neither passed nor failed
  const status = (r) => r.status || (r.passed ? 'pass' : 'fail');
  const counts = (found) => {
    const bad = found.filter((r) => status(r) === 'fail').length;
    const open = found.filter((r) => status(r) === 'undecided').length;
    const info = found.filter((r) => status(r) === 'info').length;
    return [found.length - bad - open - info, open, bad, info];
  };
  const countText = ([good, open, bad, info]) =>
    `${good} passed, ${open ? `${open} undecided, ` : ''}${bad} failed${info ? `, ${info} info` : ''}`;
  const [good, open, bad, info] = counts(c.checks);
  const head = el('p');
  head.append(el('span', `${good} passed`, 'pass'), ', ');
  if (open) head.append(el('span', `${open} undecided`, 'undecided'), ', ');
  head.append(el('span', `${bad} failed`, bad ? 'fail' : 'pass'));
  if (info) head.append(', ', el('span', `${info} info`, 'info'));
  // one table per check group, in the order the groups run; failures first within each
  const groups = (c.groups || []).map((g) => g.name);
  for (const r of c.checks) if (!groups.includes(r.group)) groups.push(r.group);
  const described = Object.fromEntries((c.groups || []).map((g) => [g.name, g.checks]));
  const parts = [head];
  for (const name of groups) {
    const found = c.checks.filter((r) => r.group === name);
    if (!found.length) continue;
    const n = counts(found);
    const title = el('h3', `${name}: ${countText(n)}`, n[2] ? 'fail' : (n[1] ? 'undecided' : 'pass'));
    const order = { fail: 0, undecided: 1, pass: 2, info: 3 };
    const rows = [...found].sort((a, b) => order[status(a)] - order[status(b)])
      .map((r) => ({ result: { fail: 'FAIL', undecided: 'UNDECIDED', pass: 'pass', info: 'INFO' }[status(r)],
                     check: r.check, subject: r.subject, detail: r.detail }));
    parts.push(title);
    if (described[name]) parts.push(el('p', described[name]));
    parts.push(table(['result', 'check', 'subject', 'detail'], rows));
  }
  body.replaceChildren(...parts);
}

function showProvenance() {
  const m = DATA.manifest;
  const rows = [
    { item: 'design', value: m.design.name },
    { item: 'design file', value: m.design.source },
    { item: 'design sha256', value: m.design.sha256 },
    { item: 'revision', value: DATA.revision },
    { item: 'date', value: DATA.date },
    { item: 'tactcad', value: m.tactcad_version },
    ...Object.entries(m.cad_stack).map(([k, v]) => ({ item: k, value: v })),
    { item: 'three.js (this page)', value: DATA.three_version },
    { item: 'units', value: m.units },
  ];
  $('provenance-body').replaceChildren(table(['item', 'value'], rows));
}

function showHeader() {
  const m = DATA.manifest;
  document.title = `${m.design.name}: review`;
  $('title').textContent = `${m.design.name}: design review`;
  $('subtitle').textContent = `revision ${DATA.revision}, ${DATA.date}, design sha256 ${m.design.sha256.slice(0, 12)}…`;
  review.sha256 = m.design.sha256;
  const sel = $('scene-select');
  const current = sel.value;
  sel.replaceChildren(...DATA.scenes.map((n) => { const o = el('option', n); o.value = n; return o; }));
  if (DATA.scenes.includes(current)) sel.value = current;
}
$('scene-select').addEventListener('change', (e) => showScene(e.target.value, false));

function load() {  // what this file carries
  DATA = JSON.parse($('review-data').textContent);
  SCENES = JSON.parse($('review-scenes').textContent);
  showHeader();
  showBook();
  showScene(DATA.scenes[0], false);
  showSheets();
  showTables();
}

// --- live reload under `tactcad watch` ---------------------------------------------------
function loadLive(live) {
  DATA = live.data;
  if (live.checks) window.TACTCAD_CHECKS = live.checks;
  SCENES = {};  // fetched by sha256 when shown
  const current = new Set(Object.values(DATA.scene_sha256));
  for (const digest of fetched.keys()) if (!current.has(digest)) fetched.delete(digest);
  const before = $('scene-select').value;
  showHeader();
  showBook();
  const name = $('scene-select').value || DATA.scenes[0];
  showScene(name, name === before);  // a scene the update removed: the one shown instead is fitted
  // the 3D view first, then (after a frame) the drawings and tables
  requestAnimationFrame(() => setTimeout(() => { showSheets(); showTables(); }, 0));
}

// seq: the state this page shows; null for the page as served, which may be older than the
// watch's state (the 3D view of an export still running), so it reads /data once at once
// every 200 ms while the watch answers; when it does not (stopped), less and less often,
// up to every 5 s, until it answers again
async function poll(seq, wait = 200) {
  try {
    const state = await (await fetch('/state', { cache: 'no-store' })).json();
    review.refusal = state.refusal;
    setText($('refusal'), state.refusal ? `The last edit was refused; the page shows the last good export.\n${state.refusal}` : '');
    $('refusal').classList.toggle('shown', !!state.refusal);
    setText($('status'), state.status || '');
    if (state.seq !== seq && state.sha256) {
      const live = await (await fetch('/data', { cache: 'no-store' })).json();
      if (live.data) {
        loadLive(live);
        if (seq !== null) review.updates += 1;
      }
      seq = live.seq;
    }
    wait = 200;
  } catch (e) {
    setText($('status'), 'watch: not reachable');
    wait = Math.min(2 * wait, 5000);
  }
  setTimeout(() => poll(seq, wait), wait);
}

load();
// served by `tactcad watch` (its /state answers), not by any web server: follow its updates
if (LIVE) {
  fetch('/state', { cache: 'no-store' }).then((r) => (r.ok ? r.json() : null))
    .then((state) => { if (state && 'seq' in state) poll(null); }).catch(() => {});
}
