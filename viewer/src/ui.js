// The page skeleton (side panel + view area) and its style; built by the bundle so the HTML that
// volmap-view writes only carries data.

const CSS = `
html,body{margin:0;height:100%;font:13px/1.35 system-ui,sans-serif;color:#222;background:#f4f4f6}
#vm-root{display:flex;height:100%}
#vm-panel{width:330px;min-width:330px;overflow-y:auto;padding:8px 10px;box-sizing:border-box;background:#fff;border-right:1px solid #ccc}
#vm-panel h1{font-size:14px;margin:2px 0 6px;word-break:break-all}
#vm-panel h2{font-size:12px;margin:10px 0 4px;text-transform:uppercase;letter-spacing:.04em;color:#555}
#vm-panel table{border-collapse:collapse;width:100%;font-size:12px}
#vm-panel td,#vm-panel th{padding:1px 4px;text-align:right;border-bottom:1px solid #eee}
#vm-panel td:first-child,#vm-panel th:first-child{text-align:left}
#vm-panel canvas{width:100%;display:block}
#vm-panel label{display:inline-flex;align-items:center;gap:3px;margin-right:8px}
#vm-panel input[type=range]{flex:1;min-width:90px}
#vm-panel .row{display:flex;align-items:center;gap:4px;margin:2px 0}
#vm-panel .row input[type=number]{width:70px}
#vm-panel .muted{color:#777;font-size:11px}
#vm-views{flex:1;position:relative;overflow:hidden}
#vm-canvas{position:absolute;inset:0;width:100%;height:100%;display:block}
.vm-label{position:absolute;top:6px;padding:1px 6px;background:rgba(255,255,255,.8);border-radius:3px;font-weight:600;pointer-events:none}
#vm-error{position:absolute;left:10px;bottom:10px;right:10px;color:#a00;background:#fff;white-space:pre-wrap;display:none}
`;

export function buildPage(meta, fieldOptions, hasCharts) {
  const style = document.createElement('style');
  style.textContent = CSS;
  document.head.appendChild(style);
  const root = document.createElement('div');
  root.id = 'vm-root';
  const axes = ['x', 'y', 'z'].map((a) => `
    <div class="row"><label><input type="checkbox" id="vm-slice-${a}-on">${a.toUpperCase()}</label>
      <input type="range" id="vm-slice-${a}" min="0" max="1" step="0.001" value="0.5">
      <label><input type="checkbox" id="vm-slice-${a}-flip">flip</label></div>`).join('');
  root.innerHTML = `
  <div id="vm-panel">
    <h1 id="vm-title"></h1>
    <div class="muted" id="vm-subtitle"></div>
    <h2>Colour</h2>
    <div class="row"><select id="vm-field">${fieldOptions}</select>
      ${hasCharts ? '<label><input type="checkbox" id="vm-charts">charts on boundary</label>' : ''}</div>
    <canvas id="vm-colorbar" style="height:46px"></canvas>
    <div class="row">range <input type="number" id="vm-lo" step="any"> – <input type="number" id="vm-hi" step="any">
      <button id="vm-range-reset" title="default range">reset</button>
      <label><input type="checkbox" id="vm-log">log</label></div>
    <h2>Histogram</h2>
    <canvas id="vm-histogram" style="height:130px"></canvas>
    <div class="row"><label><input type="checkbox" id="vm-weighted">volume-weighted</label>
      <span class="muted" id="vm-hist-note"></span></div>
    <h2>Slice (tet centroids)</h2>
    ${axes}
    <div class="row">in <label><input type="radio" name="vm-space" value="source" checked>source</label>
      <label id="vm-space-target-label"><input type="radio" name="vm-space" value="target">target</label></div>
    <h2>Filter</h2>
    <div class="row"><label><input type="checkbox" id="vm-thr-on">value</label>
      <span id="vm-thr-dir">≥</span><input type="range" id="vm-thr" min="0" max="1" step="0.001" value="0.5">
      <span id="vm-thr-val" class="muted"></span></div>
    <div class="row"><label><input type="checkbox" id="vm-invalid">only inverted / degenerate tets</label></div>
    <div class="row"><label><input type="checkbox" id="vm-edges" checked>edges</label>
      <label><input type="checkbox" id="vm-context" checked>boundary ghost</label>
      ${hasCharts ? '<label><input type="checkbox" id="vm-marks" checked>arcs/corners</label>' : ''}</div>
    <div class="muted" id="vm-counts"></div>
    <h2>Picked tet</h2>
    <div id="vm-pick" class="muted">click a tet</div>
    <h2>Global figures</h2>
    <div id="vm-summary"></div>
  </div>
  <div id="vm-views"><canvas id="vm-canvas"></canvas><div id="vm-error"></div></div>`;
  document.body.appendChild(root);
  return root;
}

export function showError(message) {
  const el = document.getElementById('vm-error');
  if (el) { el.style.display = 'block'; el.textContent = message; } else {
    const pre = document.createElement('pre');
    pre.style.color = '#a00';
    pre.textContent = message;
    document.body.appendChild(pre);
  }
}
