// volmap/core/tet_mesh.hpp — the array-based half-face tet mesh (datastructure.md §2-§5).
//
// Convention block (read this first):
// - Tets are 4 vertex ids in the USER's order (never reordered); tv[4t+i] is local vertex i of t.
//   A VOLMAP-positive tet (v0,v1,v2,v3) has orient3d(v0,v1,v2,v3) > 0 (volmap-reference.md §1).
// - Half-face h = 4t+i is the face of t opposite local vertex i; its vertices in outward order (for a
//   positive tet) are kTetFace[i]: F0=(1,3,2) F1=(0,2,3) F2=(0,3,1) F3=(0,1,2) (local_tables.hpp).
// - opp[h] is the matching half-face 4t'+j of the neighbour (same vertices, opposite winding) or
//   kBoundary. opp[opp[h]] == h. tv[opp[h]] is the apex across the face.
// - v2h[v] is one half-face containing v, a boundary one whenever v is on the boundary, so
//   vertex_is_boundary(v) is O(1).
// - Edits never renumber untouched elements. Deleted tets become tombstones (tv[4t] = kInvalidIndex)
//   whose slots are reused by later edits (vertices deleted by replace_cavity likewise: v2h = kInvalidIndex);
//   compact() removes tombstones and returns old->new maps.
//   Loop over slots with num_tet_slots() and skip !tet_is_live(t) when tombstones may exist.
// - Caches (edge ids, vertex->tets CSR, boundary half-face list) are built on demand and tagged with
//   topology_version(); every topological edit bumps it. Using a cache never changes a result.
//   Caches are built lazily by const calls: call build_caches() before sharing a mesh across threads.
// - Navigation never allocates. Errors are thrown as volmap::Error (never printed, never asserted).
#pragma once

#include <volmap/core/ids.hpp>
#include <volmap/core/local_tables.hpp>
#include <volmap/core/mesh_data.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace volmap {

class PropertyRegistry;  // properties.hpp

// A read-only view over contiguous ids (a minimal span).
template <class T>
struct Span {
  const T* first = nullptr;
  std::size_t count = 0;
  const T* begin() const { return first; }
  const T* end() const { return first + count; }
  std::size_t size() const { return count; }
  bool empty() const { return count == 0; }
  const T& operator[](std::size_t i) const { return first[i]; }
};

// Old->new index maps returned by compact(); kInvalidIndex for removed elements.
// Half-faces map as 4*tet_old_to_new[h>>2] + (h&3).
struct CompactRemap {
  std::vector<std::uint32_t> vertex_old_to_new;
  std::vector<std::uint32_t> tet_old_to_new;
};

// One tet of a cavity fill (TetMesh::replace_cavity): four vertices, each a live vertex of the
// cavity or CavityTet::new_vertex(k), the k-th new vertex of the fill; and `parent`, a cavity tet whose
// label and tet property values the new tet takes (TetId::kInvalid: label 0 and the defaults).
struct CavityTet {
  static constexpr std::uint32_t kFirstNewVertex = 0xC0000000u;  // existing vertex ids stay below
  static constexpr VertexId new_vertex(std::uint32_t k) { return VertexId(kFirstNewVertex + k); }
  std::array<VertexId, 4> v;
  TetId parent = TetId::kInvalid;
};

// What replace_cavity made: the new tets (in the fill's order) and the new vertices (k-th = new_vertex(k)).
struct CavityReplacement {
  std::vector<TetId> tets;
  std::vector<VertexId> vertices;
};

// Result of check_invariants(): ok, or the first problem found in words.
struct InvariantReport {
  bool ok = true;
  std::string problem;
};

class TetMesh {
 public:
  static constexpr std::uint32_t kBoundary = kInvalidIndex;

  TetMesh();
  // Builds the half-face structure in linear time. Throws Error(BadInput) naming the offending
  // tet/face/vertex for: sizes not multiples of 3/4, more than 2^29 tets, ids out of range, a tet repeating a vertex,
  // a face shared by more than two tets, matched faces with equal winding (inconsistent
  // orientation), a vertex used by no tet.
  explicit TetMesh(const TetMeshData& data);
  TetMesh(const TetMesh& other);  // copies geometry/topology; properties stay with `other`
  // Properties attached to *this stay attached, reset to their default values at the new sizes.
  TetMesh& operator=(const TetMesh& other);
  TetMesh(TetMesh&&) noexcept;
  TetMesh& operator=(TetMesh&&) noexcept;
  ~TetMesh();

  // Live elements as flat arrays (tombstones dropped, survivors renumbered in slot order as
  // compact() would). Labels are kept (0 for elements created by edits, tets inherit the parent's).
  TetMeshData to_data() const;

  // ---- sizes -------------------------------------------------------------------------------
  std::size_t num_vertices() const { return num_live_vertices_; }
  std::size_t num_tets() const { return num_live_tets_; }
  std::size_t num_vertex_slots() const { return v2h_.size(); }
  std::size_t num_tet_slots() const { return tv_.size() / 4; }
  bool tet_is_live(TetId t) const { return tv_[4 * std::size_t(t.idx())] != kInvalidIndex; }
  bool vertex_is_live(VertexId v) const { return v2h_[v.idx()] != kInvalidIndex; }

  // ---- tets and half-faces ----------------------------------------------------------------
  VertexId tet_vertex(TetId t, int i) const { return VertexId(tv_[4 * std::size_t(t.idx()) + i]); }
  std::array<VertexId, 4> tet_vertices(TetId t) const {
    const std::uint32_t* p = &tv_[4 * std::size_t(t.idx())];
    return {VertexId(p[0]), VertexId(p[1]), VertexId(p[2]), VertexId(p[3])};
  }
  // Local index (0..3) of v in t, or -1.
  int tet_local_index(TetId t, VertexId v) const {
    const std::uint32_t* p = &tv_[4 * std::size_t(t.idx())];
    for (int i = 0; i < 4; ++i)
      if (p[i] == v.idx()) return i;
    return -1;
  }
  HalfFaceId half_face(TetId t, int i) const { return HalfFaceId(t, i); }
  // The matching half-face of the neighbour, or HalfFaceId::kInvalid on the boundary.
  HalfFaceId half_face_opposite(HalfFaceId h) const { return HalfFaceId(opp_[h.idx()]); }
  bool half_face_is_boundary(HalfFaceId h) const { return opp_[h.idx()] == kBoundary; }
  // The vertex of tet(h) not on h (its local index is h.local()).
  VertexId half_face_apex(HalfFaceId h) const { return VertexId(tv_[h.idx()]); }
  // The three vertices of h, outward (counter-clockwise from outside) for a positive tet.
  std::array<VertexId, 3> half_face_vertices(HalfFaceId h) const {
    const std::uint32_t* p = &tv_[4 * std::size_t(h.tet().idx())];
    const std::uint8_t* f = kTetFace[h.local()];
    return {VertexId(p[f[0]]), VertexId(p[f[1]]), VertexId(p[f[2]])};
  }
  // Neighbour across the face opposite local vertex i, or TetId::kInvalid.
  TetId tet_neighbor(TetId t, int i) const {
    const std::uint32_t o = opp_[4 * std::size_t(t.idx()) + i];
    return o == kBoundary ? TetId::kInvalid : TetId(o >> 2);
  }

  // ---- vertices ----------------------------------------------------------------------------
  const double* vertex_position(VertexId v) const { return &xyz_[3 * std::size_t(v.idx())]; }
  void set_vertex_position(VertexId v, const double p[3]) {
    double* q = &xyz_[3 * std::size_t(v.idx())];
    q[0] = p[0]; q[1] = p[1]; q[2] = p[2];
  }
  HalfFaceId vertex_half_face(VertexId v) const { return HalfFaceId(v2h_[v.idx()]); }
  bool vertex_is_boundary(VertexId v) const { return opp_[v2h_[v.idx()]] == kBoundary; }
  // Tets containing v, sorted by id, written into `out` (cleared first; reuses its capacity), found by
  // walking face neighbours around v from v2h (no cache involved; O(d) for d tets: past 48 tets the
  // walk marks visited tets in a per-thread buffer of one entry per tet slot, grown on demand and
  // reused). On a non-manifold ("pinched")
  // vertex, whose tets are not connected through faces containing v, this is only the cluster
  // holding v2h[v]; vertex_tets(v) (cache) lists all tets containing v.
  void vertex_star(VertexId v, std::vector<TetId>& out) const;
  // The same tets in walk order (no sort): for membership tests, where the order does not matter.
  void vertex_star_unsorted(VertexId v, std::vector<TetId>& out) const;

  // ---- raw arrays (read-only; layout in the convention block) -------------------------------
  const std::vector<std::uint32_t>& tet_vertex_array() const { return tv_; }
  const std::vector<std::uint32_t>& opposite_array() const { return opp_; }
  const std::vector<std::uint32_t>& vertex_half_face_array() const { return v2h_; }
  const std::vector<double>& positions() const { return xyz_; }
  const std::vector<std::int32_t>& vertex_labels() const { return vertex_labels_; }  // empty if none
  const std::vector<std::int32_t>& tet_labels() const { return tet_labels_; }        // empty if none

  // ---- edge stars (no allocation) -----------------------------------------------------------
  // Visits every tet around the edge (local a, local b) of tet t, starting at t, turning with
  // kTetCross; when the edge is on the boundary the walk continues from t the other way. The
  // visitor is f(TetId) or f(TetId, int local_a, int local_b) (locals of the edge's two vertices in
  // the visited tet). Returns true when the ring is closed (interior edge).
  template <class F>
  bool edge_star(TetId t, int a, int b, F&& f) const;
  // Same, in rotation order from one boundary face to the other for boundary edges (rewinds
  // first; costs a second walk on boundary edges only).
  template <class F>
  bool edge_star_ordered(TetId t, int a, int b, F&& f) const;
  // Number of tets around the edge.
  std::size_t edge_degree(TetId t, int a, int b) const {
    std::size_t n = 0;
    edge_star(t, a, b, [&n](TetId) { ++n; });
    return n;
  }
  // One tet containing both va and vb with their locals, or TetId::kInvalid when no edge (va,vb).
  TetId find_edge(VertexId va, VertexId vb, int* local_a, int* local_b) const;

  // ---- caches ------------------------------------------------------------------------------
  std::uint64_t topology_version() const { return topology_version_; }
  void build_caches() const;  // all of them, now
  void clear_caches() const;
  // Edge ids (cache): e_of_tet[6t+k] for local edge kTetEdge[k], edge_v[2e], one (6t+k) per edge.
  // An id names one edge star (fan of face-connected tets): on a mesh with a pinched (non-manifold)
  // edge, that vertex pair gets one id per fan. analyze_topology() reports such meshes.
  std::size_t num_edges() const;
  EdgeId tet_edge(TetId t, int k) const;
  std::array<VertexId, 2> edge_vertices(EdgeId e) const;
  // All edges as 2*num_edges() vertex ids (edge e = entries 2e, 2e+1), e.g. for Laplacian assembly.
  Span<VertexId> edge_vertex_array() const;
  // One (tet, local edge k) holding e.
  std::pair<TetId, int> edge_tet(EdgeId e) const;
  template <class F>
  bool edge_star(EdgeId e, F&& f) const {
    const auto tk = edge_tet(e);
    return edge_star(tk.first, kTetEdge[tk.second][0], kTetEdge[tk.second][1], std::forward<F>(f));
  }
  // Spans returned by the cache accessors below stay valid until the next edit or clear_caches().
  // Vertex -> tets CSR (cache), each list sorted by tet id.
  Span<TetId> vertex_tets(VertexId v) const;
  // Boundary half-faces, sorted (cache).
  Span<HalfFaceId> boundary_half_faces() const;
  bool edge_cache_current() const { return edge_cache_.version == topology_version_; }
  bool vertex_tets_cache_current() const { return vt_cache_.version == topology_version_; }
  bool boundary_cache_current() const { return bnd_cache_.version == topology_version_; }

  // Memory: the core arrays (tv, opp, v2h, xyz; labels and free lists separately) and caches.
  std::size_t core_bytes() const;
  std::size_t label_bytes() const;
  std::size_t cache_bytes() const;

  // ---- edits (ids of untouched elements never change) ---------------------------------------
  // Each returns the new vertex (position p, default vertex properties). Children of a split tet
  // inherit its tet properties and label; the parent's slot is reused by one child, the others
  // take free slots or append. Positivity is the caller's business: a child that replaces slot j by
  // p is positive iff p is strictly on vertex j's side (orient3d is affine in each argument).
  // Splits the edge (local a, local b) of t: every tet of its star becomes two.
  VertexId split_edge(TetId t, int a, int b, const double p[3]);
  // Same for the edge (va, vb); throws Error(Failed) when there is no such edge.
  VertexId split_edge(VertexId va, VertexId vb, const double p[3]);
  // Splits face h: each tet on it (1 on the boundary, else 2) becomes three.
  VertexId split_face(HalfFaceId h, const double p[3]);
  // Splits tet t into four around p.
  VertexId split_tet(TetId t, const double p[3]);
  // 2-3 flip of the interior face h: the two tets (a,b,c,d) + (a,b,c,e) become three around edge de.
  // can_*: topology allows it (the new edge does not exist yet) and the new tets are strictly
  // positive (exact) under coordinates xyz (3 per vertex slot; nullptr = the mesh's positions).
  bool can_flip_2_3(HalfFaceId h, const double* xyz = nullptr) const;
  // Throws Error(Failed) when the topology forbids the flip (boundary face, existing edge de);
  // geometry is not checked (use can_flip_2_3). Returns the three tets (two reused slots + one).
  std::array<TetId, 3> flip_2_3(HalfFaceId h);
  // 3-2 flip of the interior edge (local a, local b) of t of degree 3.
  bool can_flip_3_2(TetId t, int a, int b, const double* xyz = nullptr) const;
  std::array<TetId, 2> flip_3_2(TetId t, int a, int b);
  // Edge removal (the n -> 2n-4 flip, tet_mesh_edge_removal.cpp; n = 3 is the 3-2 flip) of the
  // interior edge (local a, local b) of t, va and vb its vertices. edge_ring lists the n vertices
  // around the edge in rotation order, oriented so that (ring[i], ring[i+1], vb, va) is an even
  // permutation of the tet holding them (positive for a positive mesh); it throws Error(Failed) for
  // a boundary edge. A triangulation of the ring polygon is n-2 triangles of ring positions
  // (i, j, k), i < j < k; each becomes the tets (ring[i], ring[j], ring[k], va) and
  // (ring[k], ring[j], ring[i], vb). can_remove_edge: the topology allows it (interior edge, the
  // triangles triangulate the polygon, no diagonal is an edge yet) and every new tet is strictly
  // positive (exact) under xyz (3 per vertex slot; nullptr = the mesh's positions).
  std::vector<VertexId> edge_ring(TetId t, int a, int b) const;
  bool can_remove_edge(TetId t, int a, int b, const std::vector<std::array<int, 3>>& triangles, const double* xyz = nullptr) const;
  // Throws Error(Failed) when the topology forbids it (geometry is not checked). Returns the 2n-4
  // new tets (fill order: the va tet then the vb tet of each triangle); they take the ring's slots
  // first, so n = 3 leaves one tombstone. Labels and tet properties: those of the ring tet
  // (ring[i], ring[i+1]) of each triangle's first corner.
  std::vector<TetId> remove_edge(TetId t, int a, int b, const std::vector<std::array<int, 3>>& triangles);
  // Cavity replacement (tet_mesh_cavity.cpp): the live tets `cavity` (normally a topological ball)
  // are replaced by the tets `fill`, over the cavity's vertices and new ones at `new_positions`
  // (3 doubles per new vertex, each used by some fill tet). The fill must close onto the cavity: every
  // face of a fill tet is shared with exactly one other fill tet (opposite winding) or is exactly one
  // boundary face of the cavity (same winding; it takes over that face's neighbour or its place on
  // the mesh boundary), and every cavity boundary face is covered so. A fill face inside the cavity
  // may not already be a face outside it. Fill tet k takes the slot of cavity[k] while there are
  // cavity slots; the rest take free slots or append; unused cavity slots become tombstones. Cavity
  // vertices the fill does not use (interior ones) are deleted. Labels and tet properties come from
  // each fill tet's parent, new vertices get the defaults. Anything else throws Error(Failed) and
  // leaves the mesh (and its properties) unchanged. Positivity is the caller's business.
  CavityReplacement replace_cavity(const std::vector<TetId>& cavity, const std::vector<CavityTet>& fill,
                                   const std::vector<double>& new_positions = {});
  // Removes tombstones; permutes every registered property and the labels. Survivors keep their
  // relative order.
  CompactRemap compact();
  std::size_t num_free_tet_slots() const { return free_tets_.size(); }

  // Structural check for tests and fuzzers: opp symmetric with equal vertex sets and opposite
  // windings, live tets reference live vertices only, free list == tombstones, v2h valid and
  // boundary-preferring, every live vertex used, and (check_positive) every live tet strictly
  // positive (exact orient3d).
  InvariantReport check_invariants(bool check_positive = false) const;

  PropertyRegistry& property_registry() const { return *properties_; }
  const std::shared_ptr<PropertyRegistry>& property_registry_shared() const { return properties_; }

 private:
  friend struct TetMeshEditor;
  int local_of(std::uint32_t t, std::uint32_t v) const {
    const std::uint32_t* p = &tv_[4 * std::size_t(t)];
    return p[0] == v ? 0 : p[1] == v ? 1 : p[2] == v ? 2 : 3;
  }
  void ensure_edge_cache() const;
  void ensure_vertex_tets_cache() const;
  void ensure_boundary_cache() const;
  std::uint32_t allocate_tet(std::uint32_t parent);
  std::uint32_t take_tet_slot();  // a free slot or a new one; no label, property or count update
  std::uint32_t allocate_vertex(const double p[3]);
  void free_tet(std::uint32_t t);
  void link(std::uint32_t h, std::uint32_t g) {
    opp_[h] = g;
    if (g != kBoundary) opp_[g] = h;
  }
  void refresh_v2h(const std::uint32_t* tets, std::size_t n);
  void edited() { ++topology_version_; }

  std::vector<std::uint32_t> tv_;   // 4 per tet slot
  std::vector<std::uint32_t> opp_;  // 4 per tet slot
  std::vector<std::uint32_t> v2h_;  // 1 per vertex slot (kInvalidIndex: deleted vertex)
  std::vector<double> xyz_;         // 3 per vertex slot
  std::vector<std::int32_t> vertex_labels_;  // empty, or 1 per vertex slot
  std::vector<std::int32_t> tet_labels_;     // empty, or 1 per tet slot
  std::vector<std::uint32_t> free_tets_;
  std::vector<std::uint32_t> free_vertices_;
  std::size_t num_live_tets_ = 0;
  std::size_t num_live_vertices_ = 0;
  std::uint64_t topology_version_ = 1;
  std::shared_ptr<PropertyRegistry> properties_;
  mutable std::vector<std::uint32_t> scratch_;  // edit work space (no per-edit allocation)

  struct EdgeCache {
    std::uint64_t version = 0;
    std::vector<EdgeId> e_of_tet;
    std::vector<VertexId> edge_v;
    std::vector<std::uint32_t> edge_tet;  // 6t+k
  };
  struct VertexTetsCache {
    std::uint64_t version = 0;
    std::vector<std::uint32_t> offsets;
    std::vector<TetId> tets;
  };
  struct BoundaryCache {
    std::uint64_t version = 0;
    std::vector<HalfFaceId> faces;
  };
  mutable EdgeCache edge_cache_;
  mutable VertexTetsCache vt_cache_;
  mutable BoundaryCache bnd_cache_;
};

// ---- inline edge-star walks ----------------------------------------------------------------

template <class F>
bool TetMesh::edge_star(TetId t0, int a0, int b0, F&& f) const {
  const std::uint32_t* tv = tv_.data();
  const std::uint32_t* opp = opp_.data();
  const std::uint32_t va = tv[4 * std::size_t(t0.idx()) + a0];
  const std::uint32_t vb = tv[4 * std::size_t(t0.idx()) + b0];
  auto visit = [&f](std::uint32_t t, int a, int b) {
    if constexpr (std::is_invocable_v<F, TetId, int, int>)
      f(TetId(t), a, b);
    else
      f(TetId(t));
  };
  std::uint32_t t = t0.idx();
  int a = a0, b = b0;
  for (;;) {
    visit(t, a, b);
    const std::uint32_t o = opp[4 * std::size_t(t) + kTetCross[a][b]];
    if (o == kBoundary) break;
    t = o >> 2;
    if (t == t0.idx()) return true;
    a = local_of(t, va);
    b = local_of(t, vb);
  }
  // Boundary edge: the other side of t0.
  t = t0.idx();
  a = a0;
  b = b0;
  for (;;) {
    const std::uint32_t o = opp[4 * std::size_t(t) + kTetCross[b][a]];
    if (o == kBoundary) return false;
    t = o >> 2;
    a = local_of(t, va);
    b = local_of(t, vb);
    visit(t, a, b);
  }
}

template <class F>
bool TetMesh::edge_star_ordered(TetId t0, int a0, int b0, F&& f) const {
  const std::uint32_t* opp = opp_.data();
  const std::uint32_t va = tv_[4 * std::size_t(t0.idx()) + a0];
  const std::uint32_t vb = tv_[4 * std::size_t(t0.idx()) + b0];
  std::uint32_t t = t0.idx();
  int a = a0, b = b0;
  for (;;) {  // rewind to the boundary (or around the closed ring back to t0)
    const std::uint32_t o = opp[4 * std::size_t(t) + kTetCross[b][a]];
    if (o == kBoundary) break;
    if ((o >> 2) == t0.idx()) break;
    t = o >> 2;
    a = local_of(t, va);
    b = local_of(t, vb);
  }
  if (t != t0.idx() && opp[4 * std::size_t(t) + kTetCross[b][a]] != kBoundary) {
    t = t0.idx(); a = a0; b = b0;  // closed ring: start at t0
  }
  return edge_star(TetId(t), a, b, std::forward<F>(f));
}

}  // namespace volmap
