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
#include <map>
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

// The checked plan of one replacement: everything replace_cavity writes, computed from the mesh's
// public arrays before anything is written. Each step refuses (throws) on the first problem.
class CavityPlan {
 public:
  CavityPlan(const TetMesh& mesh, const std::vector<TetId>& cavity, const std::vector<CavityTet>& fill, std::size_t num_new)
      : mesh_(mesh), fill_(fill), num_new_(num_new) {
    read_cavity(cavity);
    read_fill();
    check_dropped_vertices();
    match_faces();
    check_glued_faces_are_new();
  }

  std::vector<std::uint32_t> fill_tv;                      // 4 per fill tet (new vertices as kFirstNewVertex + k)
  std::vector<std::uint32_t> dropped;                      // cavity vertices the fill does not use
  std::vector<std::uint32_t> outside;                      // per cavity boundary face: its half-face across (or kBoundary)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> glued;     // (4k+i, 4k'+i'): fill faces glued together
  std::vector<std::pair<std::uint32_t, std::uint32_t>> replaced;  // (4k+i, j): fill face taking cavity boundary face j

 private:
  // The cavity: live, distinct tets; its vertices; its boundary faces (with their neighbours across).
  void read_cavity(const std::vector<TetId>& cavity) {
    const auto& tv = mesh_.tet_vertex_array();
    const auto& opp = mesh_.opposite_array();
    in_cavity_.reserve(cavity.size());
    for (TetId t : cavity) {
      if (t.idx() >= mesh_.num_tet_slots() || !mesh_.tet_is_live(t)) refuse("cavity tet " + std::to_string(t.idx()) + " is not live");
      in_cavity_.push_back(t.idx());
    }
    std::sort(in_cavity_.begin(), in_cavity_.end());
    if (std::adjacent_find(in_cavity_.begin(), in_cavity_.end()) != in_cavity_.end()) refuse("the cavity lists a tet twice");
    faces_.reserve(4 * fill_.size() + 2 * cavity.size());
    for (std::uint32_t t : in_cavity_) {
      for (int i = 0; i < 4; ++i) {
        cavity_vertices_.push_back(tv[4 * std::size_t(t) + i]);
        const std::uint32_t o = opp[4 * std::size_t(t) + i];
        if (o != TetMesh::kBoundary && sorted_contains(in_cavity_, o >> 2)) continue;
        FaceEntry f;
        detail::face_key(&tv[4 * std::size_t(t)], i, f.min_v, f.key, f.parity);
        f.id = kCavityFace | std::uint32_t(outside.size());
        outside.push_back(o);
        faces_.push_back(f);
        for (int k = 0; k < 3; ++k) boundary_vertices_.push_back(tv[4 * std::size_t(t) + kTetFace[i][k]]);
      }
    }
    for (auto* list : {&cavity_vertices_, &boundary_vertices_}) {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
  }

  // The fill: vertex references (cavity vertices or new ones), parents in the cavity, faces.
  void read_fill() {
    fill_tv.resize(4 * fill_.size());
    used_.assign(cavity_vertices_.size(), 0);
    std::vector<std::uint8_t> new_used(num_new_, 0);
    for (std::size_t k = 0; k < fill_.size(); ++k) {
      const std::string which = "fill tet " + std::to_string(k);
      const TetId parent = fill_[k].parent;
      if (parent.is_valid() && !sorted_contains(in_cavity_, parent.idx()))
        refuse(which + ": parent " + std::to_string(parent.idx()) + " is not a cavity tet");
      for (int i = 0; i < 4; ++i) {
        const std::uint32_t v = fill_[k].v[i].idx();
        if (v >= CavityTet::kFirstNewVertex) {
          if (v - CavityTet::kFirstNewVertex >= num_new_)
            refuse(which + " uses new vertex " + std::to_string(v - CavityTet::kFirstNewVertex) + " of " + std::to_string(num_new_));
          new_used[v - CavityTet::kFirstNewVertex] = 1;
        } else {
          const auto it = std::lower_bound(cavity_vertices_.begin(), cavity_vertices_.end(), v);
          if (it == cavity_vertices_.end() || *it != v) refuse(which + " uses vertex " + std::to_string(v) + ", not a vertex of the cavity");
          used_[std::size_t(it - cavity_vertices_.begin())] = 1;
        }
        for (int j = 0; j < i; ++j)
          if (fill_tv[4 * k + j] == v) refuse(which + " repeats a vertex");
        fill_tv[4 * k + i] = v;
      }
      for (int i = 0; i < 4; ++i) {
        FaceEntry f;
        detail::face_key(&fill_tv[4 * k], i, f.min_v, f.key, f.parity);
        f.id = std::uint32_t(4 * k + i);
        faces_.push_back(f);
      }
    }
    for (std::size_t j = 0; j < num_new_; ++j)
      if (!new_used[j]) refuse("new vertex " + std::to_string(j) + " is used by no fill tet");
  }

  // A cavity vertex the fill drops must be interior to the cavity (its tets all cavity tets).
  void check_dropped_vertices() {
    const auto& v2h = mesh_.vertex_half_face_array();
    for (std::size_t k = 0; k < cavity_vertices_.size(); ++k) {
      if (used_[k]) continue;
      const std::uint32_t v = cavity_vertices_[k];
      if (sorted_contains(boundary_vertices_, v) || !sorted_contains(in_cavity_, v2h[v] >> 2))
        refuse("the fill drops vertex " + std::to_string(v) + ", which tets outside the cavity still use");
      dropped.push_back(v);
    }
  }

  // Every face once more: fill-fill (opposite windings) or fill-cavity boundary (same winding).
  void match_faces() {
    std::sort(faces_.begin(), faces_.end());  // in a group, fill faces (ids < kCavityFace) come first
    for (std::size_t g = 0; g < faces_.size();) {
      std::size_t e = g + 1;
      while (e < faces_.size() && faces_[e].same_face(faces_[g])) ++e;
      const FaceEntry& a = faces_[g];
      const std::string name = face_name(a);
      if (a.id & kCavityFace) refuse("cavity boundary face " + name + " is not covered by the fill");
      if (e - g == 1) refuse("fill face " + name + " is neither shared by two fill tets nor a cavity boundary face");
      if (e - g > 2) refuse("face " + name + " appears " + std::to_string(e - g) + " times in the fill and the cavity boundary");
      const FaceEntry& b = faces_[g + 1];
      if (b.id & kCavityFace) {
        if (a.parity != b.parity) refuse("fill face " + name + " has the opposite winding of the cavity boundary face");
        replaced.push_back({a.id, b.id & ~kCavityFace});
      } else {
        if (a.parity == b.parity)
          refuse("fill tets " + std::to_string(a.id / 4) + " and " + std::to_string(b.id / 4) + " share face " + name + " with the same winding");
        glued.push_back({a.id, b.id});
      }
      g = e;
    }
  }

  // A glued face over three cavity boundary vertices may exist outside the cavity already (a face
  // with an interior or new vertex cannot). Each vertex's star is searched: at a pinched vertex
  // vertex_star walks one cluster only.
  void check_glued_faces_are_new() const {
    std::map<std::uint32_t, std::vector<TetId>> stars;  // each vertex's star walked once
    auto star_of = [&](std::uint32_t v) -> const std::vector<TetId>& {
      auto [it, added] = stars.try_emplace(v);
      if (added) mesh_.vertex_star_unsorted(VertexId(v), it->second);
      return it->second;
    };
    for (const auto& glue : glued) {
      const std::uint32_t* f = &fill_tv[4 * std::size_t(glue.first / 4)];
      std::uint32_t x[3];
      for (int k = 0; k < 3; ++k) x[k] = f[kTetFace[glue.first % 4][k]];
      if (!(sorted_contains(boundary_vertices_, x[0]) && sorted_contains(boundary_vertices_, x[1]) && sorted_contains(boundary_vertices_, x[2])))
        continue;
      for (int k = 0; k < 3; ++k) {
        const std::vector<TetId>& star = star_of(x[k]);
        for (TetId s : star)
          if (!sorted_contains(in_cavity_, s.idx()) && mesh_.tet_local_index(s, VertexId(x[(k + 1) % 3])) >= 0 &&
              mesh_.tet_local_index(s, VertexId(x[(k + 2) % 3])) >= 0)
            refuse("fill face (" + std::to_string(x[0]) + "," + std::to_string(x[1]) + "," + std::to_string(x[2]) +
                   ") inside the cavity is already a face of tet " + std::to_string(s.idx()) + " outside it");
      }
    }
  }

  const TetMesh& mesh_;
  const std::vector<CavityTet>& fill_;
  const std::size_t num_new_;
  std::vector<std::uint32_t> in_cavity_;  // sorted tet ids
  std::vector<std::uint32_t> cavity_vertices_, boundary_vertices_;  // sorted, unique
  std::vector<std::uint8_t> used_;        // per cavity vertex: used by the fill
  std::vector<FaceEntry> faces_;
};

}  // namespace

CavityReplacement TetMesh::replace_cavity(const std::vector<TetId>& cavity, const std::vector<CavityTet>& fill,
                                          const std::vector<double>& new_positions) {
  if (cavity.empty()) refuse("empty cavity");
  if (new_positions.size() % 3 != 0) refuse("new_positions holds " + std::to_string(new_positions.size()) + " doubles, not 3 per vertex");
  const std::size_t num_new = new_positions.size() / 3;
  if (num_vertex_slots() + num_new >= CavityTet::kFirstNewVertex) refuse("vertex id space exhausted");
  const CavityPlan plan(*this, cavity, fill, num_new);

  // Commit: slots, labels and properties from the parents, vertices, links.
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
  CavityReplacement out;
  out.vertices.reserve(num_new);
  for (std::size_t j = 0; j < num_new; ++j) out.vertices.push_back(VertexId(allocate_vertex(&new_positions[3 * j])));
  for (std::size_t k = 0; k < fill.size(); ++k)
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t v = plan.fill_tv[4 * k + i];
      tv_[4 * std::size_t(slot[k]) + i] = v >= CavityTet::kFirstNewVertex ? out.vertices[v - CavityTet::kFirstNewVertex].idx() : v;
    }
  auto half_face = [&slot](std::uint32_t fill_face) { return 4 * slot[fill_face / 4] + (fill_face & 3); };
  for (const auto& [a, b] : plan.glued) link(half_face(a), half_face(b));
  for (const auto& [a, j] : plan.replaced) {
    const std::uint32_t h = half_face(a);
    opp_[h] = kBoundary;
    link(h, plan.outside[j]);
  }
  for (std::uint32_t v : plan.dropped) {
    v2h_[v] = kNone;
    free_vertices_.push_back(v);
    --num_live_vertices_;
  }
  refresh_v2h(slot.data(), slot.size());
  edited();
  out.tets.reserve(fill.size());
  for (std::uint32_t s : slot) out.tets.push_back(TetId(s));
  return out;
}

}  // namespace volmap
