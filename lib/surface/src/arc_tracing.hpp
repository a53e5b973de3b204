// Embedding the domain's graph in the working surface (internal to lib/surface; the algorithm is
// volmap-reference.md §4.2, steps 1-3): node vertices, arc paths and the chord splits between them.
// Conventions: arcs run from `from` to `to` (DomainArc); a path lists its vertices in that order;
// the star's face diagonals are traced as one path each and cut at floor(|p|/2) (Domain::diagonals).
#pragma once

#include "working_surface.hpp"

#include <volmap/surface/domain.hpp>
#include <volmap/surface/surface_map.hpp>

#include <cstddef>
#include <vector>

namespace volmap::surface_detail {

struct EmbeddedGraph {
  std::vector<VertexHandle> node_vertex;            // per domain node
  std::vector<std::vector<VertexHandle>> arc_path;  // per domain arc, from -> to
  std::size_t collided_nodes = 0;                   // nodes whose nearest vertex an earlier node took
};

// Places every probed node on the boundary vertex nearest to its probe in the input's bounding box
// [bmin, bmax] (ties to the smallest vid, vertices taken by earlier nodes skipped), then traces the
// arcs in `order` (Domain::trace_order or spanning_tree_first_order): shortest paths over free
// vertices, leaving and entering each node inside the sector its rotation leaves between the arcs
// already traced there. Chords (edges joining two graph vertices that are not arc edges) are split
// by `rule` (ChordSplitRule in surface_map.hpp). Labels the surface (on_graph, arc_label). Throws
// Error(Failed) naming the arc when no path exists.
EmbeddedGraph embed_domain_graph(WorkingSurface& surface, const Domain& domain, const std::vector<int>& order,
                                 ChordSplitRule rule, const Point3& bmin, const Point3& bmax);

// Throws Error(Failed) unless the arcs leave every node in the domain's cyclic order.
void check_rotations(const WorkingSurface& surface, const Domain& domain, const EmbeddedGraph& graph);

// Tracing order with a spanning tree of the probed nodes first (BFS from node 0 over the arcs joining
// two probed nodes, in domain order), then every other arc in the domain's order. With the traced
// graph connected and holding every probed node from the start, a correct rotation at every node
// keeps the partial embedding equivalent to the domain's, so no later arc finds its face cut off (the
// reference order can close a cycle, e.g. the octahedron's equator, with two untraced nodes on the
// wrong side).
std::vector<int> spanning_tree_first_order(const Domain& domain);

}  // namespace volmap::surface_detail
