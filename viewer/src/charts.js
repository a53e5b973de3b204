// Boundary-map structure seen from the mapped surface: charts (= domain faces), arcs and corners.
// Domain faces are inferred from the planes of the mapped boundary triangles: triangles whose
// supporting planes agree (normal within ~2.5 degrees up to sign, offset within 1e-3 of the domain
// size; the dataset's maps have 6 decimals, so points on slanted faces are only nearly coplanar)
// share a chart. A curved domain (sphere) gives too many planes: then there are no charts.
// Arcs: boundary edges between two charts. Corners: boundary vertices touching >= 3 charts.
import { LOCAL_FACES } from './topology.js';

const MAX_CHARTS = 64;

export function inferCharts(tets, xyz, boundaryFaces, radius) {
  const nb = boundaryFaces.length;
  const chart = new Int32Array(nb).fill(-1);
  const planes = [];  // [nx, ny, nz, d, count]
  const cosTol = 0.999, dTol = 1e-3 * radius;
  const tri = new Uint32Array(3);
  let curved = false;
  for (let k = 0; k < nb; k++) {
    const f = boundaryFaces[k], t = f >> 2, i = f & 3;
    for (let j = 0; j < 3; j++) tri[j] = tets[4 * t + LOCAL_FACES[3 * i + j]];
    const ax = xyz[3 * tri[0]], ay = xyz[3 * tri[0] + 1], az = xyz[3 * tri[0] + 2];
    const ux = xyz[3 * tri[1]] - ax, uy = xyz[3 * tri[1] + 1] - ay, uz = xyz[3 * tri[1] + 2] - az;
    const vx = xyz[3 * tri[2]] - ax, vy = xyz[3 * tri[2] + 1] - ay, vz = xyz[3 * tri[2] + 2] - az;
    let nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const len = Math.sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0)) continue;  // degenerate mapped triangle: no plane, left unassigned
    nx /= len; ny /= len; nz /= len;
    const d = nx * ax + ny * ay + nz * az;
    let found = -1;
    for (let c = 0; c < planes.length; c++) {
      const p = planes[c];
      const dot = nx * p[0] + ny * p[1] + nz * p[2];
      if (dot > cosTol && Math.abs(d - p[3]) < dTol) { found = c; break; }
      if (dot < -cosTol && Math.abs(-d - p[3]) < dTol) { found = c; break; }
    }
    if (found < 0) {
      if (planes.length >= MAX_CHARTS) { curved = true; break; }
      planes.push([nx, ny, nz, d, 0]);
      found = planes.length - 1;
    }
    planes[found][4]++;
    chart[k] = found;
  }
  if (curved) return { curved: true, numCharts: 0, chart: chart.fill(-1), arcs: new Uint32Array(0), corners: new Uint32Array(0) };

  // Arcs: edges shared by two boundary faces of different charts.
  const arcs = [];
  // Distinct charts per vertex, up to three (a corner needs three): typed arrays, no per-vertex sets.
  let nv = 0;
  for (let k = 0; k < tets.length; k++) if (tets[k] >= nv) nv = tets[k] + 1;
  const firstChart = new Int32Array(nv).fill(-1), secondChart = new Int32Array(nv).fill(-1);
  const onThree = new Uint8Array(nv);
  const addChart = (v, c) => {
    if (firstChart[v] < 0 || firstChart[v] === c) { firstChart[v] = c; return; }
    if (secondChart[v] < 0 || secondChart[v] === c) { secondChart[v] = c; return; }
    onThree[v] = 1;
  };
  // Edges of boundary faces matched in pairs by an open-addressing hash on typed arrays.
  const numEdges = 3 * nb;
  let size = 1;
  while (size < 2 * numEdges) size <<= 1;
  const mask = size - 1;
  const table = new Int32Array(size).fill(-1);
  const edgeLo = new Uint32Array(numEdges), edgeHi = new Uint32Array(numEdges);
  const matched = new Uint8Array(numEdges);
  for (let k = 0; k < nb; k++) {
    const f = boundaryFaces[k], t = f >> 2, i = f & 3;
    for (let j = 0; j < 3; j++) {
      const a = tets[4 * t + LOCAL_FACES[3 * i + j]], b = tets[4 * t + LOCAL_FACES[3 * i + (j + 1) % 3]];
      if (chart[k] >= 0) addChart(a, chart[k]);
      const lo = a < b ? a : b, hi = a < b ? b : a, e = 3 * k + j;
      edgeLo[e] = lo; edgeHi[e] = hi;
      let h = ((Math.imul(lo, 0x9e3779b1) ^ Math.imul(hi, 0x85ebca77)) >>> 0);
      h = (h ^ (h >>> 15)) & mask;
      for (;;) {
        const g = table[h];
        if (g < 0) { table[h] = e; break; }
        if (!matched[g] && edgeLo[g] === lo && edgeHi[g] === hi) {
          matched[g] = matched[e] = 1;
          if (chart[(g / 3) | 0] !== chart[k]) arcs.push(lo, hi);
          break;
        }
        h = (h + 1) & mask;
      }
    }
  }
  const corners = [];
  for (let v = 0; v < nv; v++) if (onThree[v]) corners.push(v);
  return { curved: false, numCharts: planes.length, chart, arcs: Uint32Array.from(arcs), corners: Uint32Array.from(corners) };
}
