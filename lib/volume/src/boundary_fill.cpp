// boundary_fill.cpp — docs/mapping.md §8 step 14 (conventions in boundary_fill.hpp): the three
// searches of steiner_free_fill.hpp and the assembly of the fill with the fewest tets.
#include <volmap/volume/boundary_fill.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/star_shaped_boundary.hpp>
#include <volmap/volume/steiner_free_fill.hpp>

#include <algorithm>
#include <array>

namespace volmap {

namespace {

using Faces = std::vector<std::array<std::uint32_t, 3>>;

constexpr std::size_t kFirstRestartNodes = 2000;  // the first restart's node limit (doubling after)

// The vertex positions of one search in both spaces (the input's ids first) and which of them are
// required (interior input vertices) or optional (added points).
struct SearchSpace {
  std::vector<double> source, target;
  std::vector<std::uint32_t> required, optional;
};

class FillSearches {
 public:
  FillSearches(const TetMeshData& input, const BoundaryMap& map, std::size_t must_beat, const BoundaryFillLimits& limits)
      : input_(input), map_(map), limits_(limits), clock_(limits.time_limit_seconds), bound_(must_beat) {
    for (std::uint64_t hf : boundary_half_faces(input)) faces_.push_back(half_face_vertices(input, hf));
    on_boundary_.assign(input.num_vertices(), 0);
    for (const auto& f : faces_)
      for (std::uint32_t v : f) on_boundary_[v] = 1;
    all_fixed_ = map.size() == input.num_vertices();
    fixed_ = input.xyz;
    for (std::size_t i = 0; i < map.size(); ++i)
      for (int k = 0; k < 3; ++k) fixed_[3 * std::size_t(map.vids[i]) + k] = map.xyz[3 * i + k];
  }

  BoundaryFill run(const CertifiedPoints& certified) {
    if (all_fixed_) own_or_boundary_vertices();
    if (certified.source && certified.target_xyz) with_certified_points(certified);
    if (all_fixed_) with_kernel_points();
    if (all_fixed_) with_one_centroid_point();
    if (!best_.found)
      best_.why_not = !all_fixed_ && !certified.source ? "interior vertices without images (no certified map)"
                      : exhausted_ ? "no fill with fewer tets exists on these vertices (search exhausted)"
                                   : "no fill with fewer tets found within the search limits";
    return std::move(best_);
  }

 private:
  const TetMeshData& input_;
  const BoundaryMap& map_;
  BoundaryFillLimits limits_;
  TimeBudget clock_;
  std::size_t bound_;  // a fill must have fewer tets
  Faces faces_;
  std::vector<std::uint8_t> on_boundary_;
  bool all_fixed_ = false;
  std::vector<double> fixed_;  // the input's positions with the map's images on ∂M
  std::size_t nodes_ = 0;
  bool exhausted_ = true;  // every search so far saw its whole space
  BoundaryFill best_;

  bool out_of_budget() const { return nodes_ >= limits_.max_nodes || clock_.expired(); }

  // Runs one search as restarts with other tie-breaks and doubling node limits (a backtracking
  // search's time is heavy-tailed: a short run with another order often ends where a long one
  // stalls); a fill with fewer tets than bound_ becomes best_ and bounds the later restarts.
  void search(const SearchSpace& space, std::size_t max_nodes, const char* name) {
    std::size_t used = 0;
    for (std::uint64_t seed = 0; used < max_nodes; ++seed) {
      if (out_of_budget()) {
        exhausted_ = false;
        return;
      }
      SteinerFreeFillLimits l;
      l.max_nodes = std::min({kFirstRestartNodes << std::min<std::uint64_t>(seed, 20), max_nodes - used, limits_.max_nodes - nodes_});
      l.time_limit_seconds = clock_.option_seconds();
      l.max_tets = bound_;
      l.seed = seed;
      const SteinerFreeFillResult r = fill_without_steiner_points(faces_, space.source.data(), space.target.data(),
                                                                  space.source.size() / 3, l, space.required, space.optional);
      nodes_ += r.nodes;
      used += r.nodes;
      if (r.found) keep(space, r.tets, name);
      if (r.exhausted) return;  // the whole space seen: nothing better on these vertices
    }
    exhausted_ = false;
  }

  // best_ becomes the fill `tets` over `space`: the input's vertices, then the optional points
  // it uses, in id order.
  void keep(const SearchSpace& space, const std::vector<std::uint32_t>& tets, const char* name) {
    const std::size_t n = input_.num_vertices(), m = space.source.size() / 3;
    std::vector<std::uint32_t> id(m, 0);
    for (std::uint32_t v = 0; v < n; ++v) id[v] = v;
    std::vector<std::uint8_t> used(m, 0);
    for (std::uint32_t v : tets) used[v] = 1;
    BoundaryFill f;
    f.found = true;
    f.search = name;
    f.source.xyz.assign(space.source.begin(), space.source.begin() + 3 * std::ptrdiff_t(n));
    f.target_xyz.assign(space.target.begin(), space.target.begin() + 3 * std::ptrdiff_t(n));
    f.locked.assign(on_boundary_.begin(), on_boundary_.end());
    f.source.vertex_labels = input_.vertex_labels;
    for (std::uint32_t v = std::uint32_t(n); v < m; ++v) {
      if (!used[v]) continue;
      id[v] = std::uint32_t(f.source.xyz.size() / 3);
      f.source.xyz.insert(f.source.xyz.end(), &space.source[3 * std::size_t(v)], &space.source[3 * std::size_t(v)] + 3);
      f.target_xyz.insert(f.target_xyz.end(), &space.target[3 * std::size_t(v)], &space.target[3 * std::size_t(v)] + 3);
      f.locked.push_back(0);
      if (!f.source.vertex_labels.empty()) f.source.vertex_labels.push_back(0);
    }
    f.source.tets.reserve(tets.size());
    for (std::uint32_t v : tets) f.source.tets.push_back(id[v]);
    if (f.source.tets == input_.tets) f.source.tet_labels = input_.tet_labels;  // the input's own tets
    bound_ = f.source.num_tets();
    best_ = std::move(f);
  }

  // Search 1.
  void own_or_boundary_vertices() {
    SearchSpace space{input_.xyz, fixed_, {}, {}};
    if (count_nonpositive(fixed_, input_.tets) == 0) {
      if (input_.num_tets() < bound_) keep(space, input_.tets, "own tets");
      return;
    }
    search(space, limits_.max_nodes_per_search, "boundary vertices");
  }

  // Search 2.
  void with_certified_points(const CertifiedPoints& c) {
    const std::size_t n = input_.num_vertices();
    SearchSpace space{input_.xyz, *c.target_xyz, {}, {}};
    space.source.resize(3 * n);
    space.source.insert(space.source.end(), c.source->xyz.begin() + 3 * std::ptrdiff_t(n), c.source->xyz.end());
    for (std::size_t i = 0; i < 3 * n; ++i)
      if (on_boundary_[i / 3]) space.target[i] = fixed_[i];  // the map's doubles on ∂M
    for (std::uint32_t v = 0; v < n; ++v)
      if (!on_boundary_[v]) space.required.push_back(v);
    for (std::uint32_t v = std::uint32_t(n); v < space.source.size() / 3; ++v) space.optional.push_back(v);
    search(space, limits_.max_nodes_per_search, "certified map's points");
  }

  // Search 3, first point: a strict kernel point of ∂M in the source and one of its image. The cone
  // from them over every boundary face is then a fill valid in both spaces, so this search has a
  // fill of 2V − 4 tets to start from (V boundary vertices) and looks for fewer.
  void with_kernel_points() {
    double p[3], q[3];
    if (!boundary_kernel_points(input_, map_, p, q)) return;
    const std::size_t n = input_.num_vertices();
    SearchSpace space{input_.xyz, fixed_, {}, {std::uint32_t(n)}};
    space.source.insert(space.source.end(), p, p + 3);
    space.target.insert(space.target.end(), q, q + 3);
    search(space, limits_.max_nodes_per_point, "one point in the kernels of the boundary");
  }

  // Search 3, then: the input's tets, those non-positive at the images first.
  void with_one_centroid_point() {
    const std::size_t n = input_.num_vertices();
    std::vector<std::int8_t> sign(input_.num_tets());
    orient3d_tets(fixed_.data(), n, input_.tets.data(), input_.num_tets(), sign.data());
    std::vector<std::size_t> order(input_.num_tets());
    for (std::size_t t = 0; t < order.size(); ++t) order[t] = t;
    std::stable_partition(order.begin(), order.end(), [&](std::size_t t) { return sign[t] <= 0; });
    SearchSpace space{input_.xyz, fixed_, {}, {std::uint32_t(n)}};
    space.source.resize(3 * n + 3);
    space.target.resize(3 * n + 3);
    for (std::size_t t : order) {
      for (int k = 0; k < 3; ++k) {
        space.source[3 * n + k] = space.target[3 * n + k] = 0;
        for (int j = 0; j < 4; ++j) {
          space.source[3 * n + k] += 0.25 * input_.xyz[3 * std::size_t(input_.tets[4 * t + j]) + k];
          space.target[3 * n + k] += 0.25 * fixed_[3 * std::size_t(input_.tets[4 * t + j]) + k];
        }
      }
      search(space, limits_.max_nodes_per_point, "one point at a tet centroid");
      if (out_of_budget()) return;
    }
  }
};

}  // namespace

BoundaryFill fill_boundary_with_fewer_tets(const TetMeshData& input, const BoundaryMap& map, const CertifiedPoints& certified,
                                           std::size_t must_beat, const BoundaryFillLimits& limits) {
  return FillSearches(input, map, must_beat, limits).run(certified);
}

}  // namespace volmap
