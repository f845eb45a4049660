// --- live reload under `tactcad watch` ---------------------------------------------------
// Served by the watch in place of the export's own live reload (export/live_page.py): on a
// change the page reads its data alone (/data) and fetches a scene's GLB (/scene/<sha256>)
// only when its bytes changed; a scene whose bytes did not change is not parsed again.
const LIVE = @@LIVE@@;  // {seq, scenes: {name: sha256 of its GLB}} of the page as served
const glbs = new Map();  // sha256 -> the GLB's bytes, fetched once
let shown = { name: null, digest: null };  // the scene in the 3D view

// the scenes fetched here are GLB bytes already, the page's own are base64
const decodeBase64 = base64Bytes;
base64Bytes = (scene) => (typeof scene === 'string' ? decodeBase64(scene) : scene);

const showSceneNow = showScene;
showScene = async (name, keepView) => {
  const digest = LIVE.scenes[name];
  if (digest && digest === shown.digest && name === shown.name && model) {
    review.shownSha256 = DATA.manifest.design.sha256;  // the same bytes: the view stays as it is
    return;
  }
  if (digest && !SCENES[name]) {
    if (!glbs.has(digest)) {
      const r = await fetch(`/scene/${digest}`, { cache: 'no-store' });
      if (!r.ok) { $('status').textContent = `scene ${name}: ${r.status}`; return; }
      glbs.set(digest, await r.arrayBuffer());
    }
    SCENES[name] = glbs.get(digest);
  }
  shown = { name, digest };
  showSceneNow(name, keepView);
};

function loadLive(live) {
  DATA = live.data;
  if (live.checks) window.TACTCAD_CHECKS = live.checks;
  LIVE.scenes = live.scenes;
  SCENES = {};  // fetched when shown
  const current = new Set(Object.values(live.scenes));
  for (const digest of glbs.keys()) if (!current.has(digest)) glbs.delete(digest);
  showHeader();
  showScene($('scene-select').value || DATA.scenes[0], true);
  // the 3D view first, then (after a frame) the drawings and tables
  requestAnimationFrame(() => setTimeout(() => { showSheets(); showTables(); }, 0));
}

async function poll(seq) {
  try {
    const state = await (await fetch('/state', { cache: 'no-store' })).json();
    const refusal = $('refusal');
    review.refusal = state.refusal;
    refusal.textContent = state.refusal ? `The last edit was refused; the page shows the last good export.\n${state.refusal}` : '';
    refusal.classList.toggle('shown', !!state.refusal);
    $('status').textContent = state.status || '';
    if (state.seq !== seq && state.sha256) {
      const live = await (await fetch('/data', { cache: 'no-store' })).json();
      loadLive(live);
      review.updates += 1;
      seq = live.seq;
    }
  } catch (e) {
    $('status').textContent = 'watch: not reachable';
  }
  setTimeout(() => poll(seq), 200);
}

load(document, false);
poll(LIVE.seq);
