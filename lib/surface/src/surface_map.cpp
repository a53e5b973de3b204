// Surface mapping onto a base domain: input checks and the attempts (see surface_map.hpp for the
// algorithm). One attempt works on a fresh copy of the boundary surface (an OpenMesh TriMesh):
// uniform subdivision rounds, the domain's graph (arc_tracing.hpp), its rotations, the charts
// (chart_embedding.hpp), the replay of the splits on the tets (split_replay.hpp) and the exact check
// of the numbers that will be written. Attempts differ in arc order and subdivision.
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/surface/surface_map.hpp>

#include "arc_tracing.hpp"
#include "chart_embedding.hpp"
#include "split_replay.hpp"
#include "working_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace volmap {
namespace {

using namespace surface_detail;

[[noreturn]] void bad_input(const std::string& reason) { throw Error(ErrorKind::BadInput, "", 0, reason); }

// Every tet must be VOLMAP-positive: the outward windings of the boundary depend on it.
void require_positive_tets(const TetMeshData& mesh) {
  std::vector<std::int8_t> signs(mesh.num_tets());
  const TetSignCounts c = orient3d_tets(mesh.xyz.data(), mesh.num_vertices(), mesh.tets.data(), mesh.num_tets(), signs.data());
  if (!c.ok) bad_input(std::string("the mesh cannot be oriented: ") + c.error);
  if (c.positive == mesh.num_tets()) return;
  const auto t = static_cast<std::size_t>(std::find_if(signs.begin(), signs.end(), [](std::int8_t s) { return s <= 0; }) -
                                          signs.begin());
  bad_input("tet " + std::to_string(t) + " is not VOLMAP-positive (orient3d <= 0): flip or repair the mesh first");
}

// The boundary must be a closed manifold genus-0 surface.
void require_sphere_topology(const BoundarySurface& b) {
  if (b.mesh.n_faces() == 0) bad_input("the mesh has no boundary");
  if (!b.complete())
    bad_input("the boundary surface is not manifold (" + std::to_string(b.rejected_half_faces.size()) +
              " boundary faces at non-manifold edges or vertices)");
  for (auto h : b.mesh.halfedges())
    if (b.mesh.is_boundary(h)) bad_input("the boundary surface is not manifold (an edge with one boundary face)");
  const long long chi = static_cast<long long>(b.mesh.n_vertices()) - static_cast<long long>(b.mesh.n_edges()) +
                        static_cast<long long>(b.mesh.n_faces());
  if (chi != 2)
    bad_input("the boundary surface is not a genus-0 sphere (Euler characteristic " + std::to_string(chi) + ")");
}

struct Attempt {
  const std::vector<int>* order;
  int subdivisions;  // rounds of splitting every boundary edge first
  ChordSplitRule chords;
  std::string name;
};

// Splits every edge of the surface, `rounds` times (surfaces too coarse for the domain).
void subdivide(WorkingSurface& s, int rounds) {
  for (int r = 0; r < rounds; ++r) {
    std::vector<EdgeHandle> edges(s.mesh.edges().begin(), s.mesh.edges().end());
    for (auto e : edges) s.split_edge(e);
  }
}

// Steps 1–3 of one attempt: the domain's graph traced on the surface, the splits replayed on the
// tets. Its tet count is known before the costly charts.
struct TracedAttempt {
  TracedAttempt(const BoundarySurface& boundary, std::uint32_t first_new_vid, const Attempt& a)
      : attempt(&a), surface(boundary, first_new_vid) {}
  const Attempt* attempt;
  WorkingSurface surface;
  EmbeddedGraph graph;
  SourceTetMesh::Refined refined;
  std::size_t num_tets() const { return refined.mesh.num_tets(); }
};

std::unique_ptr<TracedAttempt> trace_attempt(SourceTetMesh& source, const BoundarySurface& boundary,
                                             const Domain& domain, const Attempt& attempt, const Point3& bmin,
                                             const Point3& bmax) {
  auto t = std::make_unique<TracedAttempt>(boundary, source.num_input_vertices(), attempt);
  subdivide(t->surface, attempt.subdivisions);
  t->graph = embed_domain_graph(t->surface, domain, *attempt.order, attempt.chords, bmin, bmax);
  check_rotations(t->surface, domain, t->graph);
  t->refined = source.refine(t->surface.splits);
  return t;
}

// Steps 4–5 of a traced attempt: the charts, then the exact check.
SurfaceMapResult finish_attempt(TracedAttempt& t, const Domain& domain) {
  const WorkingSurface& surface = t.surface;
  const std::vector<double> img = embed_charts(t.surface, domain, t.graph);
  SurfaceMapResult result;
  result.mesh = std::move(t.refined.mesh);
  result.added_vertices = surface.splits.size();
  result.collided_nodes = t.graph.collided_nodes;
  for (auto v : t.graph.node_vertex) result.node_vertices.push_back(surface.vid_of(v));
  result.map.vids.reserve(surface.num_vertices());
  result.map.xyz.reserve(3 * surface.num_vertices());
  for (auto v : surface.mesh.vertices()) {  // index order = vid order
    result.map.vids.push_back(surface.vid_of(v));
    result.map.xyz.insert(result.map.xyz.end(), &img[3 * v.idx()], &img[3 * v.idx()] + 3);
  }
  result.check = check_surface_map(result.mesh.num_vertices(), t.refined.boundary, result.map, &domain);
  if (!result.check.ok)
    throw Error(ErrorKind::Failed, "", 0, "the computed map fails the exact check: " + result.check.reason);
  result.attempt = t.attempt->name;
  return result;
}

// Attempts (surface_map.hpp, step 3), in groups: the reference order, then a spanning tree first
// (skipped where it is the reference order); then, for surfaces too coarse for the domain (fewer
// free vertices than nodes, no room between arcs), 1 and 2 rounds of splitting every boundary
// edge first (spanning tree order). Within a group both chord rules run (the reference's alone
// with options.reference_chord_splits) and the map whose mesh has fewer tets wins (the lean one on
// a tie): the traced attempts are finished in that order until one passes. The first group with a
// map ends the search. Failed attempts are appended to `failed`. With `must_beat` (a placement
// search), a group whose traced attempts all have at least that many tets ends the search without
// a map: it cannot win, so its charts are not computed.
std::optional<SurfaceMapResult> first_map(SourceTetMesh& source, const BoundarySurface& boundary, const Domain& domain,
                                          const SurfaceMapOptions& options, const Point3& bmin, const Point3& bmax,
                                          std::vector<std::string>& failed,
                                          std::size_t must_beat = std::numeric_limits<std::size_t>::max()) {
  const std::vector<int> reference = domain.trace_order();
  const std::vector<int> tree = spanning_tree_first_order(domain);
  for (int subdivisions = 0; subdivisions <= 2; ++subdivisions)
    for (const std::vector<int>* order : {&reference, &tree}) {
      if (subdivisions > 0 && order == &reference) continue;
      if (order == &tree && subdivisions == 0 && tree == reference) continue;
      std::string name = order == &reference ? "reference arc order" : "spanning tree first";
      if (subdivisions > 0)
        name += " after " + std::to_string(subdivisions) + " subdivision round" + (subdivisions > 1 ? "s" : "");
      std::vector<Attempt> group;
      if (!options.reference_chord_splits) group.push_back({order, subdivisions, ChordSplitRule::OnlyAlongOneLine, name});
      group.push_back({order, subdivisions, ChordSplitRule::AfterEveryArc, name + ", reference chord splits"});
      std::vector<std::unique_ptr<TracedAttempt>> traced;
      for (const Attempt& a : group) {
        try {
          traced.push_back(trace_attempt(source, boundary, domain, a, bmin, bmax));
        } catch (const Error& e) {
          if (e.kind() != ErrorKind::Failed) throw;
          failed.push_back(a.name + ": " + e.reason());
        }
      }
      std::stable_sort(traced.begin(), traced.end(), [](const auto& x, const auto& y) { return x->num_tets() < y->num_tets(); });
      for (const auto& t : traced) {
        if (t->num_tets() >= must_beat) return std::nullopt;
        try {
          return finish_attempt(*t, domain);
        } catch (const Error& e) {
          if (e.kind() != ErrorKind::Failed) throw;
          failed.push_back(t->attempt->name + ": " + e.reason());
        }
      }
    }
  return std::nullopt;
}

// The search (first_map) at another placement of the node probes; `best` becomes its map when that
// has fewer tets, with `placement` appended to the attempt's name.
void keep_if_fewer_tets(SourceTetMesh& source, const BoundarySurface& boundary, const Domain& placed,
                        const SurfaceMapOptions& options, const Point3& bmin, const Point3& bmax,
                        const std::string& placement, SurfaceMapResult& best) {
  std::vector<std::string> ignored;
  std::optional<SurfaceMapResult> other =
      first_map(source, boundary, placed, options, bmin, bmax, ignored, best.mesh.num_tets());
  if (!other || other->mesh.num_tets() >= best.mesh.num_tets()) return;
  other->attempt += ", " + placement;
  other->failed_attempts = std::move(best.failed_attempts);
  best = std::move(*other);
}

// Step 6: the search again with the probes rotated; `best` becomes the map with the fewest tets
// (the unrotated one on a tie).
void keep_fewest_tets_over_rotations(SourceTetMesh& source, const BoundarySurface& boundary, const Domain& domain,
                                     const SurfaceMapOptions& options, const Point3& bmin, const Point3& bmax,
                                     SurfaceMapResult& best) {
  for (int r = 1; r < kNumProbeRotations; ++r)
    keep_if_fewer_tets(source, boundary, with_rotated_probes(domain, r), options, bmin, bmax,
                       "probes rotated (" + std::to_string(r) + ")", best);
}

// Step 7: the search again with the probes pulled towards the centre (kProbePulls) and rotated;
// `best` becomes the map with the fewest tets (the earlier one on a tie). It stops at the first map
// that adds at most kPlacementSearchGrowth.
void keep_fewest_tets_over_pulls(SourceTetMesh& source, const BoundarySurface& boundary, const Domain& domain,
                                 const SurfaceMapOptions& options, const Point3& bmin, const Point3& bmax,
                                 std::size_t input_tets, SurfaceMapResult& best) {
  for (double pull : kProbePulls) {
    const Domain pulled = with_pulled_probes(domain, pull);
    for (int r = 0; r < kNumProbeRotations && !adds_at_most(best, input_tets, kPlacementSearchGrowth); ++r)
      keep_if_fewer_tets(source, boundary, with_rotated_probes(pulled, r), options, bmin, bmax,
                         "probes pulled to " + std::to_string(std::lround(100 * pull)) + " % and rotated (" + std::to_string(r) + ")",
                         best);
  }
}

}  // namespace

SurfaceMapResult map_surface_to_domain(const TetMeshData& mesh, const Domain& domain, const SurfaceMapOptions& options) {
  if (mesh.num_tets() == 0) bad_input("the mesh has no tets");
  SourceTetMesh source(mesh);
  require_positive_tets(mesh);
  const BoundarySurface boundary = source.boundary_surface();
  require_sphere_topology(boundary);
  Point3 bmin{mesh.xyz[0], mesh.xyz[1], mesh.xyz[2]}, bmax = bmin;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      bmin[k] = std::min(bmin[k], mesh.xyz[3 * v + k]);
      bmax[k] = std::max(bmax[k], mesh.xyz[3 * v + k]);
    }
  std::vector<std::string> failed;
  std::optional<SurfaceMapResult> best = first_map(source, boundary, domain, options, bmin, bmax, failed);
  if (!best) {
    std::string all;
    for (const auto& f : failed) all += (all.empty() ? "" : "; ") + f;
    throw Error(ErrorKind::Failed, "", 0, "cannot map the boundary onto " + domain.name + " (" + all + ")");
  }
  best->failed_attempts = std::move(failed);
  if (options.search_placements && !options.reference_chord_splits) {
    if (!adds_at_most(*best, mesh.num_tets(), kPlacementSearchGrowth))
      keep_fewest_tets_over_rotations(source, boundary, domain, options, bmin, bmax, *best);
    if (!adds_at_most(*best, mesh.num_tets(), kPlacementSearchGrowth))
      keep_fewest_tets_over_pulls(source, boundary, domain, options, bmin, bmax, mesh.num_tets(), *best);
  }
  return std::move(*best);
}

}  // namespace volmap
