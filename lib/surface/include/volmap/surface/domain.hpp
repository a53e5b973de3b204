// volmap/surface/domain.hpp — base domains of the VOLMAP benchmark (cube, tet, pyr, octa, star),
// user-defined (custom) polyhedral domains read from a file, and polycubes (<volmap/surface/polycube.hpp>).
//
// Conventions (see volmap-reference.md §3):
//  - Nodes are 0-based; every node has a target point (its position on the domain). Nodes of the
//    built-in domains (except the star's face nodes 8..13) and of custom domains have a probe: a point
//    computed from the input's bounding box; the node's surface vertex is the boundary vertex nearest
//    to the probe.
//  - Arcs are traced in the listed order, from `from` to `to`. The star's 6 face diagonals are traced
//    after the 12 cube arcs; each diagonal path is cut in its middle, which becomes node 8+d; its two
//    halves are arcs 12+2d (from -> 8+d) and 13+2d (8+d -> to). Arcs 24..35 come after.
//  - Faces are cyclic node lists, counter-clockwise seen from outside (right-hand rule with the
//    outward normal). `rotation[n]` is the cyclic counter-clockwise order (seen from outside) of the
//    arcs around node n. Both are derived from the target geometry and the kernel point (every
//    domain is star-shaped w.r.t. its kernel; built-ins use the centroid of the targets).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace volmap {

using Point3 = std::array<double, 3>;

enum class DomainKind { Cube, Tet, Pyramid, Octahedron, Star, Custom, Polycube };

struct DomainArc {
  int from = -1;
  int to = -1;
};

// A face diagonal of the star: traced from `from` to `to`, its middle vertex becomes `middle_node`.
struct DomainDiagonal {
  int from = -1;
  int to = -1;
  int middle_node = -1;
  int first_arc = -1;   // from -> middle
  int second_arc = -1;  // middle -> to
};

struct DomainFace {
  std::vector<int> nodes;  // counter-clockwise seen from outside
  std::vector<int> arcs;   // arcs[i] joins nodes[i] and nodes[i+1 mod k]
};

struct Domain {
  DomainKind kind = DomainKind::Custom;
  std::string name;
  std::vector<Point3> targets;                  // one per node
  // Probe of node i = mean of the listed bbox corners (reference corner numbering, §3), unless
  // probe_fraction[i] is set (fractions of the bbox per axis: m + f*(M-m)); empty = no probe (star
  // face nodes, found from the diagonals).
  std::vector<std::vector<int>> probe_corners;
  std::vector<std::array<double, 3>> probe_fraction;  // NaN entries when unused
  std::vector<DomainArc> arcs;                  // all arcs (star: including the diagonal halves)
  std::vector<DomainDiagonal> diagonals;        // star only
  Point3 kernel{};                              // a point the domain is strictly star-shaped around
  std::vector<DomainFace> faces;
  std::vector<std::vector<int>> rotation;       // per node: incident arc ids, CCW from outside
  double size = 0;                              // diagonal of the targets' bounding box

  std::size_t num_nodes() const { return targets.size(); }
  // Custom and polycube domains are judged about their own kernel point; the built-ins about the
  // centroid of the image points (VOLMAP's criterion).
  bool has_fixed_kernel() const { return kind == DomainKind::Custom || kind == DomainKind::Polycube; }
  bool has_probe(int node) const;
  // The probe of `node` for the input bbox [bmin,bmax]. Precondition: has_probe(node).
  Point3 probe(int node, const Point3& bmin, const Point3& bmax) const;
  // Arc ids in tracing order (star: cube arcs, then the diagonals as pairs, then the rest).
  // A diagonal appears once, as its first arc id; the tracer handles both halves.
  std::vector<int> trace_order() const;
};

// The reference's bbox corner numbering (volmap-reference.md §3): corner c takes the minimum (0) or
// the maximum (1) of the bounding box per axis.
inline constexpr int kBboxCornerBits[8][3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0},
                                              {0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}};

// The domain with its node probes turned by one of the 24 rotations of the bounding box about its
// centre (0 = unchanged): the nodes then land on other extremities of the input, in the same cyclic
// arrangement (a proper rotation keeps the orientation). The targets, arcs and faces are unchanged.
inline constexpr int kNumProbeRotations = 24;
Domain with_rotated_probes(const Domain& domain, int rotation);

// The domain with its node probes pulled towards the centre of the bounding box, to `scale` (in
// (0, 1]) of their offset from it: the nodes then land on boundary points nearer the middle of
// the input's extent. The targets, arcs and faces are unchanged.
Domain with_pulled_probes(const Domain& domain, double scale);

// "cube", "tet", "pyr", "octa", "star" (also the reference's upper-case names CUBE, TETRAHEDRON,
// PYRAMID, OCTAHEDRON, STAR). Throws Error(BadInput) for anything else.
Domain builtin_domain(const std::string& name);
bool is_builtin_domain_name(const std::string& name);

// Custom domain file: one directive per line, any whitespace, `#` starts a comment:
//   n i [j ...]   node whose probe is the mean of bbox corners i, j, ... (0..7)
//   nm x y z      target of the k-th node (as many as `n` lines)
//   a i j         arc between nodes i and j (0-based), traced i -> j, in file order
//   k x y z       optional kernel point (default: centroid of the targets)
// Validation (Error(BadInput) with file and line): counts and indices, no duplicate arcs or loops,
// a 3-connected planar graph whose faces (derived from the geometry around the kernel) satisfy
// V - E + F = 2, every face planar and strictly convex, the domain strictly star-shaped w.r.t. the
// kernel. Unknown directives are errors (the reference ignores them; we report the line).
Domain read_custom_domain(const std::string& path);
// Same from text (`source_name` is used in error messages).
Domain parse_custom_domain(const std::string& text, const std::string& source_name);

// A built-in name, `polycube:<cells file or built-in polycube name>` (cell size 100, see
// polycube.hpp) or a custom domain file path.
Domain domain_from_name_or_file(const std::string& name_or_path);

// Derives kernel-relative rotations, faces and size, then validates (shared by built-ins and custom
// domains). Throws Error(BadInput) naming `source` when the domain is invalid.
void finalize_domain(Domain& domain, const std::string& source);

// Closest distance from p to the domain boundary (union of its face polygons).
double distance_to_domain_boundary(const Domain& domain, const Point3& p);

}  // namespace volmap
