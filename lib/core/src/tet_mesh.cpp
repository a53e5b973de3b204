// TetMesh: linear-time build from flat arrays, caches, edits, compaction, invariant checks.
// Conventions in tet_mesh.hpp (half-face 4t+i opposite local vertex i, outward faces kTetFace).
#include <volmap/core/tet_mesh.hpp>

#include <volmap/core/error.hpp>
#include <volmap/core/huge_pages.hpp>
#include <volmap/predicates.hpp>
#include <volmap/core/properties.hpp>

#include "face_grouping.hpp"

#include <algorithm>
#include <mutex>
#include <string>

namespace volmap {
namespace {

constexpr std::uint32_t kNone = kInvalidIndex;

[[noreturn]] void bad(const std::string& reason) { throw Error(ErrorKind::BadInput, reason); }
[[noreturn]] void failed(const std::string& reason) { throw Error(ErrorKind::Failed, reason); }

std::string triple(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  return "(" + std::to_string(a) + "," + std::to_string(b) + "," + std::to_string(c) + ")";
}

}  // namespace

TetMesh::TetMesh() : properties_(std::make_shared<PropertyRegistry>()) {}

TetMesh::~TetMesh() = default;

TetMesh::TetMesh(const TetMesh& o)
    : tv_(o.tv_), opp_(o.opp_), v2h_(o.v2h_), xyz_(o.xyz_), vertex_labels_(o.vertex_labels_),
      tet_labels_(o.tet_labels_), free_tets_(o.free_tets_), free_vertices_(o.free_vertices_),
      num_live_tets_(o.num_live_tets_), num_live_vertices_(o.num_live_vertices_),
      topology_version_(o.topology_version_), properties_(std::make_shared<PropertyRegistry>()) {}

TetMesh& TetMesh::operator=(const TetMesh& o) {
  if (this == &o) return *this;
  TetMesh copy(o);
  copy.properties_ = properties_;  // our properties stay attached to us...
  *this = std::move(copy);
  ++topology_version_;
  // ...and are reset to their default values at the new sizes (their old entries meant other elements).
  properties_->notify_compact(ElementKind::Vertex, {}, num_vertex_slots());
  properties_->notify_compact(ElementKind::Tet, {}, num_tet_slots());
  return *this;
}

TetMesh::TetMesh(TetMesh&&) noexcept = default;
TetMesh& TetMesh::operator=(TetMesh&&) noexcept = default;

TetMesh::TetMesh(const TetMeshData& data) : TetMesh() {
  if (data.xyz.size() % 3 != 0) bad("vertex coordinate array size " + std::to_string(data.xyz.size()) + " is not a multiple of 3");
  if (data.tets.size() % 4 != 0) bad("tet array size " + std::to_string(data.tets.size()) + " is not a multiple of 4");
  const std::size_t nv = data.num_vertices(), nt = data.num_tets();
  if (nt > detail::kMaxGroupedTets) bad("too many tets (" + std::to_string(nt) + " > 2^29)");
  if (nv >= kNone) bad("too many vertices (" + std::to_string(nv) + ")");
  if (!data.vertex_labels.empty() && data.vertex_labels.size() != nv)
    bad("vertex label count " + std::to_string(data.vertex_labels.size()) + " != vertex count " + std::to_string(nv));
  if (!data.tet_labels.empty() && data.tet_labels.size() != nt)
    bad("tet label count " + std::to_string(data.tet_labels.size()) + " != tet count " + std::to_string(nt));
  const std::uint32_t* tv = data.tets.data();
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* p = tv + 4 * t;
    for (int i = 0; i < 4; ++i) {
      if (p[i] >= nv)
        bad("tet " + std::to_string(t) + " references vertex " + std::to_string(p[i]) + " but there are " +
            std::to_string(nv) + " vertices");
      for (int j = 0; j < i; ++j)
        if (p[i] == p[j]) bad("tet " + std::to_string(t) + " repeats vertex " + std::to_string(p[i]));
    }
  }
  // The big arrays are mapped before their first touch (huge_pages.hpp).
  reserve_mapped(tv_, 4 * nt);
  tv_.assign(data.tets.begin(), data.tets.end());
  reserve_mapped(xyz_, 3 * nv);
  xyz_.assign(data.xyz.begin(), data.xyz.end());
  reserve_mapped(opp_, 4 * nt);
  opp_.assign(4 * nt, kBoundary);
  // Buckets are matched in parallel for big meshes; the reported error is the first one in
  // (smallest vertex, face) order, exactly as a serial pass would report it.
  std::mutex error_mutex;
  std::uint32_t error_vertex = kNone;
  std::string error;
  auto on_group = [&](std::uint32_t m, const std::uint64_t* keys, const std::uint32_t* g, std::size_t n) {
    if (n == 1) return;
    const std::uint32_t a = std::uint32_t(keys[0] >> 32), b = std::uint32_t(keys[0]);
    std::string why;
    const std::uint32_t h0 = detail::hf_of(g[0]), h1 = detail::hf_of(g[1]);
    if (n > 2) {
      std::string tets;
      for (std::size_t k = 0; k < n; ++k) tets += (k ? ", " : "") + std::to_string(detail::hf_of(g[k]) >> 2);
      why = "non-manifold face " + triple(m, a, b) + " is shared by " + std::to_string(n) + " tets (" + tets + ")";
    } else if (detail::parity_of(g[0]) == detail::parity_of(g[1])) {
      why = "inconsistent orientation: tets " + std::to_string(h0 >> 2) + " and " + std::to_string(h1 >> 2) +
            " share face " + triple(m, a, b) + " with the same winding";
    } else {
      opp_[h0] = h1;
      opp_[h1] = h0;
      return;
    }
    std::lock_guard<std::mutex> lock(error_mutex);
    if (m < error_vertex) {
      error_vertex = m;
      error = std::move(why);
    }
  };
  if (nt >= 200000)
    detail::group_faces<true>(tv, nt, nv, [](std::size_t) { return false; }, on_group);
  else
    detail::group_faces<false>(tv, nt, nv, [](std::size_t) { return false; }, on_group);
  if (error_vertex != kNone) bad(error);
  v2h_.assign(nv, kNone);
  for (std::size_t h = 0; h < 4 * nt; ++h) v2h_[tv_[h]] = std::uint32_t((h & ~std::size_t(3)) | ((h + 1) & 3));
  for (std::size_t h = 0; h < 4 * nt; ++h) {
    if (opp_[h] != kBoundary) continue;
    const std::uint8_t* f = kTetFace[h & 3];
    const std::uint32_t* p = &tv_[h & ~std::size_t(3)];
    v2h_[p[f[0]]] = v2h_[p[f[1]]] = v2h_[p[f[2]]] = std::uint32_t(h);
  }
  for (std::size_t v = 0; v < nv; ++v)
    if (v2h_[v] == kNone) bad("vertex " + std::to_string(v) + " is used by no tet");
  auto any_nonzero = [](const std::vector<std::int32_t>& l) {
    return std::any_of(l.begin(), l.end(), [](std::int32_t x) { return x != 0; });
  };
  if (any_nonzero(data.vertex_labels)) vertex_labels_ = data.vertex_labels;
  if (any_nonzero(data.tet_labels)) tet_labels_ = data.tet_labels;
  num_live_tets_ = nt;
  num_live_vertices_ = nv;
}

TetMeshData TetMesh::to_data() const {
  TetMeshData d;
  const std::size_t nvs = num_vertex_slots(), nts = num_tet_slots();
  std::vector<std::uint32_t> vmap(nvs, kNone);
  std::uint32_t nv = 0;
  for (std::size_t v = 0; v < nvs; ++v)
    if (v2h_[v] != kNone) vmap[v] = nv++;
  d.xyz.reserve(3 * std::size_t(nv));
  d.vertex_labels.reserve(nv);
  for (std::size_t v = 0; v < nvs; ++v) {
    if (vmap[v] == kNone) continue;
    d.xyz.insert(d.xyz.end(), &xyz_[3 * v], &xyz_[3 * v] + 3);
    d.vertex_labels.push_back(vertex_labels_.empty() ? 0 : vertex_labels_[v]);
  }
  d.tets.reserve(4 * num_live_tets_);
  d.tet_labels.reserve(num_live_tets_);
  for (std::size_t t = 0; t < nts; ++t) {
    if (tv_[4 * t] == kNone) continue;
    for (int i = 0; i < 4; ++i) d.tets.push_back(vmap[tv_[4 * t + i]]);
    d.tet_labels.push_back(tet_labels_.empty() ? 0 : tet_labels_[t]);
  }
  return d;
}

// ---- navigation helpers ---------------------------------------------------------------------

void TetMesh::vertex_star(VertexId v, std::vector<TetId>& out) const {
  vertex_star_unsorted(v, out);
  std::sort(out.begin(), out.end());
}

void TetMesh::vertex_star_unsorted(VertexId v, std::vector<TetId>& out) const {
  out.clear();
  const std::uint32_t h0 = v2h_[v.idx()];
  if (h0 == kNone) return;
  // Tets already queued: a linear search while the star is small, then a per-thread mark per tet
  // slot (a generation counter; the buffer only grows), so a star of d tets costs O(d).
  constexpr std::size_t kLinear = 48;
  thread_local std::vector<std::uint32_t> mark;
  thread_local std::uint32_t generation = 0;
  bool marking = false;
  auto start_marking = [&] {
    if (mark.size() < num_tet_slots()) mark.resize(num_tet_slots(), 0);
    if (++generation == 0) {
      std::fill(mark.begin(), mark.end(), 0u);
      generation = 1;
    }
    for (TetId t : out) mark[t.idx()] = generation;
    marking = true;
  };
  out.push_back(TetId(h0 >> 2));
  for (std::size_t q = 0; q < out.size(); ++q) {
    const std::uint32_t t = out[q].idx();
    const int lv = local_of(t, v.idx());
    for (int i = 0; i < 4; ++i) {
      if (i == lv) continue;
      const std::uint32_t o = opp_[4 * std::size_t(t) + i];
      if (o == kBoundary) continue;
      const TetId n(o >> 2);
      if (!marking && out.size() >= kLinear) start_marking();
      if (marking) {
        if (mark[n.idx()] == generation) continue;
        mark[n.idx()] = generation;
        out.push_back(n);
      } else if (std::find(out.begin(), out.end(), n) == out.end()) {
        out.push_back(n);
      }
    }
  }
}

// The tet of smallest id holding both (the first of the sorted star), found without sorting it.
TetId TetMesh::find_edge(VertexId va, VertexId vb, int* local_a, int* local_b) const {
  thread_local std::vector<TetId> star;
  vertex_star_unsorted(va, star);
  TetId found = TetId::kInvalid;
  for (TetId t : star)
    if ((!found.is_valid() || t.idx() < found.idx()) && tet_local_index(t, vb) >= 0) found = t;
  if (found.is_valid()) {
    if (local_a) *local_a = tet_local_index(found, va);
    if (local_b) *local_b = tet_local_index(found, vb);
  }
  return found;
}

// ---- caches ---------------------------------------------------------------------------------

void TetMesh::ensure_edge_cache() const {
  if (edge_cache_.version == topology_version_) return;
  EdgeCache& c = edge_cache_;
  const std::size_t nts = num_tet_slots();
  c.e_of_tet.assign(6 * nts, EdgeId::kInvalid);
  c.edge_v.clear();
  c.edge_tet.clear();
  // Euler (V - E + F - T = 1 for a ball, F = (4T + boundary faces)/2) gives the edge count up to a
  // few: reserve it so the cache carries no growth slack.
  std::size_t boundary_faces = 0;
  for (std::size_t h = 0; h < opp_.size(); ++h) boundary_faces += opp_[h] == kBoundary;
  boundary_faces -= 4 * free_tets_.size();
  const std::size_t expect = num_live_vertices_ + num_live_tets_ + boundary_faces / 2 + 16;
  c.edge_v.reserve(2 * expect);
  c.edge_tet.reserve(expect);
  std::uint32_t ne = 0;
  for (std::size_t t = 0; t < nts; ++t) {
    if (tv_[4 * t] == kNone) continue;
    for (int k = 0; k < 6; ++k) {
      if (c.e_of_tet[6 * t + k].is_valid()) continue;
      const EdgeId e(ne++);
      const int a = kTetEdge[k][0], b = kTetEdge[k][1];
      c.edge_v.push_back(VertexId(tv_[4 * t + a]));
      c.edge_v.push_back(VertexId(tv_[4 * t + b]));
      c.edge_tet.push_back(std::uint32_t(6 * t + k));
      edge_star(TetId(std::uint32_t(t)), a, b, [&](TetId s, int la, int lb) {
        c.e_of_tet[6 * std::size_t(s.idx()) + kTetEdgeOf[la][lb]] = e;
      });
    }
  }
  c.version = topology_version_;
}

void TetMesh::ensure_vertex_tets_cache() const {
  if (vt_cache_.version == topology_version_) return;
  VertexTetsCache& c = vt_cache_;
  const std::size_t nvs = num_vertex_slots(), nts = num_tet_slots();
  c.offsets.assign(nvs + 2, 0);
  for (std::size_t t = 0; t < nts; ++t) {
    if (tv_[4 * t] == kNone) continue;
    for (int i = 0; i < 4; ++i) ++c.offsets[std::size_t(tv_[4 * t + i]) + 2];
  }
  for (std::size_t v = 2; v < c.offsets.size(); ++v) c.offsets[v] += c.offsets[v - 1];
  c.tets.resize(c.offsets.back());
  for (std::size_t t = 0; t < nts; ++t) {
    if (tv_[4 * t] == kNone) continue;
    for (int i = 0; i < 4; ++i) c.tets[c.offsets[std::size_t(tv_[4 * t + i]) + 1]++] = TetId(std::uint32_t(t));
  }
  c.offsets.pop_back();
  c.version = topology_version_;
}

void TetMesh::ensure_boundary_cache() const {
  if (bnd_cache_.version == topology_version_) return;
  bnd_cache_.faces.clear();
  for (std::size_t h = 0; h < opp_.size(); ++h)
    if (opp_[h] == kBoundary && tv_[h & ~std::size_t(3)] != kNone) bnd_cache_.faces.push_back(HalfFaceId(std::uint32_t(h)));
  bnd_cache_.version = topology_version_;
}

void TetMesh::build_caches() const {
  ensure_edge_cache();
  ensure_vertex_tets_cache();
  ensure_boundary_cache();
}

void TetMesh::clear_caches() const {
  edge_cache_ = EdgeCache();
  vt_cache_ = VertexTetsCache();
  bnd_cache_ = BoundaryCache();
}

std::size_t TetMesh::num_edges() const {
  ensure_edge_cache();
  return edge_cache_.edge_tet.size();
}
EdgeId TetMesh::tet_edge(TetId t, int k) const {
  ensure_edge_cache();
  return edge_cache_.e_of_tet[6 * std::size_t(t.idx()) + k];
}
std::array<VertexId, 2> TetMesh::edge_vertices(EdgeId e) const {
  ensure_edge_cache();
  return {edge_cache_.edge_v[2 * std::size_t(e.idx())], edge_cache_.edge_v[2 * std::size_t(e.idx()) + 1]};
}
Span<VertexId> TetMesh::edge_vertex_array() const {
  ensure_edge_cache();
  return {edge_cache_.edge_v.data(), edge_cache_.edge_v.size()};
}
std::pair<TetId, int> TetMesh::edge_tet(EdgeId e) const {
  ensure_edge_cache();
  const std::uint32_t x = edge_cache_.edge_tet[e.idx()];
  return {TetId(x / 6), int(x % 6)};
}
Span<TetId> TetMesh::vertex_tets(VertexId v) const {
  ensure_vertex_tets_cache();
  const std::uint32_t b = vt_cache_.offsets[v.idx()], e = vt_cache_.offsets[std::size_t(v.idx()) + 1];
  return {vt_cache_.tets.data() + b, std::size_t(e - b)};
}
Span<HalfFaceId> TetMesh::boundary_half_faces() const {
  ensure_boundary_cache();
  return {bnd_cache_.faces.data(), bnd_cache_.faces.size()};
}

std::size_t TetMesh::core_bytes() const {
  return tv_.capacity() * 4 + opp_.capacity() * 4 + v2h_.capacity() * 4 + xyz_.capacity() * 8;
}
std::size_t TetMesh::label_bytes() const { return vertex_labels_.capacity() * 4 + tet_labels_.capacity() * 4; }
std::size_t TetMesh::cache_bytes() const {
  return edge_cache_.e_of_tet.capacity() * 4 + edge_cache_.edge_v.capacity() * 4 + edge_cache_.edge_tet.capacity() * 4 +
         vt_cache_.offsets.capacity() * 4 + vt_cache_.tets.capacity() * 4 + bnd_cache_.faces.capacity() * 4;
}

// ---- edits ----------------------------------------------------------------------------------

std::uint32_t TetMesh::take_tet_slot() {
  if (!free_tets_.empty()) {
    const std::uint32_t t = free_tets_.back();
    free_tets_.pop_back();
    return t;
  }
  const std::uint32_t t = std::uint32_t(num_tet_slots());
  if (t >= (std::uint32_t(1) << 30)) failed("tet id space exhausted (2^30 tets)");
  tv_.insert(tv_.end(), 4, kNone);
  opp_.insert(opp_.end(), 4, kBoundary);
  if (!tet_labels_.empty()) tet_labels_.push_back(0);
  return t;
}

std::uint32_t TetMesh::allocate_tet(std::uint32_t parent) {
  const std::uint32_t t = take_tet_slot();
  if (!tet_labels_.empty()) tet_labels_[t] = parent != kNone ? tet_labels_[parent] : 0;
  properties_->notify_add(ElementKind::Tet, t, parent);
  ++num_live_tets_;
  return t;
}

std::uint32_t TetMesh::allocate_vertex(const double p[3]) {
  std::uint32_t v;
  if (!free_vertices_.empty()) {
    v = free_vertices_.back();
    free_vertices_.pop_back();
    if (!vertex_labels_.empty()) vertex_labels_[v] = 0;
  } else {
    v = std::uint32_t(num_vertex_slots());
    if (v == kNone - 1) failed("vertex id space exhausted");
    v2h_.push_back(kNone);
    xyz_.insert(xyz_.end(), 3, 0.0);
    if (!vertex_labels_.empty()) vertex_labels_.push_back(0);
  }
  xyz_[3 * std::size_t(v)] = p[0];
  xyz_[3 * std::size_t(v) + 1] = p[1];
  xyz_[3 * std::size_t(v) + 2] = p[2];
  properties_->notify_add(ElementKind::Vertex, v, kNone);
  ++num_live_vertices_;
  return v;
}

void TetMesh::free_tet(std::uint32_t t) {
  for (int i = 0; i < 4; ++i) {
    tv_[4 * std::size_t(t) + i] = kNone;
    opp_[4 * std::size_t(t) + i] = kBoundary;
  }
  free_tets_.push_back(t);
  --num_live_tets_;
}

// Re-establishes v2h (valid, boundary-preferring) for the vertices of the given (modified) tets.
// Half-faces outside them keep their boundary status through every edit, so only these vertices
// can hold a stale v2h.
void TetMesh::refresh_v2h(const std::uint32_t* tets, std::size_t n) {
  auto holds = [this](std::uint32_t h, std::uint32_t v) {
    if (h == kNone) return false;
    const std::uint32_t* p = &tv_[4 * std::size_t(h >> 2)];
    if (p[0] == kNone || p[h & 3] == v) return false;
    return p[0] == v || p[1] == v || p[2] == v || p[3] == v;
  };
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t t = tets[k];
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t h = 4 * t + i;
      if (opp_[h] != kBoundary) continue;
      for (int j = 0; j < 3; ++j) {
        const std::uint32_t v = tv_[4 * std::size_t(t) + kTetFace[i][j]];
        const std::uint32_t cur = v2h_[v];
        if (!(holds(cur, v) && opp_[cur] == kBoundary)) v2h_[v] = h;
      }
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t t = tets[k];
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t v = tv_[4 * std::size_t(t) + i];
      if (!holds(v2h_[v], v)) v2h_[v] = 4 * t + ((i + 1) & 3);
    }
  }
}

namespace {
void check_tet_edge(const TetMesh& m, TetId t, int a, int b, const char* what) {
  if (t.idx() >= m.num_tet_slots() || !m.tet_is_live(t)) failed(std::string(what) + ": tet " + std::to_string(t.idx()) + " is not live");
  if (a < 0 || a > 3 || b < 0 || b > 3 || a == b) failed(std::string(what) + ": bad local edge (" + std::to_string(a) + "," + std::to_string(b) + ")");
}
}  // namespace

VertexId TetMesh::split_edge(TetId t0, int a0, int b0, const double p[3]) {
  check_tet_edge(*this, t0, a0, b0, "split_edge");
  // scratch_: k triples (tet, la, lb), then k child ids, then the 2k modified tets.
  scratch_.clear();
  edge_star(t0, a0, b0, [this](TetId s, int la, int lb) {
    scratch_.push_back(s.idx());
    scratch_.push_back(std::uint32_t(la));
    scratch_.push_back(std::uint32_t(lb));
  });
  const std::size_t k = scratch_.size() / 3;
  const std::uint32_t w = allocate_vertex(p);
  for (std::size_t j = 0; j < k; ++j) {
    const std::uint32_t s = scratch_[3 * j];
    const int la = int(scratch_[3 * j + 1]), lb = int(scratch_[3 * j + 2]);
    const std::uint32_t B = allocate_tet(s);
    scratch_.push_back(B);
    for (int i = 0; i < 4; ++i) tv_[4 * std::size_t(B) + i] = tv_[4 * std::size_t(s) + i];
    tv_[4 * std::size_t(B) + la] = w;  // B: va -> w
    link(4 * B + la, opp_[4 * std::size_t(s) + la]);  // B inherits the face opposite va
    link(4 * s + la, 4 * B + lb);                      // new inner face (w, c, d)
    tv_[4 * std::size_t(s) + lb] = w;                  // A (= s): vb -> w
  }
  for (std::size_t j = 0; j < k; ++j) {
    const std::uint32_t s = scratch_[3 * j];
    const int la = int(scratch_[3 * j + 1]), lb = int(scratch_[3 * j + 2]);
    const std::uint32_t B = scratch_[3 * k + j];
    for (int c = 0; c < 4; ++c) {
      if (c == la || c == lb) continue;
      const std::uint32_t o = opp_[4 * std::size_t(s) + c];  // ring face: A keeps it as is
      if (o == kBoundary) {
        opp_[4 * std::size_t(B) + c] = kBoundary;
        continue;
      }
      std::size_t jn = 0;
      while (jn < k && scratch_[3 * jn] != (o >> 2)) ++jn;
      if (jn == k) failed("split_edge: ring face of tet " + std::to_string(s) + " leaves the edge star (corrupt mesh)");
      opp_[4 * std::size_t(B) + c] = 4 * scratch_[3 * k + jn] + (o & 3);
    }
  }
  for (std::size_t j = 0; j < k; ++j) scratch_.push_back(scratch_[3 * j]);
  refresh_v2h(scratch_.data() + 3 * k, 2 * k);
  edited();
  return VertexId(w);
}

VertexId TetMesh::split_edge(VertexId va, VertexId vb, const double p[3]) {
  if (va.idx() >= num_vertex_slots() || vb.idx() >= num_vertex_slots() || !vertex_is_live(va) || !vertex_is_live(vb))
    failed("split_edge: vertex not live");
  int a = -1, b = -1;
  const TetId t = find_edge(va, vb, &a, &b);
  if (!t.is_valid()) failed("split_edge: no edge (" + std::to_string(va.idx()) + "," + std::to_string(vb.idx()) + ")");
  return split_edge(t, a, b, p);
}

VertexId TetMesh::split_face(HalfFaceId h, const double p[3]) {
  if (h.tet().idx() >= num_tet_slots() || !tet_is_live(h.tet())) failed("split_face: half-face " + std::to_string(h.idx()) + " is not live");
  struct Side {
    std::uint32_t t;
    int fi;
    std::uint32_t tv[4], opp[4];
    std::uint32_t child[4];
  } sides[2];
  int ns = 1;
  sides[0].t = h.tet().idx();
  sides[0].fi = h.local();
  const std::uint32_t o = opp_[h.idx()];
  if (o != kBoundary) {
    ns = 2;
    sides[1].t = o >> 2;
    sides[1].fi = int(o & 3);
  }
  for (int s = 0; s < ns; ++s)
    for (int i = 0; i < 4; ++i) {
      sides[s].tv[i] = tv_[4 * std::size_t(sides[s].t) + i];
      sides[s].opp[i] = opp_[4 * std::size_t(sides[s].t) + i];
    }
  const std::uint32_t w = allocate_vertex(p);
  scratch_.clear();
  for (int s = 0; s < ns; ++s) {
    Side& S = sides[s];
    bool first = true;
    for (int j = 0; j < 4; ++j) {
      if (j == S.fi) { S.child[j] = kNone; continue; }
      S.child[j] = first ? S.t : allocate_tet(S.t);
      first = false;
      scratch_.push_back(S.child[j]);
      for (int i = 0; i < 4; ++i) tv_[4 * std::size_t(S.child[j]) + i] = S.tv[i];
      tv_[4 * std::size_t(S.child[j]) + j] = w;
    }
  }
  for (int s = 0; s < ns; ++s) {
    Side& S = sides[s];
    for (int j = 0; j < 4; ++j) {
      if (j == S.fi) continue;
      const std::uint32_t c = S.child[j];
      link(4 * c + j, S.opp[j]);  // outer face inherited by slot
      for (int k = 0; k < 4; ++k)
        if (k != S.fi && k != j) opp_[4 * std::size_t(c) + k] = 4 * S.child[k] + j;
      if (ns == 1) {
        opp_[4 * std::size_t(c) + S.fi] = kBoundary;
      } else {
        const Side& T = sides[1 - s];
        int jt = 0;
        while (jt < 4 && (jt == T.fi || T.tv[jt] != S.tv[j])) ++jt;
        if (jt == 4) failed("split_face: the two sides of face " + std::to_string(h.idx()) + " disagree (corrupt mesh)");
        opp_[4 * std::size_t(c) + S.fi] = 4 * T.child[jt] + T.fi;
      }
    }
  }
  refresh_v2h(scratch_.data(), scratch_.size());
  edited();
  return VertexId(w);
}

VertexId TetMesh::split_tet(TetId t, const double p[3]) {
  if (t.idx() >= num_tet_slots() || !tet_is_live(t)) failed("split_tet: tet " + std::to_string(t.idx()) + " is not live");
  std::uint32_t otv[4], oopp[4], child[4];
  for (int i = 0; i < 4; ++i) {
    otv[i] = tv_[4 * std::size_t(t.idx()) + i];
    oopp[i] = opp_[4 * std::size_t(t.idx()) + i];
  }
  const std::uint32_t w = allocate_vertex(p);
  for (int j = 0; j < 4; ++j) {
    child[j] = j == 0 ? t.idx() : allocate_tet(t.idx());
    for (int i = 0; i < 4; ++i) tv_[4 * std::size_t(child[j]) + i] = otv[i];
    tv_[4 * std::size_t(child[j]) + j] = w;
  }
  for (int j = 0; j < 4; ++j) {
    link(4 * child[j] + j, oopp[j]);
    for (int k = 0; k < 4; ++k)
      if (k != j) opp_[4 * std::size_t(child[j]) + k] = 4 * child[k] + j;
  }
  refresh_v2h(child, 4);
  edited();
  return VertexId(w);
}

namespace {
const double* pos(const double* xyz, std::uint32_t v) { return xyz + 3 * std::size_t(v); }
}  // namespace

bool TetMesh::can_flip_2_3(HalfFaceId h, const double* xyz) const {
  if (h.tet().idx() >= num_tet_slots() || !tet_is_live(h.tet())) return false;
  const std::uint32_t o = opp_[h.idx()];
  if (o == kBoundary) return false;
  const std::uint32_t t = h.tet().idx();
  const std::uint32_t d = tv_[h.idx()], e = tv_[o];
  if (d == e) return false;
  if (find_edge(VertexId(d), VertexId(e), nullptr, nullptr).is_valid()) return false;
  if (!xyz) xyz = xyz_.data();
  const std::uint32_t* p = &tv_[4 * std::size_t(t)];
  for (int j = 0; j < 4; ++j) {
    if (j == h.local()) continue;
    const double* q[4];
    for (int i = 0; i < 4; ++i) q[i] = pos(xyz, i == j ? e : p[i]);
    if (orient3d(q[0], q[1], q[2], q[3]) <= 0) return false;
  }
  return true;
}

std::array<TetId, 3> TetMesh::flip_2_3(HalfFaceId h) {
  if (h.tet().idx() >= num_tet_slots() || !tet_is_live(h.tet())) failed("flip_2_3: half-face " + std::to_string(h.idx()) + " is not live");
  const std::uint32_t o = opp_[h.idx()];
  if (o == kBoundary) failed("flip_2_3: half-face " + std::to_string(h.idx()) + " is on the boundary");
  const std::uint32_t t = h.tet().idx(), t2 = o >> 2;
  const int fi = h.local();
  std::uint32_t otv[4], oopp[4], otv2[4], oopp2[4];
  for (int i = 0; i < 4; ++i) {
    otv[i] = tv_[4 * std::size_t(t) + i];
    oopp[i] = opp_[4 * std::size_t(t) + i];
    otv2[i] = tv_[4 * std::size_t(t2) + i];
    oopp2[i] = opp_[4 * std::size_t(t2) + i];
  }
  const std::uint32_t d = otv[fi], e = otv2[o & 3];
  if (d == e) failed("flip_2_3: tets " + std::to_string(t) + " and " + std::to_string(t2) + " have the same vertices");
  if (find_edge(VertexId(d), VertexId(e), nullptr, nullptr).is_valid())
    failed("flip_2_3: edge (" + std::to_string(d) + "," + std::to_string(e) + ") already exists");
  std::uint32_t child[4] = {kNone, kNone, kNone, kNone};
  int made = 0;
  for (int j = 0; j < 4; ++j) {
    if (j == fi) continue;
    child[j] = made == 0 ? t : made == 1 ? t2 : allocate_tet(t);
    ++made;
  }
  for (int j = 0; j < 4; ++j) {
    if (j == fi) continue;
    for (int i = 0; i < 4; ++i) tv_[4 * std::size_t(child[j]) + i] = otv[i];
    tv_[4 * std::size_t(child[j]) + j] = e;
  }
  for (int j = 0; j < 4; ++j) {
    if (j == fi) continue;
    const std::uint32_t c = child[j];
    link(4 * c + j, oopp[j]);  // (d, face minus v_j): t's face opposite v_j
    int j2 = 0;
    while (otv2[j2] != otv[j]) ++j2;
    link(4 * c + fi, oopp2[j2]);  // (e, face minus v_j): t2's face opposite v_j
    for (int k = 0; k < 4; ++k)
      if (k != fi && k != j) opp_[4 * std::size_t(c) + k] = 4 * child[k] + j;
  }
  std::array<TetId, 3> out;
  std::uint32_t mod[3];
  int n = 0;
  for (int j = 0; j < 4; ++j)
    if (j != fi) { out[n] = TetId(child[j]); mod[n++] = child[j]; }
  refresh_v2h(mod, 3);
  edited();
  return out;
}

namespace {
// The ring of an edge of degree 3: tets and locals (a = local of va, b = local of vb).
struct Ring3 {
  std::uint32_t t[3];
  int a[3], b[3];
};
}  // namespace

bool TetMesh::can_flip_3_2(TetId t, int a, int b, const double* xyz) const {
  if (t.idx() >= num_tet_slots() || !tet_is_live(t) || a < 0 || a > 3 || b < 0 || b > 3 || a == b) return false;
  Ring3 r;
  int n = 0;
  const bool closed = edge_star(t, a, b, [&](TetId s, int la, int lb) {
    if (n < 3) { r.t[n] = s.idx(); r.a[n] = la; r.b[n] = lb; }
    ++n;
  });
  if (!closed || n != 3) return false;
  const std::uint32_t* p = &tv_[4 * std::size_t(t.idx())];
  std::uint32_t z = kNone;
  for (int i = 0; i < 4; ++i) {
    const std::uint32_t v = tv_[4 * std::size_t(r.t[1]) + i];
    if (v != p[0] && v != p[1] && v != p[2] && v != p[3]) z = v;
  }
  if (z == kNone) return false;
  // The triangle (x, y, z) must not exist yet: no tet other than the ring holds x, y and z.
  int cx = -1, cy = -1;
  for (int i = 0; i < 4; ++i)
    if (i != a && i != b) (cx < 0 ? cx : cy) = i;
  thread_local std::vector<TetId> star;
  vertex_star_unsorted(VertexId(p[cx]), star);
  for (TetId s : star)
    if (tet_local_index(s, VertexId(p[cy])) >= 0 && tet_local_index(s, VertexId(z)) >= 0) return false;
  if (!xyz) xyz = xyz_.data();
  for (int rep = 0; rep < 2; ++rep) {  // N_d = t with vb -> z, N_e = t with va -> z
    const double* q[4];
    for (int i = 0; i < 4; ++i) q[i] = pos(xyz, i == (rep == 0 ? b : a) ? z : p[i]);
    if (orient3d(q[0], q[1], q[2], q[3]) <= 0) return false;
  }
  return true;
}

std::array<TetId, 2> TetMesh::flip_3_2(TetId t, int a, int b) {
  check_tet_edge(*this, t, a, b, "flip_3_2");
  Ring3 r;
  int n = 0;
  const bool closed = edge_star(t, a, b, [&](TetId s, int la, int lb) {
    if (n < 3) { r.t[n] = s.idx(); r.a[n] = la; r.b[n] = lb; }
    ++n;
  });
  if (!closed || n != 3) failed("flip_3_2: the edge is on the boundary or its degree is not 3");
  std::uint32_t p[4];
  for (int i = 0; i < 4; ++i) p[i] = tv_[4 * std::size_t(t.idx()) + i];
  std::uint32_t z = kNone;
  for (int i = 0; i < 4; ++i) {
    const std::uint32_t v = tv_[4 * std::size_t(r.t[1]) + i];
    if (v != p[0] && v != p[1] && v != p[2] && v != p[3]) z = v;
  }
  if (z == kNone) failed("flip_3_2: degenerate ring around the edge");
  int cx = -1, cy = -1;
  for (int i = 0; i < 4; ++i)
    if (i != a && i != b) (cx < 0 ? cx : cy) = i;
  {
    thread_local std::vector<TetId> star;
    vertex_star_unsorted(VertexId(p[cx]), star);
    for (TetId s : star)
      if (tet_local_index(s, VertexId(p[cy])) >= 0 && tet_local_index(s, VertexId(z)) >= 0)
        failed("flip_3_2: triangle " + triple(p[cx], p[cy], z) + " already exists");
  }
  // The ring tets holding (y, z) and (x, z) (both hold the edge and z).
  int ryz = -1, rxz = -1;
  for (int q = 1; q < 3; ++q) {
    if (tet_local_index(TetId(r.t[q]), VertexId(p[cy])) >= 0) ryz = q;
    else rxz = q;
  }
  if (ryz < 0 || rxz < 0) failed("flip_3_2: degenerate ring around the edge");
  auto opp_of = [this](std::uint32_t tt, int i) { return opp_[4 * std::size_t(tt) + i]; };
  // External half-faces, read before anything is rewritten.
  const std::uint32_t e_d_xy = opp_of(r.t[0], b);                   // (d,x,y): t's face opposite e
  const std::uint32_t e_e_xy = opp_of(r.t[0], a);                   // (e,x,y): t's face opposite d
  const std::uint32_t e_d_yz = opp_of(r.t[ryz], r.b[ryz]);          // (d,y,z)
  const std::uint32_t e_e_yz = opp_of(r.t[ryz], r.a[ryz]);          // (e,y,z)
  const std::uint32_t e_d_xz = opp_of(r.t[rxz], r.b[rxz]);          // (d,x,z)
  const std::uint32_t e_e_xz = opp_of(r.t[rxz], r.a[rxz]);          // (e,x,z)
  const std::uint32_t Nd = r.t[0], Ne = r.t[1], dead = r.t[2];
  free_tet(dead);
  for (int i = 0; i < 4; ++i) {
    tv_[4 * std::size_t(Nd) + i] = p[i];
    tv_[4 * std::size_t(Ne) + i] = p[i];
  }
  tv_[4 * std::size_t(Nd) + b] = z;  // N_d: e -> z
  tv_[4 * std::size_t(Ne) + a] = z;  // N_e: d -> z
  opp_[4 * std::size_t(Nd) + a] = 4 * Ne + b;  // (z,x,y)
  opp_[4 * std::size_t(Ne) + b] = 4 * Nd + a;
  link(4 * Nd + b, e_d_xy);
  link(4 * Nd + cx, e_d_yz);  // face without x: (d, y, z)
  link(4 * Nd + cy, e_d_xz);  // face without y: (d, x, z)
  link(4 * Ne + a, e_e_xy);
  link(4 * Ne + cx, e_e_yz);
  link(4 * Ne + cy, e_e_xz);
  const std::uint32_t mod[2] = {Nd, Ne};
  refresh_v2h(mod, 2);
  edited();
  return {TetId(Nd), TetId(Ne)};
}

CompactRemap TetMesh::compact() {
  CompactRemap r;
  const std::size_t nvs = num_vertex_slots(), nts = num_tet_slots();
  r.vertex_old_to_new.assign(nvs, kNone);
  r.tet_old_to_new.assign(nts, kNone);
  std::uint32_t nv = 0, nt = 0;
  for (std::size_t v = 0; v < nvs; ++v)
    if (v2h_[v] != kNone) r.vertex_old_to_new[v] = nv++;
  for (std::size_t t = 0; t < nts; ++t)
    if (tv_[4 * t] != kNone) r.tet_old_to_new[t] = nt++;
  const auto& vm = r.vertex_old_to_new;
  const auto& tm = r.tet_old_to_new;
  auto map_h = [&tm](std::uint32_t h) { return h == kNone ? kNone : 4 * tm[h >> 2] + (h & 3); };
  for (std::size_t t = 0; t < nts; ++t) {
    if (tm[t] == kNone) continue;
    for (int i = 0; i < 4; ++i) {
      tv_[4 * std::size_t(tm[t]) + i] = vm[tv_[4 * t + i]];
      opp_[4 * std::size_t(tm[t]) + i] = map_h(opp_[4 * t + i]);
    }
    if (!tet_labels_.empty()) tet_labels_[tm[t]] = tet_labels_[t];
  }
  for (std::size_t v = 0; v < nvs; ++v) {
    if (vm[v] == kNone) continue;
    v2h_[vm[v]] = map_h(v2h_[v]);
    for (int c = 0; c < 3; ++c) xyz_[3 * std::size_t(vm[v]) + c] = xyz_[3 * v + c];
    if (!vertex_labels_.empty()) vertex_labels_[vm[v]] = vertex_labels_[v];
  }
  tv_.resize(4 * std::size_t(nt));
  opp_.resize(4 * std::size_t(nt));
  v2h_.resize(nv);
  xyz_.resize(3 * std::size_t(nv));
  if (!tet_labels_.empty()) tet_labels_.resize(nt);
  if (!vertex_labels_.empty()) vertex_labels_.resize(nv);
  free_tets_.clear();
  free_vertices_.clear();
  properties_->notify_compact(ElementKind::Vertex, vm, nv);
  properties_->notify_compact(ElementKind::Tet, tm, nt);
  edited();
  return r;
}

InvariantReport TetMesh::check_invariants(bool check_positive) const {
  InvariantReport rep;
  auto fail = [&rep](std::string why) {
    rep.ok = false;
    rep.problem = std::move(why);
    return rep;
  };
  const std::size_t nvs = num_vertex_slots(), nts = num_tet_slots();
  if (opp_.size() != tv_.size() || tv_.size() % 4 || xyz_.size() != 3 * nvs) return fail("array sizes disagree");
  if (!tet_labels_.empty() && tet_labels_.size() != nts) return fail("tet label array size");
  if (!vertex_labels_.empty() && vertex_labels_.size() != nvs) return fail("vertex label array size");
  std::vector<char> dead_listed(nts, 0);
  for (std::uint32_t t : free_tets_) {
    if (t >= nts || tv_[4 * std::size_t(t)] != kNone) return fail("free list holds live tet " + std::to_string(t));
    if (dead_listed[t]) return fail("free list holds tet " + std::to_string(t) + " twice");
    dead_listed[t] = 1;
  }
  std::size_t live_t = 0, live_v = 0;
  std::vector<char> used(nvs, 0), on_boundary(nvs, 0);
  for (std::size_t t = 0; t < nts; ++t) {
    const std::uint32_t* p = &tv_[4 * t];
    if (p[0] == kNone) {
      if (!dead_listed[t]) return fail("tombstone " + std::to_string(t) + " is not on the free list");
      for (int i = 0; i < 4; ++i)
        if (p[i] != kNone) return fail("tombstone " + std::to_string(t) + " keeps vertex ids");
      continue;
    }
    ++live_t;
    for (int i = 0; i < 4; ++i) {
      if (p[i] >= nvs || v2h_[p[i]] == kNone) return fail("tet " + std::to_string(t) + " references dead or missing vertex " + std::to_string(p[i]));
      for (int j = 0; j < i; ++j)
        if (p[i] == p[j]) return fail("tet " + std::to_string(t) + " repeats a vertex");
      used[p[i]] = 1;
    }
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t h = std::uint32_t(4 * t + i), g = opp_[h];
      const std::uint8_t* f = kTetFace[i];
      if (g == kBoundary) {
        for (int k = 0; k < 3; ++k) on_boundary[p[f[k]]] = 1;
        continue;
      }
      if (g >= opp_.size() || tv_[g & ~3u] == kNone) return fail("half-face " + std::to_string(h) + " points to a dead or missing tet");
      if (opp_[g] != h) return fail("opp not symmetric at half-face " + std::to_string(h));
      if ((g >> 2) == t) return fail("half-face " + std::to_string(h) + " matched inside its own tet");
      const std::uint32_t* q = &tv_[g & ~3u];
      const std::uint8_t* fg = kTetFace[g & 3];
      // Opposite windings: q's face must be p's face read backwards (some rotation).
      const std::uint32_t x = p[f[0]], y = p[f[1]], z = p[f[2]];
      const std::uint32_t u = q[fg[0]], v = q[fg[1]], w = q[fg[2]];
      const bool reversed = (u == x && v == z && w == y) || (u == z && v == y && w == x) || (u == y && v == x && w == z);
      if (!reversed) return fail("half-faces " + std::to_string(h) + " and " + std::to_string(g) + " do not have the same vertices with opposite windings");
    }
  }
  if (live_t != num_live_tets_) return fail("live tet count " + std::to_string(num_live_tets_) + " != " + std::to_string(live_t));
  if (live_t + free_tets_.size() != nts) return fail("tombstones not all on the free list");
  for (std::size_t v = 0; v < nvs; ++v) {
    const std::uint32_t h = v2h_[v];
    if (h == kNone) continue;
    ++live_v;
    if (!used[v]) return fail("vertex " + std::to_string(v) + " is used by no tet");
    if (h >= opp_.size() || tv_[h & ~3u] == kNone) return fail("v2h of vertex " + std::to_string(v) + " points to a dead tet");
    const std::uint32_t* p = &tv_[h & ~3u];
    if (p[h & 3] == v || !(p[0] == v || p[1] == v || p[2] == v || p[3] == v))
      return fail("v2h of vertex " + std::to_string(v) + " is a half-face without it");
    if ((opp_[h] == kBoundary) != bool(on_boundary[v]))
      return fail("v2h of vertex " + std::to_string(v) + " is not boundary-preferring");
  }
  if (live_v != num_live_vertices_) return fail("live vertex count mismatch");
  if (check_positive) {
    const FpEnvironmentScope fp;  // one MXCSR check for the whole pass (predicates.hpp)
    for (std::size_t t = 0; t < nts; ++t) {
      const std::uint32_t* p = &tv_[4 * t];
      if (p[0] == kNone) continue;
      if (fp.orient3d(&xyz_[3 * std::size_t(p[0])], &xyz_[3 * std::size_t(p[1])], &xyz_[3 * std::size_t(p[2])],
                   &xyz_[3 * std::size_t(p[3])]) <= 0)
        return fail("tet " + std::to_string(t) + " is not strictly positive");
    }
  }
  return rep;
}

}  // namespace volmap
