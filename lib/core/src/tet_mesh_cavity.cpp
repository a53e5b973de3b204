// TetMesh::replace_cavity — replace a ball of tets by a fill that closes onto its boundary
// (datastructure.md §4). Conventions in tet_mesh.hpp: half-face 4t+i is the face opposite local
// vertex i, outward in kTetFace order; a fill face that replaces a cavity boundary face has that
// face's winding (both see the cavity from inside), two fill faces glued together have opposite
// windings. The edit plans everything (slots, links, vertex deletions) and checks the plan before
// it writes anything, so a refused fill leaves the mesh and its properties untouched.
#include <volmap/core/tet_mesh.hpp>

#include <volmap/core/error.hpp>
#include <volmap/core/properties.hpp>

#include "face_grouping.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace volmap {
namespace {

constexpr std::uint32_t kNone = kInvalidIndex;
constexpr std::uint32_t kCavityFace = 0x80000000u;  // face id flag: a cavity boundary face (else 4k+i of the fill)

[[noreturn]] void refuse(const std::string& reason) { throw Error(ErrorKind::Failed, "", 0, "replace_cavity: " + reason); }

// One face in the matching: its vertex set (smallest id, packed other two), winding parity, and id.
struct FaceEntry {
  std::uint32_t min_v;
  std::uint64_t key;
  std::uint32_t parity;
  std::uint32_t id;  // 4k+i of fill tet k, or kCavityFace | index into the cavity boundary list
  bool operator<(const FaceEntry& o) const {
    if (min_v != o.min_v) return min_v < o.min_v;
    if (key != o.key) return key < o.key;
    return id < o.id;
  }
  bool same_face(const FaceEntry& o) const { return min_v == o.min_v && key == o.key; }
};

std::string face_name(const FaceEntry& f) {
  auto name = [](std::uint32_t v) {
    return v >= CavityTet::kFirstNewVertex ? "new" + std::to_string(v - CavityTet::kFirstNewVertex) : std::to_string(v);
  };
  return "(" + name(f.min_v) + "," + name(std::uint32_t(f.key >> 32)) + "," + name(std::uint32_t(f.key)) + ")";
}

bool sorted_contains(const std::vector<std::uint32_t>& v, std::uint32_t x) { return std::binary_search(v.begin(), v.end(), x); }

}  // namespace

CavityReplacement TetMesh::replace_cavity(const std::vector<TetId>& cavity, const std::vector<CavityTet>& fill,
                                          const std::vector<double>& new_positions) {
  // ---- the cavity: live, distinct tets; its vertices; its boundary faces ----------------------
  if (cavity.empty()) refuse("empty cavity");
  if (new_positions.size() % 3 != 0) refuse("new_positions holds " + std::to_string(new_positions.size()) + " doubles, not 3 per vertex");
  const std::size_t num_new = new_positions.size() / 3;
  if (num_vertex_slots() + num_new >= CavityTet::kFirstNewVertex) refuse("vertex id space exhausted");
  std::vector<std::uint32_t> in_cavity;  // sorted tet ids
  in_cavity.reserve(cavity.size());
  for (TetId t : cavity) {
    if (t.idx() >= num_tet_slots() || !tet_is_live(t)) refuse("cavity tet " + std::to_string(t.idx()) + " is not live");
    in_cavity.push_back(t.idx());
  }
  std::sort(in_cavity.begin(), in_cavity.end());
  if (std::adjacent_find(in_cavity.begin(), in_cavity.end()) != in_cavity.end()) refuse("the cavity lists a tet twice");
  std::vector<std::uint32_t> cavity_vertices, boundary_vertices, outside;  // outside[j]: neighbour of boundary face j
  std::vector<FaceEntry> faces;
  faces.reserve(4 * fill.size() + 2 * cavity.size());
  for (std::uint32_t t : in_cavity) {
    for (int i = 0; i < 4; ++i) {
      cavity_vertices.push_back(tv_[4 * std::size_t(t) + i]);
      const std::uint32_t o = opp_[4 * std::size_t(t) + i];
      if (o != kBoundary && sorted_contains(in_cavity, o >> 2)) continue;
      FaceEntry f;
      detail::face_key(&tv_[4 * std::size_t(t)], i, f.min_v, f.key, f.parity);
      f.id = kCavityFace | std::uint32_t(outside.size());
      outside.push_back(o);
      faces.push_back(f);
      for (int k = 0; k < 3; ++k) boundary_vertices.push_back(tv_[4 * std::size_t(t) + kTetFace[i][k]]);
    }
  }
  for (auto* list : {&cavity_vertices, &boundary_vertices}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }

  // ---- the fill: vertex references, parents, faces --------------------------------------------
  std::vector<std::uint32_t> fill_tv(4 * fill.size()), used(cavity_vertices.size(), 0), new_used(num_new, 0);
  for (std::size_t k = 0; k < fill.size(); ++k) {
    const std::string which = "fill tet " + std::to_string(k);
    const TetId parent = fill[k].parent;
    if (parent.is_valid() && !sorted_contains(in_cavity, parent.idx())) refuse(which + ": parent " + std::to_string(parent.idx()) + " is not a cavity tet");
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t v = fill[k].v[i].idx();
      if (v >= CavityTet::kFirstNewVertex) {
        if (v - CavityTet::kFirstNewVertex >= num_new) refuse(which + " uses new vertex " + std::to_string(v - CavityTet::kFirstNewVertex) + " of " + std::to_string(num_new));
        new_used[v - CavityTet::kFirstNewVertex] = 1;
      } else {
        const auto it = std::lower_bound(cavity_vertices.begin(), cavity_vertices.end(), v);
        if (it == cavity_vertices.end() || *it != v) refuse(which + " uses vertex " + std::to_string(v) + ", not a vertex of the cavity");
        used[std::size_t(it - cavity_vertices.begin())] = 1;
      }
      for (int j = 0; j < i; ++j)
        if (fill_tv[4 * k + j] == v) refuse(which + " repeats a vertex");
      fill_tv[4 * k + i] = v;
    }
    for (int i = 0; i < 4; ++i) {
      FaceEntry f;
      detail::face_key(&fill_tv[4 * k], i, f.min_v, f.key, f.parity);
      f.id = std::uint32_t(4 * k + i);
      faces.push_back(f);
    }
  }
  for (std::size_t j = 0; j < num_new; ++j)
    if (!new_used[j]) refuse("new vertex " + std::to_string(j) + " is used by no fill tet");
  // A cavity vertex the fill drops must be interior to the cavity (its tets all cavity tets).
  for (std::size_t k = 0; k < cavity_vertices.size(); ++k)
    if (!used[k] && (sorted_contains(boundary_vertices, cavity_vertices[k]) || !sorted_contains(in_cavity, v2h_[cavity_vertices[k]] >> 2)))
      refuse("the fill drops vertex " + std::to_string(cavity_vertices[k]) + ", which tets outside the cavity still use");

  // ---- matching: fill-fill (opposite windings) or fill-cavity boundary (same winding) -----------
  std::sort(faces.begin(), faces.end());  // in a group, fill faces (ids < kCavityFace) come first
  std::vector<std::pair<std::uint32_t, std::uint32_t>> glued, replaced;  // (4k+i, 4k'+i') / (4k+i, boundary face)
  for (std::size_t g = 0; g < faces.size();) {
    std::size_t e = g + 1;
    while (e < faces.size() && faces[e].same_face(faces[g])) ++e;
    const FaceEntry& a = faces[g];
    const std::string name = face_name(a);
    if (a.id & kCavityFace) refuse("cavity boundary face " + name + " is not covered by the fill");
    if (e - g == 1) refuse("fill face " + name + " is neither shared by two fill tets nor a cavity boundary face");
    if (e - g > 2) refuse("face " + name + " appears " + std::to_string(e - g) + " times in the fill and the cavity boundary");
    const FaceEntry& b = faces[g + 1];
    if (b.id & kCavityFace) {
      if (a.parity != b.parity) refuse("fill face " + name + " has the opposite winding of the cavity boundary face");
      replaced.push_back({a.id, b.id & ~kCavityFace});
    } else {
      if (a.parity == b.parity) refuse("fill tets " + std::to_string(a.id / 4) + " and " + std::to_string(b.id / 4) + " share face " + name + " with the same winding");
      glued.push_back({a.id, b.id});
    }
    g = e;
  }
  // A glued face over three cavity boundary vertices may exist outside the cavity already
  // (a face with an interior or new vertex cannot).
  std::vector<TetId> star;
  for (const auto& [a, b] : glued) {
    const std::uint32_t* f = &fill_tv[4 * std::size_t(a / 4)];
    std::uint32_t x[3];
    for (int k = 0; k < 3; ++k) x[k] = f[kTetFace[a % 4][k]];
    if (!(sorted_contains(boundary_vertices, x[0]) && sorted_contains(boundary_vertices, x[1]) && sorted_contains(boundary_vertices, x[2])))
      continue;
    for (int k = 0; k < 3; ++k) {  // each star: at a pinched vertex vertex_star walks one cluster only
      vertex_star(VertexId(x[k]), star);
      for (TetId s : star)
        if (!sorted_contains(in_cavity, s.idx()) && tet_local_index(s, VertexId(x[(k + 1) % 3])) >= 0 &&
            tet_local_index(s, VertexId(x[(k + 2) % 3])) >= 0)
          refuse("fill face (" + std::to_string(x[0]) + "," + std::to_string(x[1]) + "," + std::to_string(x[2]) +
                 ") inside the cavity is already a face of tet " + std::to_string(s.idx()) + " outside it");
    }
  }

  // ---- commit: slots, labels and properties from the parents, vertices, links ------------------
  CavityReplacement out;
  std::vector<std::uint32_t> slot(fill.size()), parent(fill.size());
  for (std::size_t k = 0; k < fill.size(); ++k) {
    slot[k] = k < cavity.size() ? cavity[k].idx() : take_tet_slot();
    parent[k] = fill[k].parent.idx();
  }
  if (!tet_labels_.empty()) {
    std::vector<std::int32_t> label(fill.size());
    for (std::size_t k = 0; k < fill.size(); ++k) label[k] = parent[k] != kNone ? tet_labels_[parent[k]] : 0;
    for (std::size_t k = 0; k < fill.size(); ++k) tet_labels_[slot[k]] = label[k];
  }
  properties_->notify_assign(ElementKind::Tet, slot.data(), parent.data(), fill.size());
  if (fill.size() > cavity.size()) num_live_tets_ += fill.size() - cavity.size();
  for (std::size_t k = fill.size(); k < cavity.size(); ++k) free_tet(cavity[k].idx());
  out.vertices.reserve(num_new);
  for (std::size_t j = 0; j < num_new; ++j) out.vertices.push_back(VertexId(allocate_vertex(&new_positions[3 * j])));
  for (std::size_t k = 0; k < fill.size(); ++k)
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t v = fill_tv[4 * k + i];
      tv_[4 * std::size_t(slot[k]) + i] = v >= CavityTet::kFirstNewVertex ? out.vertices[v - CavityTet::kFirstNewVertex].idx() : v;
    }
  auto half_face = [&slot](std::uint32_t fill_face) { return 4 * slot[fill_face / 4] + (fill_face & 3); };
  for (const auto& [a, b] : glued) link(half_face(a), half_face(b));
  for (const auto& [a, j] : replaced) {
    const std::uint32_t h = half_face(a);
    opp_[h] = kBoundary;
    link(h, outside[j]);
  }
  for (std::size_t k = 0; k < cavity_vertices.size(); ++k) {
    if (used[k]) continue;  // not used by the fill: an interior vertex of the cavity
    v2h_[cavity_vertices[k]] = kNone;
    free_vertices_.push_back(cavity_vertices[k]);
    --num_live_vertices_;
  }
  refresh_v2h(slot.data(), slot.size());
  edited();
  out.tets.reserve(fill.size());
  for (std::uint32_t s : slot) out.tets.push_back(TetId(s));
  return out;
}

}  // namespace volmap
