// volmap-view browser side: two linked three.js views (source, target) of a tet mesh / volume map.
// Only boundary faces and cut faces (faces of visible tets whose neighbour is hidden by a slice or a
// filter) are drawn, recomputed on typed arrays (topology.js), so 100k-tet maps stay interactive.
// Validity (inverted / degenerate) comes from exact C++ flags; the browser never decides it.
// The test hook is window.volmapView (counts, timings, pick(), setSlice(), ...).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { loadEmbeddedData, FLAG_INVERTED, FLAG_DEGENERATE, FLAG_SOURCE_BAD } from './data.js';
import { faceAdjacency, boundaryFaceList, visibleFaces, LOCAL_FACES } from './topology.js';
import { inferCharts } from './charts.js';
import { viridis, chartColor, COLOR_INVERTED, COLOR_DEGENERATE, COLOR_NEUTRAL } from './colormap.js';
import { drawColorBar, drawHistogram, computeHistogram, fmt } from './plots.js';
import { buildPage, showError } from './ui.js';

const api = (window.volmapView = { ready: false, errors: [], counts: {}, timings: {} });
window.addEventListener('error', (e) => api.errors.push(String(e.message)));

// ---------------------------------------------------------------------------------------------
// Geometry helpers

// Bounding box of the finite points of xyz (points with NaN, e.g. unmapped interior vertices of a
// boundary map, are skipped). Returns {min, max, center, radius}.
function boundingBox(xyz) {
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < xyz.length; i += 3) {
    const x = xyz[i], y = xyz[i + 1], z = xyz[i + 2];
    if (!(Number.isFinite(x) && Number.isFinite(y) && Number.isFinite(z))) continue;
    if (x < min[0]) min[0] = x; if (x > max[0]) max[0] = x;
    if (y < min[1]) min[1] = y; if (y > max[1]) max[1] = y;
    if (z < min[2]) min[2] = z; if (z > max[2]) max[2] = z;
  }
  if (!(min[0] <= max[0])) { min.fill(0); max.fill(1); }
  const center = [0, 1, 2].map((a) => (min[a] + max[a]) / 2);
  const dx = max[0] - min[0], dy = max[1] - min[1], dz = max[2] - min[2];
  const radius = Math.max(1e-30, Math.sqrt(dx * dx + dy * dy + dz * dz) / 2);
  return { min, max, center, radius };
}

// Positions centred and scaled into the unit sphere, so both views share one camera.
function normalised(xyz, box) {
  const out = new Float32Array(xyz.length);
  const s = 1 / box.radius;
  for (let i = 0; i < xyz.length; i += 3) {
    out[i] = (xyz[i] - box.center[0]) * s;
    out[i + 1] = (xyz[i + 1] - box.center[1]) * s;
    out[i + 2] = (xyz[i + 2] - box.center[2]) * s;
  }
  return out;
}

// Tet centroids as fractions of the bounding box along each axis (what the slice sliders move).
function centroidFractions(xyz, tets, numTets, box) {
  const out = new Float32Array(3 * numTets);
  for (let a = 0; a < 3; a++) {
    const lo = box.min[a], span = box.max[a] - box.min[a] || 1;
    for (let t = 0; t < numTets; t++) {
      const c = (xyz[3 * tets[4 * t] + a] + xyz[3 * tets[4 * t + 1] + a] + xyz[3 * tets[4 * t + 2] + a] +
                 xyz[3 * tets[4 * t + 3] + a]) / 4;
      out[3 * t + a] = (c - lo) / span;
    }
  }
  return out;
}

// A triangle soup whose GPU buffers grow on demand; draws `count` faces.
class FaceLayer {
  constructor(scene, material, withEdges) {
    this.scene = scene;
    this.material = material;
    this.edgeMaterial = withEdges ? new THREE.LineBasicMaterial({ color: 0x000000, transparent: true, opacity: 0.22 }) : null;
    this.capacity = 0;
    this.count = 0;
    this.mesh = null;
    this.edges = null;
  }
  ensure(capacity) {
    if (capacity <= this.capacity) return;
    const cap = Math.max(1024, Math.ceil(capacity * 1.25));
    if (this.mesh) { this.scene.remove(this.mesh); this.mesh.geometry.dispose(); }
    if (this.edges) { this.scene.remove(this.edges); this.edges.geometry.dispose(); }
    const g = new THREE.BufferGeometry();
    this.pos = new Float32Array(9 * cap);
    this.col = new Uint8Array(9 * cap);
    g.setAttribute('position', new THREE.BufferAttribute(this.pos, 3).setUsage(THREE.DynamicDrawUsage));
    g.setAttribute('color', new THREE.BufferAttribute(this.col, 3, true).setUsage(THREE.DynamicDrawUsage));
    g.boundingSphere = new THREE.Sphere(new THREE.Vector3(), 2);
    this.mesh = new THREE.Mesh(g, this.material);
    this.scene.add(this.mesh);
    if (this.edgeMaterial) {
      const e = new THREE.BufferGeometry();
      this.epos = new Float32Array(18 * cap);
      e.setAttribute('position', new THREE.BufferAttribute(this.epos, 3).setUsage(THREE.DynamicDrawUsage));
      e.boundingSphere = new THREE.Sphere(new THREE.Vector3(), 2);
      this.edges = new THREE.LineSegments(e, this.edgeMaterial);
      this.scene.add(this.edges);
    }
    this.capacity = cap;
  }
  // faces: face ids 4t+i; xyz: normalised positions; colorOf(face, k) -> [r,g,b] bytes.
  setFaces(faces, count, tets, xyz, faceColors) {
    this.ensure(count);
    const pos = this.pos, col = this.col, epos = this.epos;
    for (let k = 0; k < count; k++) {
      const f = faces[k], t = f >> 2, i = f & 3;
      for (let j = 0; j < 3; j++) {
        const v = tets[4 * t + LOCAL_FACES[3 * i + j]];
        pos[9 * k + 3 * j] = xyz[3 * v];
        pos[9 * k + 3 * j + 1] = xyz[3 * v + 1];
        pos[9 * k + 3 * j + 2] = xyz[3 * v + 2];
      }
      if (epos) {
        const b = 18 * k, p = 9 * k;
        epos.set(pos.subarray(p, p + 6), b);          // edge 0-1
        epos.set(pos.subarray(p + 3, p + 9), b + 6);  // edge 1-2
        epos.set(pos.subarray(p + 6, p + 9), b + 12); // edge 2-0
        epos.set(pos.subarray(p, p + 3), b + 15);
      }
    }
    this.count = count;
    this.recolor(faces, count, faceColors);
    const g = this.mesh.geometry;
    g.attributes.position.clearUpdateRanges();
    g.attributes.position.addUpdateRange(0, 9 * count);
    g.attributes.position.needsUpdate = true;
    g.setDrawRange(0, 3 * count);
    if (this.edges) {
      const e = this.edges.geometry;
      e.attributes.position.clearUpdateRanges();
      e.attributes.position.addUpdateRange(0, 18 * count);
      e.attributes.position.needsUpdate = true;
      e.setDrawRange(0, 6 * count);
    }
  }
  recolor(faces, count, faceColors) {
    if (!this.mesh) return;  // nothing drawn yet
    const col = this.col;
    for (let k = 0; k < count; k++) {
      const f = faces[k];
      const r = faceColors[3 * f], gg = faceColors[3 * f + 1], b = faceColors[3 * f + 2];
      for (let j = 0; j < 3; j++) { col[9 * k + 3 * j] = r; col[9 * k + 3 * j + 1] = gg; col[9 * k + 3 * j + 2] = b; }
    }
    const a = this.mesh.geometry.attributes.color;
    a.clearUpdateRanges();
    a.addUpdateRange(0, 9 * count);
    a.needsUpdate = true;
  }
}

// ---------------------------------------------------------------------------------------------

function main() {
  const tStart = performance.now();
  const { meta, arrays } = loadEmbeddedData();
  const tDecoded = performance.now();
  const nt = meta.num_tets, nv = meta.num_vertices;
  const tets = arrays.tets;
  const flags = arrays.flags;
  const neighbour = faceAdjacency(tets, nt);
  const boundary = boundaryFaceList(neighbour);
  const tTopology = performance.now();

  const hasVolumeTarget = meta.mode === 'volume-map';
  const hasSurfaceTarget = meta.mode === 'boundary-map';
  const targetXyz = arrays.target_xyz || null;

  const srcBox = boundingBox(arrays.source_xyz);
  const views = [{ name: 'source', label: meta.source_name || 'source', box: srcBox, xyz: normalised(arrays.source_xyz, srcBox) }];
  if (targetXyz) {
    const box = boundingBox(targetXyz);
    views.push({ name: 'target', label: meta.target_name || 'target', box, xyz: normalised(targetXyz, box) });
  }
  const centroids = { source: centroidFractions(arrays.source_xyz, tets, nt, srcBox) };
  if (hasVolumeTarget) centroids.target = centroidFractions(targetXyz, tets, nt, views[1].box);

  // Charts from the mapped boundary (domain faces), when there is a target.
  let charts = null;
  const faceChart = new Int32Array(4 * nt).fill(-1);
  if (targetXyz) {
    charts = inferCharts(tets, targetXyz, boundary, views[1].box.radius);
    if (charts.curved || charts.numCharts === 0) charts = charts.curved ? charts : null;
    if (charts) for (let k = 0; k < boundary.length; k++) faceChart[boundary[k]] = charts.chart[k];
  }
  const hasCharts = !!(charts && !charts.curved && charts.numCharts > 0);
  const tCharts = performance.now();

  // Fields (per-tet scalars computed in C++).
  const fields = meta.fields.filter((f) => arrays['field_' + f.key]);
  const fieldOptions = fields.map((f) => `<option value="${f.key}">${f.label}</option>`).join('');
  buildPage(meta, fieldOptions || '<option value="">(no per-tet values)</option>', hasCharts);
  const $ = (id) => document.getElementById(id);
  $('vm-title').textContent = meta.title || 'volmap-view';
  $('vm-subtitle').textContent = `${meta.mode}: ${nv.toLocaleString()} vertices, ${nt.toLocaleString()} tets, ${boundary.length.toLocaleString()} boundary faces` +
    (hasCharts ? `, ${charts.numCharts} charts, ${charts.corners.length} corners` : charts && charts.curved ? ', curved domain (no charts)' : '');
  if (!hasVolumeTarget) $('vm-space-target-label').style.display = 'none';

  const state = {
    field: fields.find((f) => f.key === meta.initial_field) || fields[0] || null,
    lo: 0, hi: 1,
    weighted: false,
    log: false,
    slices: [0, 1, 2].map(() => ({ on: false, value: 0.5, flip: false })),
    space: 'source',
    thrOn: false, thr: 0,
    onlyInvalid: false,
    chartsOnBoundary: hasSurfaceTarget,
    edges: nt <= 400000,
    context: true,
    marks: true,
    picked: -1,
  };
  if (hasCharts) $('vm-charts').checked = state.chartsOnBoundary;
  $('vm-edges').checked = state.edges;
  if (state.field) $('vm-field').value = state.field.key;

  // Display value of a tet for a field: NaN/inf -> upper, clamped to [lower, upper] (VOLMAP rule 2).
  const displayValues = new Float32Array(nt);
  const validForField = new Uint8Array(nt);
  function prepareField() {
    const f = state.field;
    if (!f) { validForField.fill(0); return; }
    const raw = arrays['field_' + f.key];
    for (let t = 0; t < nt; t++) {
      let v = raw[t];
      if (!Number.isFinite(v)) v = f.upper;
      displayValues[t] = Math.min(f.upper, Math.max(f.lower, v));
      validForField[t] = f.valid_only && (flags[t] & (FLAG_INVERTED | FLAG_DEGENERATE)) ? 0 : 1;
    }
  }
  function defaultRange() {
    const f = state.field;
    if (!f) return [0, 1];
    if (f.worse === 'low') return [f.lower, f.upper];
    const vals = [];
    for (let t = 0; t < nt; t++) if (validForField[t]) vals.push(displayValues[t]);
    if (!vals.length) return [f.lower, f.upper];
    const sorted = Float32Array.from(vals).sort();
    let hi = sorted[Math.min(sorted.length - 1, Math.floor(0.98 * sorted.length))];
    if (!(hi > f.lower)) hi = Math.min(f.upper, f.lower + 1);
    return [f.lower, Number(hi.toPrecision(3))];
  }

  // Per-face colours (tet colour, or chart colour on boundary faces).
  const faceColors = new Uint8Array(12 * nt);
  const tetColor = new Uint8Array(3 * nt);
  // Position of a value on the colour scale, in [0,1] (log scale: log1p of the distance to lo).
  function scaleOf(v) {
    const span = state.hi > state.lo ? state.hi - state.lo : 1;
    if (state.log) return Math.log1p(Math.max(0, v - state.lo)) / Math.log1p(span);
    return (v - state.lo) / span;
  }
  function computeColors() {
    const rgb = [0, 0, 0];
    for (let t = 0; t < nt; t++) {
      let c;
      if (flags[t] & FLAG_INVERTED) c = COLOR_INVERTED;
      else if (flags[t] & FLAG_DEGENERATE) c = COLOR_DEGENERATE;
      else if (state.field) {
        viridis(scaleOf(displayValues[t]), rgb, 0);
        c = rgb;
      } else c = COLOR_NEUTRAL;
      tetColor[3 * t] = c[0]; tetColor[3 * t + 1] = c[1]; tetColor[3 * t + 2] = c[2];
    }
    for (let f = 0; f < 4 * nt; f++) {
      const t = f >> 2;
      let r = tetColor[3 * t], g = tetColor[3 * t + 1], b = tetColor[3 * t + 2];
      if (state.chartsOnBoundary && neighbour[f] < 0 && faceChart[f] >= -1 && charts && !charts.curved) {
        const cc = chartColor(faceChart[f]);
        r = cc[0]; g = cc[1]; b = cc[2];
      }
      faceColors[3 * f] = r; faceColors[3 * f + 1] = g; faceColors[3 * f + 2] = b;
    }
  }

  // ---- three.js scene per view ----
  const canvas = $('vm-canvas');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.outputColorSpace = THREE.LinearSRGBColorSpace;  // vertex colours are already sRGB bytes
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setScissorTest(true);
  const surfaceMaterial = new THREE.MeshLambertMaterial({
    vertexColors: true, side: THREE.DoubleSide, flatShading: true,
    polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
  });
  const ghostMaterial = new THREE.MeshBasicMaterial({
    color: 0x8890a0, transparent: true, opacity: 0.10, depthWrite: false, side: THREE.DoubleSide,
    polygonOffset: true, polygonOffsetFactor: 4, polygonOffsetUnits: 4,
  });
  const highlightMaterial = new THREE.MeshBasicMaterial({ color: 0xffe000, transparent: true, opacity: 0.75, depthTest: false, side: THREE.DoubleSide });
  const highlightEdgeMaterial = new THREE.LineBasicMaterial({ color: 0xd00000, depthTest: false });

  for (const view of views) {
    view.scene = new THREE.Scene();
    view.scene.background = new THREE.Color(0xf4f4f6);
    view.camera = new THREE.PerspectiveCamera(35, 1, 0.01, 100);
    view.camera.position.set(1.45, 1.1, 3.35);  // oblique: a cube domain shows three faces
    view.camera.lookAt(0, 0, 0);
    view.scene.add(view.camera);
    // three.js lights are physical (Lambert = albedo/π): scale by π so a face lit head-on shows
    // about its own colour (vertex colours are sRGB bytes, output untouched).
    view.scene.add(new THREE.AmbientLight(0xffffff, 0.55 * Math.PI));
    const light = new THREE.DirectionalLight(0xffffff, 0.5 * Math.PI);
    light.position.set(0.4, 0.6, 1);
    view.camera.add(light);
    view.volume = view.name === 'source' || hasVolumeTarget;  // draws tet faces (else: surface only)
    view.layer = new FaceLayer(view.scene, surfaceMaterial, true);
    // Boundary ghost: all boundary faces, faint, to keep the shape when slicing / filtering.
    const ghost = new FaceLayer(view.scene, ghostMaterial, false);
    ghost.setFaces(boundary, boundary.length, tets, view.xyz, faceColors);
    ghost.mesh.renderOrder = 2;
    view.ghost = ghost;
    // Highlight of the picked tet.
    const hg = new THREE.BufferGeometry();
    hg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(36), 3));
    view.highlight = new THREE.Mesh(hg, highlightMaterial);
    const he = new THREE.BufferGeometry();
    he.setAttribute('position', new THREE.BufferAttribute(new Float32Array(36), 3));
    view.highlightEdges = new THREE.LineSegments(he, highlightEdgeMaterial);
    view.highlight.renderOrder = view.highlightEdges.renderOrder = 10;
    view.highlight.visible = view.highlightEdges.visible = false;
    view.highlight.frustumCulled = view.highlightEdges.frustumCulled = false;
    view.scene.add(view.highlight, view.highlightEdges);
    // Centroid markers of the exactly flagged tets (degenerate ones are flat: invisible as faces).
    {
      const bad = [];
      for (let t = 0; t < nt; t++) if (flags[t] & (FLAG_INVERTED | FLAG_DEGENERATE)) bad.push(t);
      const mp = new Float32Array(3 * bad.length), mc = new Float32Array(3 * bad.length);
      bad.forEach((t, k) => {
        for (let a = 0; a < 3; a++) {
          let c = 0;
          for (let j = 0; j < 4; j++) c += view.xyz[3 * tets[4 * t + j] + a];
          mp[3 * k + a] = c / 4;
        }
        const col = flags[t] & FLAG_INVERTED ? COLOR_INVERTED : COLOR_DEGENERATE;
        for (let a = 0; a < 3; a++) mc[3 * k + a] = col[a] / 255;
      });
      const mg = new THREE.BufferGeometry();
      mg.setAttribute('position', new THREE.BufferAttribute(mp, 3));
      mg.setAttribute('color', new THREE.BufferAttribute(mc, 3));
      view.badMarkers = new THREE.Points(mg, new THREE.PointsMaterial({ size: 6, sizeAttenuation: false, vertexColors: true, depthTest: false }));
      view.badMarkers.renderOrder = 8;
      view.badMarkers.visible = false;
      view.scene.add(view.badMarkers);
    }
    // Arcs and corners of the boundary map.
    if (hasCharts) {
      const ap = new Float32Array(3 * charts.arcs.length);
      for (let k = 0; k < charts.arcs.length; k++) ap.set(view.xyz.subarray(3 * charts.arcs[k], 3 * charts.arcs[k] + 3), 3 * k);
      const ag = new THREE.BufferGeometry();
      ag.setAttribute('position', new THREE.BufferAttribute(ap, 3));
      view.arcs = new THREE.LineSegments(ag, new THREE.LineBasicMaterial({ color: 0x101010 }));
      const cp = new Float32Array(3 * charts.corners.length);
      for (let k = 0; k < charts.corners.length; k++) cp.set(view.xyz.subarray(3 * charts.corners[k], 3 * charts.corners[k] + 3), 3 * k);
      const cg = new THREE.BufferGeometry();
      cg.setAttribute('position', new THREE.BufferAttribute(cp, 3));
      view.corners = new THREE.Points(cg, new THREE.PointsMaterial({ color: 0x000000, size: 8, sizeAttenuation: false }));
      view.arcs.renderOrder = view.corners.renderOrder = 5;
      view.scene.add(view.arcs, view.corners);
    }
  }

  // One OrbitControls drives the first camera; the others copy it (linked views).
  const controls = new OrbitControls(views[0].camera, canvas);
  controls.enableDamping = false;
  const syncCameras = () => {
    for (let i = 1; i < views.length; i++) {
      views[i].camera.position.copy(views[0].camera.position);
      views[i].camera.quaternion.copy(views[0].camera.quaternion);
      views[i].camera.zoom = views[0].camera.zoom;
      views[i].camera.updateProjectionMatrix();
    }
  };
  controls.addEventListener('change', () => { syncCameras(); requestRender(); });

  function layout() {
    const host = $('vm-views');
    const w = host.clientWidth, h = host.clientHeight;
    renderer.setSize(w, h, false);
    const vw = w / views.length;
    views.forEach((view, i) => {
      view.viewport = { x: Math.round(i * vw), y: 0, w: Math.round((i + 1) * vw) - Math.round(i * vw), h };
      view.camera.aspect = view.viewport.w / Math.max(1, h);
      // Keep the unit sphere in view in both directions: widen the vertical fov of portrait views.
      const half = (35 / 2) * Math.PI / 180;
      view.camera.fov = view.camera.aspect >= 1 ? 35 : (2 * Math.atan(Math.tan(half) / view.camera.aspect)) * 180 / Math.PI;
      view.camera.updateProjectionMatrix();
      if (!view.labelEl) {
        view.labelEl = document.createElement('div');
        view.labelEl.className = 'vm-label';
        view.labelEl.textContent = `${view.name}: ${view.label}`;
        host.appendChild(view.labelEl);
      }
      view.labelEl.style.left = `${view.viewport.x + 8}px`;
    });
    requestRender();
  }

  let renderPending = false;
  let firstFrameDone = false;
  function render() {
    renderPending = false;
    const h = renderer.domElement.clientHeight;
    for (const view of views) {
      const vp = view.viewport;
      renderer.setViewport(vp.x, h - vp.y - vp.h, vp.w, vp.h);
      renderer.setScissor(vp.x, h - vp.y - vp.h, vp.w, vp.h);
      renderer.render(view.scene, view.camera);
    }
    if (!firstFrameDone) {
      firstFrameDone = true;
      api.timings.firstRenderMs = performance.now();  // since navigation start
      api.ready = true;
    }
  }
  function requestRender() {
    if (renderPending) return;
    renderPending = true;
    requestAnimationFrame(render);
  }

  // ---- visibility and drawn faces ----
  const visible = new Uint8Array(nt);
  let faceBuf = null;
  let drawn = { faces: new Int32Array(0), count: 0 };
  function computeVisibility() {
    const cf = centroids[state.space] || centroids.source;
    const thrOn = state.thrOn && state.field;
    const worseLow = state.field && state.field.worse === 'low';
    let n = 0;
    for (let t = 0; t < nt; t++) {
      let vis = 1;
      for (let a = 0; a < 3 && vis; a++) {
        const s = state.slices[a];
        if (!s.on) continue;
        const c = cf[3 * t + a];
        if (s.flip ? c < s.value : c > s.value) vis = 0;
      }
      const bad = flags[t] & (FLAG_INVERTED | FLAG_DEGENERATE);
      if (vis && state.onlyInvalid && !bad) vis = 0;
      if (vis && thrOn && !bad) {
        const v = displayValues[t];
        if (worseLow ? v > state.thr : v < state.thr) vis = 0;
      }
      visible[t] = vis;
      n += vis;
    }
    return n;
  }
  function updateGeometry() {
    const numVisible = computeVisibility();
    drawn = visibleFaces(neighbour, visible, faceBuf);
    faceBuf = drawn.faces;
    for (const view of views) {
      if (view.volume) view.layer.setFaces(drawn.faces, drawn.count, tets, view.xyz, faceColors);
      else view.layer.setFaces(boundary, boundary.length, tets, view.xyz, faceColors);  // mapped surface
      if (view.layer.edges) view.layer.edges.visible = state.edges;
      view.ghost.mesh.visible = state.context;
      view.badMarkers.visible = state.onlyInvalid;
      if (view.arcs) view.arcs.visible = view.corners.visible = state.marks;
    }
    let cut = 0;
    for (let k = 0; k < drawn.count; k++) if (neighbour[drawn.faces[k]] >= 0) cut++;
    api.counts = { drawnFaces: drawn.count, cutFaces: cut, boundaryFaces: boundary.length, visibleTets: numVisible, tets: nt,
                   charts: hasCharts ? charts.numCharts : 0, corners: hasCharts ? charts.corners.length : 0,
                   arcs: hasCharts ? charts.arcs.length / 2 : 0 };
    $('vm-counts').textContent = `drawn: ${drawn.count.toLocaleString()} faces (${cut.toLocaleString()} cut), ` +
      `${numVisible.toLocaleString()} / ${nt.toLocaleString()} tets visible`;
    requestRender();
  }
  // Slider drags fire many input events: recompute at most once per frame.
  let geometryPending = false;
  function scheduleGeometry() {
    if (geometryPending) return;
    geometryPending = true;
    requestAnimationFrame(() => { geometryPending = false; updateGeometry(); });
  }
  function recolorAll() {
    computeColors();
    for (const view of views) {
      if (view.volume) view.layer.recolor(drawn.faces, drawn.count, faceColors);
      else view.layer.recolor(boundary, boundary.length, faceColors);
    }
    requestRender();
  }

  // ---- side panel: colour bar, histogram, figures ----
  function weightsArray() {
    return hasVolumeTarget ? arrays.volume_out : arrays.volume_in;
  }
  function updatePlots() {
    const f = state.field;
    const label = f ? f.label : 'no values';
    drawColorBar($('vm-colorbar'), state.lo, state.hi, label + (state.log ? ' (log)' : ''), true);
    const hist = f ? computeHistogram(displayValues, validForField, state.weighted ? weightsArray() : null, 40, scaleOf)
                   : { bins: new Float64Array(40), total: 0, overflow: 0 };
    drawHistogram($('vm-histogram'), hist, state.lo, state.hi, state.weighted, state.log);
    api.histogram = { bins: Array.from(hist.bins), total: hist.total, weighted: state.weighted, field: f ? f.key : null };
    $('vm-hist-note').textContent = f && f.valid_only ? 'valid tets only' : '';
    const thr = $('vm-thr');
    thr.min = state.lo; thr.max = state.hi; thr.step = (state.hi - state.lo) / 1000 || 0.001;
    $('vm-thr-dir').textContent = f && f.worse === 'low' ? '≤' : '≥';
    $('vm-thr-val').textContent = fmt(state.thr);
  }
  function selectField(key) {
    state.field = fields.find((f) => f.key === key) || null;
    state.log = !!(state.field && state.field.worse === 'high');
    $('vm-log').checked = state.log;
    prepareField();
    [state.lo, state.hi] = defaultRange();
    state.thr = state.field && state.field.worse === 'low' ? state.hi : state.lo;
    $('vm-thr').value = state.thr;
    $('vm-lo').value = state.lo; $('vm-hi').value = state.hi;
    computeColors();
    updatePlots();
    if (state.thrOn) updateGeometry(); else recolorAll();
    if (state.picked >= 0) showPicked(state.picked);
  }

  function summaryTable() {
    const s = meta.summary || {};
    const rows = [];
    const count = (label, v) => rows.push(`<tr><td>${label}</td><td colspan="3">${v}</td></tr>`);
    count('tets', nt.toLocaleString());
    count('vertices', nv.toLocaleString());
    if (s.num_inverted !== undefined) {
      const pct = (100 * s.num_inverted / Math.max(1, nt)).toFixed(3);
      count(hasVolumeTarget ? 'inverted (exact)' : 'negative (exact)', `${s.num_inverted.toLocaleString()} (${pct}%)`);
    }
    if (s.num_degenerate !== undefined) count('degenerate (exact)', s.num_degenerate.toLocaleString());
    if (s.num_source_nonpositive) count('source tets ≤ 0', s.num_source_nonpositive.toLocaleString());
    let html = `<table>${rows.join('')}</table>`;
    if (s.fields && Object.keys(s.fields).length) {
      html += '<table><tr><th>field</th><th>min</th><th>max</th><th title="energies: |volume|-weighted mean over valid tets; quality: plain mean">E / mean</th></tr>';
      for (const f of meta.fields) {
        const g = s.fields[f.key];
        if (!g) continue;
        html += `<tr><td title="${g.weighting || ''}">${f.label}</td><td>${fmt(g.min)}</td><td>${fmt(g.max)}</td><td>${fmt(g.weighted_mean)}</td></tr>`;
      }
      html += '</table><div class="muted">energies: E = mean weighted by |target volume| over valid tets, clamped (VOLMAP metrics rule); quality: plain mean</div>';
    }
    $('vm-summary').innerHTML = html;
  }

  // ---- picking ----
  const raycaster = new THREE.Raycaster();
  function tetVertices(t, xyz, out) {
    for (let j = 0; j < 4; j++) {
      const v = tets[4 * t + j];
      out[3 * j] = xyz[3 * v]; out[3 * j + 1] = xyz[3 * v + 1]; out[3 * j + 2] = xyz[3 * v + 2];
    }
  }
  function showPicked(t) {
    state.picked = t;
    const p = new Float32Array(12);
    for (const view of views) {
      const on = t >= 0;
      view.highlight.visible = view.highlightEdges.visible = on;
      if (!on) continue;
      tetVertices(t, view.xyz, p);
      // Boundary maps place only boundary vertices: draw the faces / edges whose vertices are placed.
      const placed = [0, 1, 2, 3].map((j) => Number.isFinite(p[3 * j]) && Number.isFinite(p[3 * j + 1]) && Number.isFinite(p[3 * j + 2]));
      const tri = view.highlight.geometry.attributes.position.array;
      tri.fill(0);
      let anyFace = false;
      for (let i = 0; i < 4; i++) {
        const ok = [0, 1, 2].every((j) => placed[LOCAL_FACES[3 * i + j]]);
        if (!ok) continue;
        anyFace = true;
        for (let j = 0; j < 3; j++) {
          const l = LOCAL_FACES[3 * i + j];
          tri.set(p.subarray(3 * l, 3 * l + 3), 9 * i + 3 * j);
        }
      }
      view.highlight.geometry.attributes.position.needsUpdate = true;
      const ed = view.highlightEdges.geometry.attributes.position.array;
      ed.fill(0);
      const pairs = [0, 1, 0, 2, 0, 3, 1, 2, 1, 3, 2, 3];
      for (let k = 0; k < 12; k += 2) {
        if (!placed[pairs[k]] || !placed[pairs[k + 1]]) continue;
        ed.set(p.subarray(3 * pairs[k], 3 * pairs[k] + 3), 3 * k);
        ed.set(p.subarray(3 * pairs[k + 1], 3 * pairs[k + 1] + 3), 3 * k + 3);
      }
      view.highlightEdges.geometry.attributes.position.needsUpdate = true;
      view.highlight.visible = view.highlightEdges.visible = anyFace;
    }
    requestRender();
    if (t < 0) { $('vm-pick').textContent = 'click a tet'; api.picked = null; return null; }
    const info = { tet: t, flags: flags[t], inverted: !!(flags[t] & FLAG_INVERTED), degenerate: !!(flags[t] & FLAG_DEGENERATE),
                   highlightedIn: views.filter((v) => v.highlight.visible).map((v) => v.name) };
    const rows = [`<tr><td>tet id</td><td>${t}</td></tr>`,
      `<tr><td>vertices</td><td>${Array.from(tets.subarray(4 * t, 4 * t + 4)).join(' ')}</td></tr>`];
    const srcBad = (flags[t] & FLAG_SOURCE_BAD) !== 0;
    let status;
    if (hasVolumeTarget) {
      status = info.inverted ? 'inverted (orientation flipped)' : info.degenerate ? 'degenerate (zero volume)' :
               srcBad ? 'valid (same orientation as its negative source)' : 'valid (positive)';
    } else {
      status = info.inverted ? 'negative' : info.degenerate ? 'degenerate' : 'positive';
    }
    rows.push(`<tr><td>${hasVolumeTarget ? 'mapped tet' : 'tet'} (exact)</td><td>${status}</td></tr>`);
    if (arrays.volume_in) { info.volumeIn = arrays.volume_in[t]; rows.push(`<tr><td>volume (source)</td><td>${fmt(info.volumeIn)}</td></tr>`); }
    if (arrays.volume_out) { info.volumeOut = arrays.volume_out[t]; rows.push(`<tr><td>volume (target)</td><td>${fmt(info.volumeOut)}</td></tr>`); }
    if (arrays.sigma) {
      info.sigma = Array.from(arrays.sigma.subarray(3 * t, 3 * t + 3));
      rows.push(`<tr><td>σ₁ σ₂ σ₃ of J</td><td>${info.sigma.map(fmt).join(' ')}</td></tr>`);
    }
    info.fields = {};
    for (const f of fields) {
      const v = arrays['field_' + f.key][t];
      info.fields[f.key] = v;
      rows.push(`<tr><td>${f.label}</td><td>${fmt(v)}</td></tr>`);
    }
    $('vm-pick').innerHTML = `<table>${rows.join('')}</table>`;
    api.picked = info;
    return info;
  }
  function pickAt(clientX, clientY) {
    const rect = canvas.getBoundingClientRect();
    const x = clientX - rect.left, y = clientY - rect.top;
    const view = views.find((v) => x >= v.viewport.x && x < v.viewport.x + v.viewport.w);
    if (!view) return showPicked(-1);
    const ndc = new THREE.Vector2(((x - view.viewport.x) / view.viewport.w) * 2 - 1, -((y - view.viewport.y) / view.viewport.h) * 2 + 1);
    raycaster.setFromCamera(ndc, view.camera);
    const hits = raycaster.intersectObject(view.layer.mesh, false);
    if (!hits.length) return showPicked(-1);
    const k = hits[0].faceIndex;
    const faces = view.volume ? drawn.faces : boundary;
    return showPicked(faces[k] >> 2);
  }

  // ---- wiring ----
  let down = null;
  canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
  canvas.addEventListener('pointerup', (e) => {
    if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) < 4) pickAt(e.clientX, e.clientY);
    down = null;
  });
  ['x', 'y', 'z'].forEach((a, i) => {
    const on = $(`vm-slice-${a}-on`), val = $(`vm-slice-${a}`), flip = $(`vm-slice-${a}-flip`);
    on.addEventListener('change', () => { state.slices[i].on = on.checked; updateGeometry(); });
    val.addEventListener('input', () => { state.slices[i].value = +val.value; state.slices[i].on = on.checked = true; scheduleGeometry(); });
    flip.addEventListener('change', () => { state.slices[i].flip = flip.checked; updateGeometry(); });
  });
  document.querySelectorAll('input[name=vm-space]').forEach((r) => r.addEventListener('change', () => { state.space = r.value; updateGeometry(); }));
  $('vm-field').addEventListener('change', () => selectField($('vm-field').value));
  $('vm-log').addEventListener('change', () => { state.log = $('vm-log').checked; updatePlots(); recolorAll(); });
  $('vm-weighted').addEventListener('change', () => { state.weighted = $('vm-weighted').checked; updatePlots(); });
  const rangeChanged = () => {
    const lo = parseFloat($('vm-lo').value), hi = parseFloat($('vm-hi').value);
    if (Number.isFinite(lo) && Number.isFinite(hi) && hi > lo) { state.lo = lo; state.hi = hi; updatePlots(); recolorAll(); }
  };
  $('vm-lo').addEventListener('change', rangeChanged);
  $('vm-hi').addEventListener('change', rangeChanged);
  $('vm-range-reset').addEventListener('click', () => selectField(state.field ? state.field.key : ''));
  $('vm-thr-on').addEventListener('change', () => { state.thrOn = $('vm-thr-on').checked; updateGeometry(); });
  $('vm-thr').addEventListener('input', () => {
    state.thr = +$('vm-thr').value; $('vm-thr-val').textContent = fmt(state.thr);
    state.thrOn = $('vm-thr-on').checked = true; scheduleGeometry();
  });
  $('vm-invalid').addEventListener('change', () => { state.onlyInvalid = $('vm-invalid').checked; updateGeometry(); });
  $('vm-edges').addEventListener('change', () => { state.edges = $('vm-edges').checked; updateGeometry(); });
  $('vm-context').addEventListener('change', () => { state.context = $('vm-context').checked; updateGeometry(); });
  if (hasCharts) {
    $('vm-charts').addEventListener('change', () => { state.chartsOnBoundary = $('vm-charts').checked; recolorAll(); });
    $('vm-marks').addEventListener('change', () => { state.marks = $('vm-marks').checked; updateGeometry(); });
  }
  window.addEventListener('resize', layout);

  // ---- test / scripting hook ----
  Object.assign(api, {
    meta,
    pick: (clientX, clientY) => pickAt(clientX, clientY),
    pickTet: (t) => showPicked(t),
    // Screen coordinates (client) of the centre of view i.
    viewCenter: (i = 0) => {
      const rect = canvas.getBoundingClientRect(), vp = views[i].viewport;
      return [rect.left + vp.x + vp.w / 2, rect.top + vp.y + vp.h / 2];
    },
    setSlice: (axis, value, flip = false, on = true) => {
      const i = typeof axis === 'number' ? axis : 'xyz'.indexOf(axis);
      Object.assign(state.slices[i], { value, flip, on });
      const a = 'xyz'[i];
      $(`vm-slice-${a}`).value = value; $(`vm-slice-${a}-flip`).checked = flip; $(`vm-slice-${a}-on`).checked = on;
      updateGeometry();
      return api.counts.drawnFaces;
    },
    setField: (key) => { $('vm-field').value = key; selectField(key); },
    setThreshold: (value, on = true) => {
      state.thr = value; state.thrOn = on;
      $('vm-thr').value = value; $('vm-thr-on').checked = on; $('vm-thr-val').textContent = fmt(value);
      updateGeometry();
      return api.counts.visibleTets;
    },
    // Tets visible now (for tests): ids of the first `max` visible tets and their display values.
    visibleSample: (max = 1000) => {
      const out = [];
      for (let t = 0; t < nt && out.length < max; t++) if (visible[t]) out.push([t, displayValues[t], flags[t]]);
      return out;
    },
    setOnlyInvalid: (on) => { state.onlyInvalid = $('vm-invalid').checked = on; updateGeometry(); return api.counts.drawnFaces; },
    setWeighted: (on) => { state.weighted = $('vm-weighted').checked = on; updatePlots(); return api.histogram; },
    renderNow: () => render(),
  });

  api.timings.decodeMs = tDecoded - tStart;
  api.timings.topologyMs = tTopology - tDecoded;
  api.timings.chartsMs = tCharts - tTopology;
  layout();
  prepareField();
  selectField(state.field ? state.field.key : '');
  summaryTable();
  updateGeometry();
  api.timings.setupMs = performance.now() - tStart;
}

try {
  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', () => {
    try { main(); } catch (e) { api.errors.push(String(e && e.stack || e)); console.error(e); showError(String(e && e.message || e)); }
  });
  else main();
} catch (e) {
  api.errors.push(String(e && e.stack || e));
  console.error(e);
  showError(String(e && e.message || e));
}
