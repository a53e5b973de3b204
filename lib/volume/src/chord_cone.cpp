// chord_cone.cpp — B0's cone patches (docs/mapping.md §4; conventions in chord_cone.hpp). Faces of
// ∂R are listed in the outward order of the R tet they bound (kTetFace), so a point q sees one from
// inside iff orient3d(face, q) > 0 and the cone tet is (face, w). A region is a sorted list of tets.
#include <volmap/volume/chord_cone.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/chord_rules.hpp>
#include <volmap/volume/kernel_lp.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace volmap {

namespace {

bool contains(const std::vector<TetId>& sorted, TetId t) { return std::binary_search(sorted.begin(), sorted.end(), t); }

// A region with an admissible cone: ∂R's faces, the R tet behind each, and the apex.
struct ConePlan {
  std::vector<TetId> region;
  std::vector<std::array<VertexId, 3>> faces;
  std::vector<TetId> parents;
  std::vector<std::uint32_t> vertices;  // R's vertices, sorted (all on ∂R when admissible)
  double apex[3] = {0, 0, 0};
  long long cost() const { return (long long)faces.size() - (long long)region.size(); }
};

// Plans the cone over `region` (sorted); false when it is not admissible or would cost more than
// max_cost (checked before the kernel LP, the costly part).
bool plan_cone(const TetMesh& mesh, std::vector<TetId> region, ConePlan& plan,
               long long max_cost = std::numeric_limits<long long>::max()) {
  plan.region = std::move(region);
  plan.faces.clear();
  plan.parents.clear();
  double worst = std::numeric_limits<double>::infinity();
  std::vector<std::uint32_t>& on_boundary = plan.vertices;
  on_boundary.clear();
  for (TetId t : plan.region) {
    const auto tv = mesh.tet_vertices(t);
    worst = std::min(worst, tet_shape(mesh.vertex_position(tv[0]), mesh.vertex_position(tv[1]), mesh.vertex_position(tv[2]),
                                      mesh.vertex_position(tv[3])));
    for (int i = 0; i < 4; ++i) {
      const HalfFaceId o = mesh.half_face_opposite(HalfFaceId(t, i));
      if (o.is_valid() && contains(plan.region, o.tet())) continue;
      const auto f = mesh.half_face_vertices(HalfFaceId(t, i));
      plan.faces.push_back(f);
      plan.parents.push_back(t);
      for (VertexId x : f) on_boundary.push_back(x.idx());
    }
  }
  std::sort(on_boundary.begin(), on_boundary.end());
  on_boundary.erase(std::unique(on_boundary.begin(), on_boundary.end()), on_boundary.end());
  if (plan.cost() > max_cost) return false;
  for (TetId t : plan.region)  // a vertex strictly inside R would be lost
    for (VertexId x : mesh.tet_vertices(t))
      if (!std::binary_search(on_boundary.begin(), on_boundary.end(), x.idx())) return false;
  std::vector<double> triangles;
  triangles.reserve(9 * plan.faces.size());
  for (const auto& f : plan.faces)
    for (VertexId x : f) triangles.insert(triangles.end(), mesh.vertex_position(x), mesh.vertex_position(x) + 3);
  if (!strict_kernel_point(triangles, plan.apex)) return false;  // exact: the apex sees every face from inside
  for (const auto& f : plan.faces)
    if (tet_shape(mesh.vertex_position(f[0]), mesh.vertex_position(f[1]), mesh.vertex_position(f[2]), plan.apex) < kFixShapeRatio * worst)
      return false;
  return true;
}

bool commit(TetMesh& mesh, const ConePlan& plan) {
  std::vector<CavityTet> fill;
  fill.reserve(plan.faces.size());
  for (std::size_t k = 0; k < plan.faces.size(); ++k)
    fill.push_back({{plan.faces[k][0], plan.faces[k][1], plan.faces[k][2], CavityTet::new_vertex(0)}, plan.parents[k]});
  try {
    mesh.replace_cavity(plan.region, fill, {plan.apex[0], plan.apex[1], plan.apex[2]});
  } catch (const Error&) {  // refused (e.g. a region that is not a ball): untouched
    return false;
  }
  return true;
}

std::vector<TetId> star_of(const TetMesh& mesh, std::uint32_t v) {
  std::vector<TetId> star;
  mesh.vertex_star(VertexId(v), star);
  return star;  // sorted
}

std::vector<TetId> merged(const std::vector<TetId>& a, const std::vector<TetId>& b) {
  std::vector<TetId> out;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

}  // namespace

std::size_t boundary_faces_at(const TetMesh& mesh, std::uint32_t v) {
  if (!mesh.vertex_is_boundary(VertexId(v))) return 0;
  thread_local std::vector<TetId> star;
  mesh.vertex_star_unsorted(VertexId(v), star);
  std::size_t n = 0;
  for (TetId t : star)
    for (int i = 0; i < 4; ++i)
      n += mesh.half_face_is_boundary(HalfFaceId(t, i)) && mesh.tet_vertex(t, i).idx() != v;
  return n;
}

bool cone_vertex_star(TetMesh& mesh, std::uint32_t v) {
  if (!mesh.vertex_is_boundary(VertexId(v))) return false;
  ConePlan plan;
  return plan_cone(mesh, star_of(mesh, v), plan) && commit(mesh, plan);
}

bool cone_region(TetMesh& mesh, std::uint32_t seed, const PendingChordsAt& chords, const ConeRegionLimits& limits, long long* added,
                 std::vector<std::uint32_t>* touched) {
  if (!mesh.vertex_is_boundary(VertexId(seed))) return false;
  std::set<std::size_t> taken;  // chords the region takes away
  long long beaten = 0;         // what they would cost otherwise
  // chords(v) once per vertex: nothing is edited before the commit, so the answers stand (each
  // call may walk vertex stars to find the chords; at a hub of a coarse mesh that was most of B0).
  std::map<std::uint32_t, std::vector<std::pair<std::size_t, long long>>> chords_at;
  auto chords_of = [&](std::uint32_t v) -> const std::vector<std::pair<std::size_t, long long>>& {
    auto it = chords_at.find(v);
    if (it == chords_at.end()) it = chords_at.emplace(v, chords(v)).first;
    return it->second;
  };
  // The chords at v not taken yet, and what they cost.
  auto gain = [&](std::uint32_t v, bool take) {
    long long g = 0;
    for (const auto& [id, cost] : chords_of(v)) {
      if (taken.count(id)) continue;
      g += cost;
      if (take) taken.insert(id);
    }
    return g;
  };
  ConePlan best;
  if (!plan_cone(mesh, star_of(mesh, seed), best)) return false;
  beaten += gain(seed, true);
  std::set<std::uint32_t> members = {seed}, refused;
  for (int step = 0; step < limits.max_steps; ++step) {
    // The boundary vertex of R with the most costly chords not taken yet.
    std::uint32_t next = kInvalidIndex;
    long long next_gain = -1;
    for (const std::uint32_t x : best.vertices) {
      if (members.count(x) || refused.count(x) || !mesh.vertex_is_boundary(VertexId(x))) continue;
      const long long g = gain(x, false);
      if (g > next_gain || (g == next_gain && x < next)) {
        next = x;
        next_gain = g;
      }
    }
    if (next == kInvalidIndex) break;
    std::vector<TetId> grown = merged(best.region, star_of(mesh, next));
    ConePlan plan;
    if (grown.size() > limits.max_tets || !plan_cone(mesh, std::move(grown), plan, best.cost() + next_gain)) {
      refused.insert(next);
      continue;
    }
    best = std::move(plan);
    members.insert(next);
    beaten += gain(next, true);
  }
  if (best.cost() >= beaten || !commit(mesh, best)) return false;
  *added = best.cost();
  if (touched) *touched = best.vertices;  // all on ∂R
  return true;
}

}  // namespace volmap
