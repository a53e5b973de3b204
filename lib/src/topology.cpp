// analyze_topology: face grouping by counting sort (face_grouping.hpp), union-find for components,
// per-vertex link walks over a CSR of boundary faces. Conventions in topology.hpp.
#include <volmap/topology.hpp>

#include <volmap/error.hpp>
#include <volmap/local_tables.hpp>

#include "face_grouping.hpp"

#include <algorithm>
#include <numeric>
#include <string>

namespace volmap {
namespace {

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// CSR of (key -> values) by counting sort; values of one key keep insertion order.
struct Csr {
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> values;
};

}  // namespace

TopologyReport analyze_topology(const TetMeshData& data) {
  TopologyReport r;
  if (data.xyz.size() % 3 != 0) throw Error(ErrorKind::BadInput, "", 0, "vertex coordinate array size is not a multiple of 3");
  if (data.tets.size() % 4 != 0) throw Error(ErrorKind::BadInput, "", 0, "tet array size is not a multiple of 4");
  const std::size_t nv = data.num_vertices(), nt = data.num_tets();
  if (nt > (std::size_t(1) << 30)) throw Error(ErrorKind::BadInput, "", 0, "too many tets");
  r.num_vertices = nv;
  r.num_tets = nt;
  const std::uint32_t* tv = data.tets.data();

  std::vector<char> degenerate(nt, 0);
  std::vector<char> used(nv, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* p = tv + 4 * t;
    for (int i = 0; i < 4; ++i) {
      if (p[i] >= nv)
        throw Error(ErrorKind::BadInput, "", 0,
                    "tet " + std::to_string(t) + " references vertex " + std::to_string(p[i]) + " but there are " +
                        std::to_string(nv) + " vertices");
      for (int j = 0; j < i; ++j)
        if (p[i] == p[j]) degenerate[t] = 1;
    }
    if (degenerate[t]) {
      ++r.num_degenerate_tets;
      continue;
    }
    for (int i = 0; i < 4; ++i) used[p[i]] = 1;
  }
  for (std::size_t v = 0; v < nv; ++v) r.num_unused_vertices += used[v] ? 0 : 1;

  // Faces: multiplicities, boundary half-faces, tet adjacency.
  UnionFind tet_sets(nt);
  std::vector<std::uint32_t>& bhf = r.boundary_half_faces;
  detail::group_faces(
      tv, nt, nv, [&degenerate](std::size_t t) { return degenerate[t] != 0; },
      [&](std::uint32_t, const detail::FaceEntry* g, std::size_t n) {
        ++r.num_faces;
        if (n == 1) {
          bhf.push_back(g[0].hf);
          return;
        }
        for (std::size_t k = 1; k < n; ++k) tet_sets.unite(g[0].hf >> 2, g[k].hf >> 2);
        if (n == 2) {
          ++r.num_interior_faces;
          if (g[0].parity == g[1].parity) {
            ++r.num_inconsistent_faces;
            if (r.example_inconsistent_face == kNone) r.example_inconsistent_face = g[0].hf;
          }
        } else {
          ++r.num_nonmanifold_faces;
          if (r.example_nonmanifold_face == kNone) r.example_nonmanifold_face = g[0].hf;
        }
      });
  std::sort(bhf.begin(), bhf.end());
  for (std::size_t t = 0; t < nt; ++t)
    if (!degenerate[t] && tet_sets.find(std::uint32_t(t)) == t) ++r.num_tet_components;

  // Boundary triangles (outward windings), vertex -> boundary faces CSR.
  const std::size_t nf = bhf.size();
  r.num_boundary_faces = nf;
  std::vector<std::uint32_t> tri(3 * nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t* p = tv + 4 * std::size_t(bhf[f] >> 2);
    const std::uint8_t* lf = kTetFace[bhf[f] & 3];
    for (int k = 0; k < 3; ++k) tri[3 * f + k] = p[lf[k]];
  }
  Csr vf;
  vf.offsets.assign(nv + 2, 0);
  for (std::uint32_t v : tri) ++vf.offsets[std::size_t(v) + 2];
  for (std::size_t v = 2; v < vf.offsets.size(); ++v) vf.offsets[v] += vf.offsets[v - 1];
  vf.values.resize(3 * nf);
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) vf.values[vf.offsets[std::size_t(tri[3 * f + k]) + 1]++] = std::uint32_t(f);
  for (std::size_t v = 0; v < nv; ++v) r.num_boundary_vertices += vf.offsets[v + 1] > vf.offsets[v] ? 1 : 0;

  // Boundary edges: each triangle edge (u,v) filed under min(u,v); count faces per edge.
  UnionFind vsets(nv);
  std::vector<std::uint32_t> others;  // per-vertex scratch
  for (std::size_t v = 0; v < nv; ++v) {
    const std::uint32_t b = vf.offsets[v], e = vf.offsets[v + 1];
    if (b == e) continue;
    others.clear();
    for (std::uint32_t k = b; k < e; ++k) {
      const std::uint32_t* t3 = &tri[3 * std::size_t(vf.values[k])];
      for (int j = 0; j < 3; ++j)
        if (t3[j] > v) others.push_back(t3[j]);
    }
    std::sort(others.begin(), others.end());
    std::size_t i = 0;
    while (i < others.size()) {
      std::size_t j = i + 1;
      while (j < others.size() && others[j] == others[i]) ++j;
      ++r.num_boundary_edges;
      vsets.unite(std::uint32_t(v), others[i]);
      const std::size_t m = j - i;
      if (m != 2) {
        ++r.num_nonmanifold_boundary_edges;
        if (m == 1) ++r.num_border_edges;
        else ++r.num_overshared_edges;
        if (r.example_nonmanifold_edge_vertex == kNone) r.example_nonmanifold_edge_vertex = std::uint32_t(v);
      }
      i = j;
    }
  }
  for (std::size_t v = 0; v < nv; ++v)
    if (vf.offsets[v + 1] > vf.offsets[v] && vsets.find(std::uint32_t(v)) == v) ++r.num_boundary_components;

  // Vertex links: the opposite edges of the boundary faces around v must form one cycle (or one
  // path, for a vertex on a border), i.e. every link vertex has degree 2 (1 at path ends) and the
  // link is connected.
  std::vector<std::uint32_t> link, ends;
  std::vector<char> seen;
  for (std::size_t v = 0; v < nv; ++v) {
    const std::uint32_t b = vf.offsets[v], e = vf.offsets[v + 1];
    if (b == e) continue;
    link.clear();
    for (std::uint32_t k = b; k < e; ++k) {
      const std::uint32_t* t3 = &tri[3 * std::size_t(vf.values[k])];
      for (int j = 0; j < 3; ++j)
        if (t3[j] == v) {
          link.push_back(t3[(j + 1) % 3]);
          link.push_back(t3[(j + 2) % 3]);
        }
    }
    ends = link;
    std::sort(ends.begin(), ends.end());
    bool ok = true;
    std::size_t degree1 = 0;
    std::uint32_t start = link[0];
    for (std::size_t i = 0; i < ends.size() && ok;) {
      std::size_t j = i + 1;
      while (j < ends.size() && ends[j] == ends[i]) ++j;
      if (j - i == 1) {
        ++degree1;
        start = ends[i];
      } else if (j - i != 2) {
        ok = false;
      }
      i = j;
    }
    if (ok && degree1 != 0 && degree1 != 2) ok = false;
    if (ok) {  // connected: walk from `start` along unused link edges
      const std::size_t ne = link.size() / 2;
      std::size_t walked = 0;
      std::uint32_t cur = start;
      seen.assign(ne, 0);  // O(k^2) walk: links are small
      for (;;) {
        std::size_t k = 0;
        for (; k < ne; ++k) {
          if (seen[k]) continue;
          const std::uint32_t p = link[2 * k], q = link[2 * k + 1];
          if (p == cur || q == cur) {
            seen[k] = 1;
            cur = p == cur ? q : p;
            ++walked;
            break;
          }
        }
        if (k == ne) break;
      }
      ok = walked == ne;
    }
    if (!ok) {
      ++r.num_nonmanifold_boundary_vertices;
      if (r.example_nonmanifold_vertex == kNone) r.example_nonmanifold_vertex = std::uint32_t(v);
    }
  }

  r.boundary_euler = (long long)r.num_boundary_vertices - (long long)r.num_boundary_edges + (long long)nf;
  const long long twice_genus = 2 * (long long)r.num_boundary_components - r.boundary_euler;
  r.boundary_genus = twice_genus >= 0 ? twice_genus / 2 : -((-twice_genus + 1) / 2);

  r.faces_manifold = r.num_nonmanifold_faces == 0;
  r.orientation_consistent = r.num_inconsistent_faces == 0;
  r.single_tet_component = r.num_tet_components == 1;
  r.boundary_edges_manifold = r.num_nonmanifold_boundary_edges == 0;
  r.boundary_vertices_manifold = r.num_nonmanifold_boundary_vertices == 0;
  r.boundary_closed = r.num_border_edges == 0;
  r.single_boundary_component = r.num_boundary_components == 1;
  r.boundary_genus_defined = nf > 0 && r.boundary_closed && r.boundary_edges_manifold && r.boundary_vertices_manifold &&
                             twice_genus % 2 == 0;
  r.boundary_genus_zero = r.boundary_genus_defined && r.boundary_genus == 0;
  r.no_degenerate_tets = r.num_degenerate_tets == 0;
  r.no_unused_vertices = r.num_unused_vertices == 0;
  return r;
}

}  // namespace volmap
