// Decodes the data volmap-view embeds in the page:
//   <script type="application/json" id="volmap-meta">  : layout + figures computed in C++
//   <script type="application/octet-stream" id="volmap-data"> : one base64 blob of little-endian arrays
// meta.arrays[name] = {type: 'f32'|'u32'|'i32'|'u8', offset (bytes, 4-aligned), count}.
// Conventions (see tools/support/view_export.hpp): vertex ids 0-based, tets 4 ids each in file
// order (VOLMAP-positive: orient3d(v0,v1,v2,v3) > 0), per-tet flags decided exactly in C++.

const CTORS = { f32: Float32Array, u32: Uint32Array, i32: Int32Array, u8: Uint8Array };

function base64ToBytes(text) {
  const clean = text.replace(/\s+/g, '');
  if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(clean);
  const bin = atob(clean);
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}

export function loadEmbeddedData(doc = document) {
  const metaEl = doc.getElementById('volmap-meta');
  const dataEl = doc.getElementById('volmap-data');
  if (!metaEl || !dataEl) throw new Error('volmap-view: embedded data not found in the page');
  const meta = JSON.parse(metaEl.textContent);
  if (meta.format !== 'volmap-view-1') throw new Error(`volmap-view: unknown data format ${meta.format}`);
  const bytes = base64ToBytes(dataEl.textContent);
  if (bytes.length !== meta.byte_length) {
    throw new Error(`volmap-view: data blob has ${bytes.length} bytes, expected ${meta.byte_length}`);
  }
  const buffer = bytes.buffer;
  const arrays = {};
  for (const [name, a] of Object.entries(meta.arrays)) {
    const Ctor = CTORS[a.type];
    if (!Ctor) throw new Error(`volmap-view: array ${name} has unknown type ${a.type}`);
    if (a.offset % Ctor.BYTES_PER_ELEMENT !== 0 || a.offset + a.count * Ctor.BYTES_PER_ELEMENT > bytes.length) {
      throw new Error(`volmap-view: array ${name} is out of the data blob`);
    }
    arrays[name] = new Ctor(buffer, bytes.byteOffset + a.offset, a.count);
  }
  return { meta, arrays };
}

// Flag bits written by volmap::write_view_html (exact, from volmap predicates).
export const FLAG_INVERTED = 1;    // orient3d(mapped tet) < 0
export const FLAG_DEGENERATE = 2;  // orient3d(mapped tet) == 0
export const FLAG_SOURCE_BAD = 4;  // orient3d(source tet) <= 0
