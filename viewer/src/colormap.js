// Colour maps (sRGB bytes). Viridis sampled at 9 stops (matplotlib's published table), linear in
// between; special colours for tets whose validity the C++ side decided exactly.

const VIRIDIS = [
  [68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141],
  [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37],
];

export const COLOR_INVERTED = [255, 0, 200];
export const COLOR_DEGENERATE = [255, 64, 0];
export const COLOR_NEUTRAL = [190, 190, 196];

export function viridis(t, out, o) {
  if (!(t > 0)) t = 0; else if (t > 1) t = 1;
  const x = t * (VIRIDIS.length - 1);
  const i = Math.min(VIRIDIS.length - 2, Math.floor(x));
  const u = x - i, a = VIRIDIS[i], b = VIRIDIS[i + 1];
  out[o] = a[0] + (b[0] - a[0]) * u;
  out[o + 1] = a[1] + (b[1] - a[1]) * u;
  out[o + 2] = a[2] + (b[2] - a[2]) * u;
}

export function cssColor(rgb) { return `rgb(${rgb[0] | 0},${rgb[1] | 0},${rgb[2] | 0})`; }

// Distinct colours for charts (domain faces); index wraps.
const CHART = [
  [230, 25, 75], [60, 180, 75], [255, 225, 25], [0, 130, 200], [245, 130, 48], [145, 30, 180],
  [70, 240, 240], [240, 50, 230], [210, 245, 60], [250, 190, 212], [0, 128, 128], [220, 190, 255],
  [170, 110, 40], [255, 250, 200], [128, 0, 0], [170, 255, 195], [128, 128, 0], [255, 215, 180],
  [0, 0, 128], [128, 128, 128],
];
export function chartColor(c) { return c < 0 ? COLOR_NEUTRAL : CHART[c % CHART.length]; }
