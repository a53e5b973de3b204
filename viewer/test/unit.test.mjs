// Unit tests of the viewer's typed-array geometry (node's test runner, no browser):
//   node --test test/unit.test.mjs
// Oracles: brute-force face matching on a Freudenthal grid (known boundary face count 12 n^2),
// the chart / corner / arc counts of a cube, and the base64 + array layout decoder.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { faceAdjacency, boundaryFaceList, visibleFaces, LOCAL_FACES } from '../src/topology.js';
import { inferCharts } from '../src/charts.js';

// n^3 cubes, 6 tets each (Kuhn split), as in tests/view_test_support.hpp.
function grid(n) {
  const xyz = [], tets = [];
  const vid = (i, j, k) => (i * (n + 1) + j) * (n + 1) + k;
  for (let i = 0; i <= n; i++) for (let j = 0; j <= n; j++) for (let k = 0; k <= n; k++) xyz.push(i / n, j / n, k / n);
  const perms = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
  for (let i = 0; i < n; i++) for (let j = 0; j < n; j++) for (let k = 0; k < n; k++) for (const p of perms) {
    const c = [i, j, k], t = [vid(...c)];
    for (const a of p) { c[a]++; t.push(vid(...c)); }
    tets.push(...t);
  }
  return { xyz: Float32Array.from(xyz), tets: Uint32Array.from(tets), nt: tets.length / 4 };
}

function bruteNeighbours(tets, nt) {
  const key = (f) => {
    const t = f >> 2, i = f & 3;
    return [0, 1, 2].map((j) => tets[4 * t + LOCAL_FACES[3 * i + j]]).sort((a, b) => a - b).join(',');
  };
  const byKey = new Map();
  for (let f = 0; f < 4 * nt; f++) { const k = key(f); byKey.set(k, [...(byKey.get(k) || []), f]); }
  const nb = new Int32Array(4 * nt).fill(-1);
  for (const fs of byKey.values()) if (fs.length === 2) { nb[fs[0]] = fs[1]; nb[fs[1]] = fs[0]; }
  return nb;
}

test('face adjacency matches brute force and the grid boundary count', () => {
  const n = 4, g = grid(n);
  const nb = faceAdjacency(g.tets, g.nt);
  assert.deepEqual(Array.from(nb), Array.from(bruteNeighbours(g.tets, g.nt)));
  assert.equal(boundaryFaceList(nb).length, 12 * n * n);  // 6 sides x n^2 squares x 2 triangles
});

test('cut faces: hiding half the tets exposes interior faces, hiding none shows the boundary only', () => {
  const g = grid(3);
  const nb = faceAdjacency(g.tets, g.nt);
  const all = new Uint8Array(g.nt).fill(1);
  assert.equal(visibleFaces(nb, all, null).count, boundaryFaceList(nb).length);
  const half = new Uint8Array(g.nt);
  for (let t = 0; t < g.nt; t++) {
    let cx = 0;
    for (let j = 0; j < 4; j++) cx += g.xyz[3 * g.tets[4 * t + j]];
    half[t] = cx / 4 < 0.5 ? 1 : 0;
  }
  const { faces, count } = visibleFaces(nb, half, null);
  let cut = 0;
  for (let k = 0; k < count; k++) {
    const f = faces[k];
    assert.equal(half[f >> 2], 1);
    if (nb[f] >= 0) { cut++; assert.equal(half[nb[f] >> 2], 0); }
  }
  assert.ok(cut > 0);
  assert.equal(visibleFaces(nb, new Uint8Array(g.nt), null).count, 0);
});

test('charts of a cube: 6 faces, 8 corners, arcs on the 12 edges', () => {
  const n = 3, g = grid(n);
  const nb = faceAdjacency(g.tets, g.nt);
  const boundary = boundaryFaceList(nb);
  const xyz = Float64Array.from(g.xyz, (v) => 100 * v);
  const c = inferCharts(g.tets, xyz, boundary, 100 * Math.sqrt(3) / 2);
  assert.equal(c.curved, false);
  assert.equal(c.numCharts, 6);
  assert.equal(c.corners.length, 8);
  assert.equal(c.arcs.length / 2, 12 * n);  // each cube edge split into n segments
  // Curved: a sphere-like bump on every vertex gives no planar charts.
  const bumpy = xyz.map((v, i) => v + 3 * Math.sin(i * 12.9898));
  assert.equal(inferCharts(g.tets, bumpy, boundary, 87).curved, true);
});
