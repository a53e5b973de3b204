// Face adjacency of a tet mesh on flat typed arrays (no per-element objects).
// Face f = 4*t + i is the face of tet t opposite local vertex i, listed outward for VOLMAP-positive
// tets: F0=(1,3,2) F1=(0,2,3) F2=(0,3,1) F3=(0,1,2) (volmap-reference.md §1).
// neighbour[f] = the matching face 4*t'+i' of the adjacent tet, or -1 on the boundary.

export const LOCAL_FACES = [1, 3, 2, 0, 2, 3, 0, 3, 1, 0, 1, 2];

export function faceAdjacency(tets, numTets) {
  const numFaces = 4 * numTets;
  const neighbour = new Int32Array(numFaces).fill(-1);
  // Sorted vertex triple of every face.
  const key = new Uint32Array(3 * numFaces);
  for (let f = 0; f < numFaces; f++) {
    const t = f >> 2, i = f & 3;
    let a = tets[4 * t + LOCAL_FACES[3 * i]], b = tets[4 * t + LOCAL_FACES[3 * i + 1]], c = tets[4 * t + LOCAL_FACES[3 * i + 2]];
    let s;
    if (a > b) { s = a; a = b; b = s; }
    if (b > c) { s = b; b = c; c = s; }
    if (a > b) { s = a; a = b; b = s; }
    key[3 * f] = a; key[3 * f + 1] = b; key[3 * f + 2] = c;
  }
  // Open-addressing hash table of face ids (power-of-two size, load <= 0.5).
  let size = 1;
  while (size < 2 * numFaces) size <<= 1;
  const mask = size - 1;
  const table = new Int32Array(size).fill(-1);
  for (let f = 0; f < numFaces; f++) {
    const a = key[3 * f], b = key[3 * f + 1], c = key[3 * f + 2];
    let h = (Math.imul(a, 0x9e3779b1) ^ Math.imul(b, 0x85ebca77) ^ Math.imul(c, 0xc2b2ae3d)) >>> 0;
    h = (h ^ (h >>> 15)) & mask;
    for (;;) {
      const g = table[h];
      if (g < 0) { table[h] = f; break; }
      if (neighbour[g] < 0 && key[3 * g] === a && key[3 * g + 1] === b && key[3 * g + 2] === c) {
        neighbour[g] = f; neighbour[f] = g; break;
      }
      h = (h + 1) & mask;
    }
  }
  return neighbour;
}

export function boundaryFaceList(neighbour) {
  let n = 0;
  for (let f = 0; f < neighbour.length; f++) if (neighbour[f] < 0) n++;
  const list = new Int32Array(n);
  n = 0;
  for (let f = 0; f < neighbour.length; f++) if (neighbour[f] < 0) list[n++] = f;
  return list;
}

// Faces to draw: faces of visible tets whose neighbour is absent (boundary) or hidden (cut faces).
// Writes face ids into `out` (grown when too small) and returns {faces, count}.
export function visibleFaces(neighbour, visible, out) {
  const numFaces = neighbour.length;
  let count = 0;
  for (let f = 0; f < numFaces; f++) {
    if (!visible[f >> 2]) continue;
    const g = neighbour[f];
    if (g >= 0 && visible[g >> 2]) continue;
    count++;
  }
  if (!out || out.length < count) out = new Int32Array(Math.max(count, 1024) * 1.25 | 0);
  let k = 0;
  for (let f = 0; f < numFaces; f++) {
    if (!visible[f >> 2]) continue;
    const g = neighbour[f];
    if (g >= 0 && visible[g >> 2]) continue;
    out[k++] = f;
  }
  return { faces: out, count };
}
