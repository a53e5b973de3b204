// Headless browser test of a page written by volmap-view.
//   node test/view.test.mjs <view.html> [--screenshot out.png] [--expect-charts N --expect-corners N] [--label name]
// Opens the page from file:// in Debian's Chromium (playwright-core, no browser download), with no
// network, and checks: no console errors, the colour bar and histogram canvases have drawn pixels,
// moving a slice changes the drawn face count, a click at the centre of the source view picks a tet
// (and the pick shows in the panel), the boundary-map structure (charts = domain faces, corners) when --expect-charts/--expect-corners. Saves a screenshot
// and prints the load timings. Last line: "N passed, N failed".
import { chromium } from 'playwright-core';
import { mkdtempSync, rmSync, statSync, mkdirSync, existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve, dirname } from 'node:path';
import { pathToFileURL } from 'node:url';

const args = process.argv.slice(2);
const opt = (name, fallback) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : fallback; };
const valued = new Set(['--screenshot', '--label', '--expect-charts', '--expect-corners']);
const html = args.find((a, i) => !a.startsWith('--') && !(i > 0 && valued.has(args[i - 1])));
if (!html) { console.error('usage: node test/view.test.mjs <view.html> [--screenshot out.png] [--expect-charts N --expect-corners N]'); process.exit(2); }
const screenshot = opt('--screenshot', null);
const label = opt('--label', html);
const expectCharts = opt('--expect-charts', null), expectCorners = opt('--expect-corners', null);
const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
if (!existsSync(executablePath)) { console.log(`skipped: ${executablePath} is absent`); console.log('0 passed, 0 failed, 1 skipped'); process.exit(0); }

let passed = 0, failed = 0;
function check(ok, what, detail = '') {
  if (ok) passed++; else failed++;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${label}: ${what}${detail ? ' — ' + detail : ''}`);
}

const userDataDir = mkdtempSync(join(tmpdir(), 'volmap-view-chromium-'));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath,
  headless: true,
  viewport: { width: 1400, height: 820 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
         '--disable-sync', '--disable-quic', '--no-first-run', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
const errors = [];
const requests = [];
try {
  const page = context.pages()[0] || await context.newPage();
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) requests.push(r.url()); });

  const url = pathToFileURL(resolve(html)).href;
  const t0 = Date.now();
  await page.goto(url, { waitUntil: 'load', timeout: 120000 });
  await page.waitForFunction(() => window.volmapView && (window.volmapView.ready || window.volmapView.errors.length), null, { timeout: 120000 });
  const wallMs = Date.now() - t0;
  const timings = await page.evaluate(() => window.volmapView.timings);
  const nav = await page.evaluate(() => {
    const n = performance.getEntriesByType('navigation')[0];
    return n ? { responseEnd: n.responseEnd, domInteractive: n.domInteractive } : {};
  });
  const bytes = statSync(html).size;
  console.log(`${label}: ${(bytes / 1e6).toFixed(2)} MB, first render at ${timings.firstRenderMs?.toFixed(0)} ms after navigation ` +
              `(decode ${timings.decodeMs?.toFixed(0)} ms, topology ${timings.topologyMs?.toFixed(0)} ms, charts ${timings.chartsMs?.toFixed(0)} ms, ` +
              `setup ${timings.setupMs?.toFixed(0)} ms; file read by ${nav.responseEnd?.toFixed(0)} ms, DOM parsed by ${nav.domInteractive?.toFixed(0)} ms); ` +
              `goto→ready ${wallMs} ms wall`);
  const apiErrors = await page.evaluate(() => window.volmapView.errors);
  check(apiErrors.length === 0, 'viewer started without errors', apiErrors.join(' | '));

  // Colour bar and histogram drew something (count opaque, non-background pixels).
  const inked = (id) => page.evaluate((id) => {
    const c = document.getElementById(id);
    if (!c || !c.width) return 0;
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i + 3] > 0) n++;
    return n;
  }, id);
  const barInk = await inked('vm-colorbar'), histInk = await inked('vm-histogram');
  check(barInk > 500, 'colour bar rendered', `${barInk} px`);
  check(histInk > 200, 'histogram rendered', `${histInk} px`);
  const hist = await page.evaluate(() => window.volmapView.histogram);
  check(hist && hist.total > 0 && hist.bins.some((b) => b > 0), 'histogram has counts', hist ? `total ${hist.total}` : 'none');
  const weighted = await page.evaluate(() => window.volmapView.setWeighted(true));
  check(weighted.weighted && weighted.total > 0, 'volume-weighted histogram', `total weight ${weighted.total}`);
  await page.evaluate(() => window.volmapView.setWeighted(false));

  // Drawn faces: boundary only at load; a slice adds cut faces and changes the count.
  const c0 = await page.evaluate(() => ({ ...window.volmapView.counts }));
  const meta0 = await page.evaluate(() => window.volmapView.meta);
  check(c0.drawnFaces === c0.boundaryFaces && c0.cutFaces === 0, 'only boundary faces drawn at load', JSON.stringify(c0));
  if (meta0.num_boundary_faces) {
    check(c0.boundaryFaces === meta0.num_boundary_faces, 'viewer face matching (hashing) finds the C++ boundary faces (sorting)',
          `${c0.boundaryFaces} vs ${meta0.num_boundary_faces}`);
  }
  check(c0.drawnFaces < 2 * c0.tets, 'drawn faces far fewer than all tet faces', `${c0.drawnFaces} of ${4 * c0.tets}`);
  const sliced = await page.evaluate(() => {
    const t = performance.now();
    window.volmapView.setSlice('x', 0.5);
    return { ...window.volmapView.counts, ms: performance.now() - t };
  });
  console.log(`${label}: slice update (visibility + cut faces + buffers) ${sliced.ms.toFixed(1)} ms`);
  check(sliced.drawnFaces !== c0.drawnFaces && sliced.cutFaces > 0 && sliced.visibleTets < c0.tets,
        'slice changes the drawn face count', `${c0.drawnFaces} → ${sliced.drawnFaces} (${sliced.cutFaces} cut, ${sliced.visibleTets} tets visible)`);
  // Through the UI as well: drag the Z slider's value via input events.
  const zCount = await page.evaluate(async () => {
    const s = document.getElementById('vm-slice-z'); s.value = '0.3'; s.dispatchEvent(new Event('input'));
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));  // updates are per frame
    return window.volmapView.counts.drawnFaces;
  });
  check(zCount !== sliced.drawnFaces, 'Z slider (UI event) changes the drawn face count', `${sliced.drawnFaces} → ${zCount}`);
  await page.evaluate(() => { window.volmapView.setSlice('z', 0.3, false, false); });
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

  // Picking: a real mouse click at the centre of the source view.
  const [cx, cy] = await page.evaluate(() => window.volmapView.viewCenter(0));
  await page.mouse.click(cx, cy);
  const picked = await page.evaluate(() => window.volmapView.picked);
  check(picked && Number.isInteger(picked.tet) && picked.tet >= 0, 'click at the view centre picks a tet',
        picked ? `tet ${picked.tet}, σ=${(picked.sigma || []).map((s) => s.toPrecision(4)).join(',')}` : 'nothing picked');
  const panel = await page.evaluate(() => document.getElementById('vm-pick').textContent);
  check(picked && panel.includes(String(picked.tet)), 'picked tet shown in the panel');
  const meta = await page.evaluate(() => window.volmapView.meta);
  if (meta.mode === 'volume-map') {
    check(picked && picked.highlightedIn.length === 2, 'picked tet highlighted in both views', picked ? picked.highlightedIn.join(',') : '');
  }
  if (meta.mode === 'volume-map') {
    check(picked && Array.isArray(picked.sigma) && picked.sigma.length === 3 && picked.volumeOut !== undefined,
          'pick reports J singular values and volumes');
  }
  if (meta.mode !== 'mesh') {
    const [tx, ty] = await page.evaluate(() => window.volmapView.viewCenter(1));
    const p2 = await page.evaluate(([x, y]) => window.volmapView.pick(x, y), [tx, ty]);
    check(p2 && p2.tet >= 0, 'pick in the target view', p2 ? `tet ${p2.tet}` : 'nothing');
    check(p2 && p2.highlightedIn.length === 2, 'target-view pick highlighted in both views', p2 ? p2.highlightedIn.join(',') : '');
    if (picked) await page.evaluate((t) => window.volmapView.pickTet(t), picked.tet);
  }
  await page.evaluate(() => window.volmapView.setSlice('x', 0.5, false, false));  // no slice: all tets
  const invalid = await page.evaluate(() => window.volmapView.setOnlyInvalid(true));
  const counts = await page.evaluate(() => ({ ...window.volmapView.counts }));
  const s = meta.summary;
  check(counts.visibleTets === s.num_inverted + s.num_degenerate && (counts.visibleTets === 0) === (invalid === 0),
        'inverted-only filter shows exactly the tets flagged by C++',
        `${counts.visibleTets} visible, C++ says ${s.num_inverted} inverted + ${s.num_degenerate} degenerate, ${invalid} faces`);
  await page.evaluate(() => window.volmapView.setOnlyInvalid(false));
  // Energy threshold filter: only tets at or beyond the threshold stay (flagged tets always stay).
  const thr = await page.evaluate(() => {
    const api = window.volmapView, f = api.meta.fields.find((x) => x.key === api.histogram.field);
    const lo = +document.getElementById('vm-lo').value, hi = +document.getElementById('vm-hi').value;
    const value = (lo + hi) / 2;
    const n = api.setThreshold(value, true);
    const sample = api.visibleSample(5000);
    const worseLow = f && f.worse === 'low';
    const wrong = sample.filter(([, v, fl]) => !(fl & 3) && (worseLow ? v > value : v < value)).length;
    api.setThreshold(value, false);
    return { n, wrong, value, all: api.counts.visibleTets };
  });
  check(thr.n < thr.all && thr.wrong === 0, 'threshold filter keeps only tets beyond the threshold',
        `${thr.n} of ${thr.all} tets at threshold ${thr.value.toPrecision(4)}, ${thr.wrong} wrong`);
  if (expectCharts !== null) {
    check(counts.charts === +expectCharts && counts.corners === +expectCorners && counts.arcs > 0,
          `boundary map: ${expectCharts} charts (domain faces) and ${expectCorners} corners inferred`,
          `${counts.charts} charts, ${counts.corners} corners, ${counts.arcs} arc edges`);
  }
  check(requests.length === 0, 'no network requests', requests.slice(0, 3).join(' '));
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  if (screenshot) {
    mkdirSync(dirname(resolve(screenshot)), { recursive: true });
    await page.screenshot({ path: screenshot });
    console.log(`${label}: screenshot ${resolve(screenshot)}`);
  }
  check(errors.length === 0, 'no console errors', errors.slice(0, 5).join(' | '));
} catch (e) {
  check(false, 'test ran to the end', String(e && e.stack || e));
} finally {
  await context.close();
  rmSync(userDataDir, { recursive: true, force: true });
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
