// analyze_topology: face grouping by counting sort (face_grouping.hpp), union-find for tet components,
// duplicate tets only where they can exist (duplicates_possible); its boundary triangles go through
// analyze_surface_topology (union-find components with per-component chi; per vertex, over a CSR of
// incident triangles, the closed-fan test of closed_manifold_links (VertexFan, which the
// self-intersection test uses too), and where it fails the general link analysis: link union-find,
// and the edges to higher ids with their multiplicity and direction), which the surface checks
// (tetmesh_checks.cpp) use as well. Conventions in topology.hpp.
#include <volmap/core/topology.hpp>

#include <volmap/core/error.hpp>
#include <volmap/core/local_tables.hpp>

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
  void reset(std::size_t n) {
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0u);
  }
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

std::string fmt(std::size_t n) { return std::to_string(n); }

// Identical tets share all four faces; each set of copies is counted once, in the group of its face
// opposite its largest vertex (face_max: the group's largest vertex id), as the members whose
// opposite vertex is larger than face_max and equal to an earlier member's (members come sorted by
// tet). Groups hold two tets except at non-manifold faces, so the double loop stays small.
void count_duplicate_tets(const std::uint32_t* tv, std::uint32_t face_max, const std::uint32_t* g, std::size_t n,
                          TopologyReport& r) {
  for (std::size_t k = 1; k < n; ++k) {
    const std::uint32_t hk = detail::hf_of(g[k]);
    if (tv[hk] <= face_max) continue;
    for (std::size_t j = 0; j < k; ++j) {
      const std::uint32_t hj = detail::hf_of(g[j]);
      if (tv[hj] != tv[hk]) continue;
      ++r.num_duplicate_tets;
      if (r.example_duplicate_second == kNone || (hk >> 2) < r.example_duplicate_second) {
        r.example_duplicate_first = hj >> 2;
        r.example_duplicate_second = hk >> 2;
      }
      break;
    }
  }
}

// Triangle (v, next, prev) as seen from its corner v (one of its three ids).
struct Corner {
  std::uint32_t next, prev;
};
inline Corner corner_at(const std::uint32_t* tri, std::uint32_t v) {
  const int at = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
  return {tri[(at + 1) % 3], tri[(at + 2) % 3]};
}

// Per vertex v, its link: the opposite edge (next, prev) of each incident triangle (v, next, prev).
// A link vertex w is on as many triangles with v as its link degree, so the edges (v, w), w > v,
// are counted here with their multiplicity and direction (v -> w when w follows v), in (v, w)
// order. A manifold vertex has one link component and link degrees <= 2.
void general_links(std::size_t num_vertices, const std::vector<std::uint32_t>& tris,
                   const std::vector<std::uint32_t>& offsets, const std::vector<std::uint32_t>& incident,
                   UnionFind& sets, std::vector<long long>& comp_chi, SurfaceTopology& st) {
  std::vector<std::uint32_t> link_vertices, link_degree, link_forward;
  UnionFind link_sets(0);
  for (std::size_t v = 0; v < num_vertices; ++v) {
    const std::uint32_t begin = offsets[v], end = offsets[v + 1];
    if (begin == end) continue;
    link_vertices.clear();
    for (std::uint32_t i = begin; i < end; ++i)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t w = tris[3 * incident[i] + k];
        if (w != v) link_vertices.push_back(w);
      }
    std::sort(link_vertices.begin(), link_vertices.end());
    link_vertices.erase(std::unique(link_vertices.begin(), link_vertices.end()), link_vertices.end());
    const std::size_t m = link_vertices.size();
    link_sets.reset(m);
    link_degree.assign(m, 0);
    link_forward.assign(m, 0);
    auto local = [&](std::uint32_t w) {
      return std::uint32_t(std::lower_bound(link_vertices.begin(), link_vertices.end(), w) - link_vertices.begin());
    };
    for (std::uint32_t i = begin; i < end; ++i) {
      const Corner c = corner_at(&tris[3 * incident[i]], std::uint32_t(v));
      const std::uint32_t next = local(c.next), prev = local(c.prev);
      link_sets.unite(next, prev);
      ++link_degree[next];
      ++link_degree[prev];
      ++link_forward[next];
    }
    std::size_t link_components = 0;
    bool degree_ok = true;
    for (std::uint32_t i = 0; i < m; ++i) {
      if (link_sets.find(i) == i) ++link_components;
      if (link_degree[i] > 2) degree_ok = false;
      if (link_vertices[i] < v) continue;
      const std::uint32_t count = link_degree[i];  // the edge (v, w) with w > v
      ++st.num_edges;
      --comp_chi[sets.find(std::uint32_t(v))];
      if (count == 1) ++st.num_border_edges;
      if (count > 2) ++st.num_overshared_edges;
      if (count != 2 && st.example_nonmanifold_edge_vertex == kNone) st.example_nonmanifold_edge_vertex = std::uint32_t(v);
      if (count == 2 && link_forward[i] != 1) ++st.num_inconsistent_edges;
    }
    if (link_components != 1 || !degree_ok) {
      ++st.num_nonmanifold_vertices;
      if (st.example_nonmanifold_vertex == kNone) st.example_nonmanifold_vertex = std::uint32_t(v);
    }
  }
}

// The common case, decided per vertex without sorting: every vertex's incident triangles form one
// closed fan (VertexFan). Then every edge (v, w) lies on exactly two triangles that traverse it in
// opposite directions, and every link is one cycle: a closed, consistently oriented 2-manifold.
// Counts the edges (at their lower endpoint) into st and comp_chi and returns true; at the first
// vertex where this fails, returns false with st and comp_chi untouched.
bool closed_manifold_links(std::size_t num_vertices, const std::vector<std::uint32_t>& tris,
                           const std::vector<std::uint32_t>& offsets, const std::vector<std::uint32_t>& incident,
                           UnionFind& sets, std::vector<long long>& comp_chi, SurfaceTopology& st) {
  VertexFan fan;
  std::vector<std::uint32_t> edges_at(num_vertices, 0);  // edges (v, w), w > v
  for (std::size_t v = 0; v < num_vertices; ++v) {
    const std::uint32_t begin = offsets[v], end = offsets[v + 1];
    if (begin == end) continue;
    if (!fan.close(tris.data(), std::uint32_t(v), incident.data() + begin, end - begin)) return false;
    for (const std::uint32_t w : fan.ring()) edges_at[v] += w > v ? 1u : 0u;
  }
  for (std::size_t v = 0; v < num_vertices; ++v) {
    if (edges_at[v] == 0) continue;
    st.num_edges += edges_at[v];
    comp_chi[sets.find(std::uint32_t(v))] -= edges_at[v];
  }
  return true;
}

// Two tets over the same four vertices share all four faces. If a third tet has one of those faces,
// that face is non-manifold; if none does, the two form a piece of their own: a second tet component,
// or the whole mesh with no boundary face. A mesh with none of the three has no duplicate tets, and
// their count (a second pass over the faces, reading every face's opposite vertex) is skipped.
bool duplicates_possible(const TopologyReport& r) {
  return r.num_nonmanifold_faces > 0 || r.num_tet_components != 1 || r.boundary_half_faces.empty();
}

}  // namespace

TopologyReport analyze_topology(const TetMeshData& data) {
  TopologyReport r;
  if (data.xyz.size() % 3 != 0) throw Error(ErrorKind::BadInput, "vertex coordinate array size is not a multiple of 3");
  if (data.tets.size() % 4 != 0) throw Error(ErrorKind::BadInput, "tet array size is not a multiple of 4");
  const std::size_t nv = data.num_vertices(), nt = data.num_tets();
  if (nt > detail::kMaxGroupedTets) throw Error(ErrorKind::BadInput, "too many tets (> 2^29)");
  r.num_vertices = nv;
  r.num_tets = nt;
  const std::uint32_t* tv = data.tets.data();

  std::vector<char> degenerate(nt, 0);
  std::vector<char> used(nv, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* p = tv + 4 * t;
    for (int i = 0; i < 4; ++i) {
      if (p[i] >= nv)
        throw Error(ErrorKind::BadInput, "tet " + std::to_string(t) + " references vertex " + std::to_string(p[i]) + " but there are " +
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
  std::vector<std::uint64_t> boundary_bits((4 * nt + 63) / 64, 0);  // bit h: half-face h is on the boundary
  detail::group_faces(
      tv, nt, nv, [&degenerate](std::size_t t) { return degenerate[t] != 0; },
      [&](std::uint32_t, const std::uint64_t*, const std::uint32_t* g, std::size_t n) {
        ++r.num_faces;
        const std::uint32_t h0 = detail::hf_of(g[0]);
        if (n == 1) {
          boundary_bits[h0 >> 6] |= std::uint64_t(1) << (h0 & 63);
          return;
        }
        for (std::size_t k = 1; k < n; ++k) tet_sets.unite(h0 >> 2, detail::hf_of(g[k]) >> 2);
        if (n == 2) {
          ++r.num_interior_faces;
          if (detail::parity_of(g[0]) == detail::parity_of(g[1])) {
            ++r.num_inconsistent_faces;
            if (r.example_inconsistent_face == kNone) r.example_inconsistent_face = h0;
          }
        } else {
          ++r.num_nonmanifold_faces;
          if (r.example_nonmanifold_face == kNone) r.example_nonmanifold_face = h0;
        }
      });
  std::vector<std::uint32_t>& bhf = r.boundary_half_faces;  // in increasing order
  std::size_t num_boundary = 0;
  for (const std::uint64_t word : boundary_bits) num_boundary += std::size_t(__builtin_popcountll(word));
  bhf.reserve(num_boundary);
  for (std::size_t w = 0; w < boundary_bits.size(); ++w)
    for (std::uint64_t word = boundary_bits[w]; word != 0; word &= word - 1)
      bhf.push_back(std::uint32_t(64 * w + std::size_t(__builtin_ctzll(word))));
  for (std::size_t t = 0; t < nt; ++t)
    if (!degenerate[t] && tet_sets.find(std::uint32_t(t)) == t) ++r.num_tet_components;
  if (duplicates_possible(r)) {
    detail::group_faces(
        tv, nt, nv, [&degenerate](std::size_t t) { return degenerate[t] != 0; },
        [&](std::uint32_t, const std::uint64_t* keys, const std::uint32_t* g, std::size_t n) {
          if (n >= 2) count_duplicate_tets(tv, std::uint32_t(keys[0]), g, n, r);
        });
  }

  // Boundary triangles (outward windings) -> the triangle-surface topology.
  const std::size_t nf = bhf.size();
  r.num_boundary_faces = nf;
  std::vector<std::uint32_t> tri(3 * nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t* p = tv + 4 * std::size_t(bhf[f] >> 2);
    const std::uint8_t* lf = kTetFace[bhf[f] & 3];
    for (int k = 0; k < 3; ++k) tri[3 * f + k] = p[lf[k]];
  }
  const SurfaceTopology s = analyze_surface_topology(nv, tri);
  r.num_boundary_vertices = s.num_used_vertices;
  r.num_boundary_edges = s.num_edges;
  r.num_border_edges = s.num_border_edges;
  r.num_overshared_edges = s.num_overshared_edges;
  r.num_nonmanifold_boundary_edges = s.num_border_edges + s.num_overshared_edges;
  r.example_nonmanifold_edge_vertex = s.example_nonmanifold_edge_vertex;
  r.num_nonmanifold_boundary_vertices = s.num_nonmanifold_vertices;
  r.example_nonmanifold_vertex = s.example_nonmanifold_vertex;
  r.num_boundary_components = s.num_components;
  r.boundary_euler = s.euler;
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

// Each triangle is followed by the one whose prev is its next; the count of such triangles must be
// exactly one (counted without branches: fans are small and the matches unpredictable), and the walk
// must first return to its start after all m triangles. Then the followers form one cyclic
// permutation, so the prevs (the ring) are distinct: two equal prevs would both follow one triangle.
bool VertexFan::close(const std::uint32_t* tris, std::uint32_t v, const std::uint32_t* incident, std::size_t m) {
  next_.resize(m);
  prev_.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    const Corner c = corner_at(tris + 3 * std::size_t(incident[i]), v);
    if (c.next == v || c.prev == v || c.next == c.prev) return false;
    next_[i] = c.next;
    prev_[i] = c.prev;
  }
  ring_.clear();
  std::size_t i = 0;
  for (std::size_t step = 0; step < m; ++step) {
    ring_.push_back(prev_[i]);
    std::size_t follower = m, followers = 0;
    for (std::size_t j = 0; j < m; ++j) {
      const bool match = prev_[j] == next_[i];
      followers += match;
      follower = match ? j : follower;
    }
    if (followers != 1 || (follower == 0) != (step + 1 == m)) return false;
    i = follower;
  }
  return m > 0;
}

SurfaceTopology analyze_surface_topology(std::size_t num_vertices, const std::vector<std::uint32_t>& tris) {
  if (tris.size() % 3 != 0) throw Error(ErrorKind::BadInput, "triangle array size is not a multiple of 3");
  if (num_vertices >= 0xFFFFFFFFu) throw Error(ErrorKind::Unsupported, "too many vertices");
  SurfaceTopology st;
  st.num_vertices = num_vertices;
  const std::size_t n_all = tris.size() / 3;
  for (std::size_t i = 0; i < tris.size(); ++i)
    if (tris[i] >= num_vertices)
      throw Error(ErrorKind::BadInput, "triangle " + fmt(i / 3) + " refers to vertex " + fmt(tris[i]) + " of " + fmt(num_vertices));

  // Valid triangles only.
  std::vector<std::uint32_t> valid;
  valid.reserve(n_all);
  for (std::size_t t = 0; t < n_all; ++t) {
    const std::uint32_t *v = &tris[3 * t];
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
      ++st.num_repeated_id_triangles;
    else
      valid.push_back(std::uint32_t(t));
  }
  st.num_triangles = valid.size();

  UnionFind sets(num_vertices);
  for (std::uint32_t t : valid) {
    sets.unite(tris[3 * t], tris[3 * t + 1]);
    sets.unite(tris[3 * t], tris[3 * t + 2]);
  }
  std::vector<std::uint8_t> used(num_vertices, 0);
  for (std::uint32_t t : valid)
    for (int k = 0; k < 3; ++k) used[tris[3 * t + k]] = 1;

  // Per-component V and F (E below) -> chi_i.
  std::vector<long long> comp_chi(num_vertices, 0);
  for (std::size_t v = 0; v < num_vertices; ++v)
    if (used[v]) {
      ++st.num_used_vertices;
      ++comp_chi[sets.find(std::uint32_t(v))];
      if (sets.find(std::uint32_t(v)) == v) ++st.num_components;
    }
  for (std::uint32_t t : valid) ++comp_chi[sets.find(tris[3 * t])];

  // Vertex -> incident valid triangles (CSR).
  std::vector<std::uint32_t> offsets(num_vertices + 1, 0);
  for (std::uint32_t t : valid)
    for (int k = 0; k < 3; ++k) ++offsets[tris[3 * t + k] + 1];
  for (std::size_t v = 0; v < num_vertices; ++v) offsets[v + 1] += offsets[v];
  std::vector<std::uint32_t> incident(offsets.back());
  {
    std::vector<std::uint32_t> fill(offsets.begin(), offsets.end() - 1);
    for (std::uint32_t t : valid)
      for (int k = 0; k < 3; ++k) incident[fill[tris[3 * t + k]]++] = t;
  }

  if (!closed_manifold_links(num_vertices, tris, offsets, incident, sets, comp_chi, st))
    general_links(num_vertices, tris, offsets, incident, sets, comp_chi, st);
  st.euler = (long long)st.num_used_vertices - (long long)st.num_edges + (long long)st.num_triangles;

  st.genus_defined = st.num_triangles > 0 && st.num_border_edges == 0 && st.num_overshared_edges == 0 &&
                     st.num_nonmanifold_vertices == 0;
  if (st.genus_defined) {
    for (std::size_t v = 0; v < num_vertices; ++v)
      if (used[v] && sets.find(std::uint32_t(v)) == v) {
        const long long g = (2 - comp_chi[v]) / 2;
        st.genus += g;
        if (g != 0) ++st.num_nonzero_genus_components;
      }
  }
  return st;
}

}  // namespace volmap
