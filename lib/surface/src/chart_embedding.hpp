// Charts of the embedded domain graph and their planar embedding (internal to lib/surface; the
// algorithm is volmap-reference.md §4.2 step 6).
// Conventions: the image of surface vertex v is img[3*v.idx() .. +3]; nodes sit exactly on their
// targets, arc vertices on the straight segment between their nodes' targets spaced by arc length,
// chart vertices in the plane of their domain face (up to rounding).
#pragma once

#include "arc_tracing.hpp"
#include "working_surface.hpp"

#include <volmap/surface/domain.hpp>

#include <vector>

namespace volmap::surface_detail {

// Floods the faces between arcs into charts (face property `chart`), matches every chart to the
// domain face on the left of its arcs and embeds it: Tutte's barycentric embedding in the face plane
// with the chart boundary on the convex face polygon. When rounding leaves a triangle of a chart
// not strictly positive in its plane or about the check's kernel (the domain's kernel point, or the
// centroid of the image points for the built-ins; long thin parts of the surface shrink
// exponentially under Tutte's uniform weights), the chart is re-solved with stretch-reducing
// positive weights (any positive weights embed a disk on a convex polygon) until it is. Throws Error(Failed) when the charts do not match the domain's faces
// one to one or a chart stays invalid.
std::vector<double> embed_charts(WorkingSurface& surface, const Domain& domain, const EmbeddedGraph& graph);

}  // namespace volmap::surface_detail
