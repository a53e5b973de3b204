// Histogram and colour bar, drawn on 2D canvases (no chart library).
import { viridis, cssColor, COLOR_INVERTED, COLOR_DEGENERATE } from './colormap.js';

function fmt(v) {
  if (!Number.isFinite(v)) return String(v);
  const a = Math.abs(v);
  if (a !== 0 && (a < 1e-3 || a >= 1e5)) return v.toExponential(2);
  return Number(v.toPrecision(4)).toString();
}
export { fmt };

function fitCanvas(canvas) {
  const dpr = window.devicePixelRatio || 1;
  const w = canvas.clientWidth || 280, h = canvas.clientHeight || 120;
  if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
    canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  return { ctx, w, h };
}

// Colour bar: gradient over [lo, hi] plus swatches for the exact inverted / degenerate classes.
export function drawColorBar(canvas, lo, hi, label, showInvalid) {
  const { ctx, w, h } = fitCanvas(canvas);
  ctx.clearRect(0, 0, w, h);
  const barH = 14, x0 = 4, x1 = w - 4, rgb = [0, 0, 0];
  for (let x = x0; x < x1; x++) {
    viridis((x - x0) / (x1 - x0 - 1), rgb, 0);
    ctx.fillStyle = cssColor(rgb);
    ctx.fillRect(x, 2, 1, barH);
  }
  ctx.strokeStyle = '#555'; ctx.strokeRect(x0 + 0.5, 2.5, x1 - x0 - 1, barH);
  ctx.fillStyle = '#222'; ctx.font = '11px sans-serif';
  ctx.textBaseline = 'top';
  ctx.textAlign = 'left'; ctx.fillText(fmt(lo), x0, barH + 5);
  ctx.textAlign = 'right'; ctx.fillText(`≥ ${fmt(hi)}`, x1, barH + 5);
  ctx.textAlign = 'center'; ctx.fillText(label, (x0 + x1) / 2, barH + 5);
  if (showInvalid) {
    const y = barH + 22;
    ctx.textAlign = 'left';
    ctx.fillStyle = cssColor(COLOR_INVERTED); ctx.fillRect(x0, y, 12, 10);
    ctx.fillStyle = '#222'; ctx.fillText('inverted', x0 + 16, y - 1);
    ctx.fillStyle = cssColor(COLOR_DEGENERATE); ctx.fillRect(x0 + 90, y, 12, 10);
    ctx.fillStyle = '#222'; ctx.fillText('degenerate', x0 + 106, y - 1);
  }
}

// Histogram of `values` over [lo, hi] (values above hi land in the last bin, below lo in the
// first), optionally weighted; only tets with include[t] != 0. Returns the bins for inspection.
// scaleOf(v) maps a value to [0,1] on the colour scale (linear or log); bins are equal on that scale.
export function computeHistogram(values, include, weights, numBins, scaleOf) {
  const bins = new Float64Array(numBins);
  let total = 0, overflow = 0;
  for (let t = 0; t < values.length; t++) {
    if (!include[t]) continue;
    let v = values[t];
    if (Number.isNaN(v)) continue;
    const w = weights ? Math.abs(weights[t]) : 1;
    const x = scaleOf(v);
    let b = Math.floor(x * numBins);
    if (b < 0) b = 0;
    if (b >= numBins) { b = numBins - 1; if (x > 1) overflow += w; }
    bins[b] += w; total += w;
  }
  return { bins, total, overflow };
}

export function drawHistogram(canvas, hist, lo, hi, weighted, log) {
  const { ctx, w, h } = fitCanvas(canvas);
  ctx.clearRect(0, 0, w, h);
  const padB = 16, padT = 14, x0 = 4, x1 = w - 4;
  const n = hist.bins.length;
  let max = 0;
  for (const b of hist.bins) max = Math.max(max, b);
  const rgb = [0, 0, 0];
  const bw = (x1 - x0) / n;
  for (let i = 0; i < n; i++) {
    const frac = max > 0 ? hist.bins[i] / max : 0;
    const bh = frac * (h - padB - padT);
    viridis((i + 0.5) / n, rgb, 0);
    ctx.fillStyle = cssColor(rgb);
    ctx.fillRect(x0 + i * bw, h - padB - bh, Math.max(1, bw - 1), bh);
  }
  ctx.strokeStyle = '#555';
  ctx.beginPath(); ctx.moveTo(x0, h - padB + 0.5); ctx.lineTo(x1, h - padB + 0.5); ctx.stroke();
  ctx.fillStyle = '#222'; ctx.font = '11px sans-serif'; ctx.textBaseline = 'top';
  ctx.textAlign = 'left'; ctx.fillText(fmt(lo), x0, h - padB + 3);
  ctx.textAlign = 'right'; ctx.fillText(`≥ ${fmt(hi)}`, x1, h - padB + 3);
  if (log) { ctx.textAlign = 'center'; ctx.fillText('log scale', (x0 + x1) / 2, h - padB + 3); }
  ctx.textAlign = 'left'; ctx.textBaseline = 'top';
  const share = hist.total > 0 ? (100 * max / hist.total).toFixed(1) : '0';
  ctx.fillText(`${weighted ? 'volume share' : 'tets'}: peak bin ${share}%` +
               (hist.overflow > 0 ? `, > max ${(100 * hist.overflow / hist.total).toFixed(1)}%` : ''), x0, 1);
}
