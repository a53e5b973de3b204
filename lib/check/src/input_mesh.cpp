// Input-mesh validation (input_mesh.hpp): the seven checks of check_tet_mesh, the winding of interior
// faces and duplicate tets, turned into sentences. Example offenders (first zero/negative tet, first
// tet repeating a vertex) are looked up only when the matching count is nonzero; duplicate tets (among
// tets of four distinct vertices) come with the topology report.
#include <volmap/check/input_mesh.hpp>

#include <volmap/check/orientation.hpp>

#include <volmap/core/error.hpp>
#include <volmap/core/local_tables.hpp>

#include <algorithm>

namespace volmap {
namespace {

std::string fmt(std::size_t n) { return std::to_string(n); }
std::string plural(std::size_t n, const char* one, const char* many) { return fmt(n) + " " + (n == 1 ? one : many); }

std::string half_face(std::uint32_t hf) {
  return "face " + fmt(hf % 4) + " of tet " + fmt(hf / 4);
}

// First tet repeating a vertex id (kInvalid when none).
std::size_t first_repeating_tet(const TetMeshData& mesh) {
  for (std::size_t t = 0; t < mesh.num_tets(); ++t) {
    const std::uint32_t* p = &mesh.tets[4 * t];
    if (p[0] == p[1] || p[0] == p[2] || p[0] == p[3] || p[1] == p[2] || p[1] == p[3] || p[2] == p[3]) return t;
  }
  return mesh.num_tets();
}

// The first tet whose exact sign is `sign` (or 0 when there is none).
std::size_t first_tet_with_sign(const TetMeshData& mesh, int sign) {
  std::vector<std::int8_t> signs(mesh.num_tets());
  orient3d_tets(mesh.xyz.data(), mesh.num_vertices(), mesh.tets.data(), mesh.num_tets(), signs.data());
  for (std::size_t t = 0; t < signs.size(); ++t)
    if (signs[t] == sign) return t;
  return 0;
}

void add_structure_problems(const TetMeshData& mesh, const TopologyReport& topo, std::vector<std::string>& out) {
  if (topo.num_degenerate_tets)
    out.push_back(plural(topo.num_degenerate_tets, "tet uses", "tets use") + " a vertex twice (first: tet " +
                  fmt(first_repeating_tet(mesh)) + ")");
  if (topo.num_duplicate_tets)
    out.push_back(plural(topo.num_duplicate_tets, "tet repeats", "tets repeat") + " the four vertices of another (first: tets " +
                  fmt(topo.example_duplicate_first) + " and " + fmt(topo.example_duplicate_second) + ")");
  if (topo.num_nonmanifold_faces)
    out.push_back(plural(topo.num_nonmanifold_faces, "face is", "faces are") + " shared by more than two tets (first: " +
                  half_face(topo.example_nonmanifold_face) + ")");
  if (topo.num_unused_vertices) {
    std::vector<char> used(mesh.num_vertices(), 0);
    for (std::uint32_t v : mesh.tets) used[v] = 1;
    const std::size_t first = static_cast<std::size_t>(std::find(used.begin(), used.end(), 0) - used.begin());
    out.push_back(plural(topo.num_unused_vertices, "vertex belongs", "vertices belong") + " to no tet (first: vertex " +
                  fmt(first) + ")");
  }
  if (topo.num_tet_components > 1)
    out.push_back("the tets form " + fmt(topo.num_tet_components) +
                  " separate pieces (connected through faces); a map needs one piece");
}

void add_boundary_problems(const TopologyReport& topo, std::vector<std::string>& out) {
  if (topo.num_boundary_faces == 0) {
    out.push_back("it has no boundary faces");
    return;
  }
  if (topo.num_border_edges)
    out.push_back("the boundary has holes: " + plural(topo.num_border_edges, "edge lies", "edges lie") +
                  " on a single boundary face (first at vertex " + fmt(topo.example_nonmanifold_edge_vertex) + ")");
  if (topo.num_overshared_edges)
    out.push_back(plural(topo.num_overshared_edges, "boundary edge lies", "boundary edges lie") +
                  " on more than two boundary faces (first at vertex " + fmt(topo.example_nonmanifold_edge_vertex) + ")");
  if (topo.num_nonmanifold_boundary_vertices)
    out.push_back("the boundary pinches at " + plural(topo.num_nonmanifold_boundary_vertices, "vertex", "vertices") +
                  " (first: vertex " + fmt(topo.example_nonmanifold_vertex) + ")");
  if (topo.num_boundary_components > 1)
    out.push_back("the boundary consists of " + fmt(topo.num_boundary_components) +
                  " separate surfaces (a cavity or a second piece); a map needs one");
  if (topo.boundary_genus_defined && topo.boundary_genus != 0)
    out.push_back("the boundary has genus " + std::to_string(topo.boundary_genus) +
                  " (handles or tunnels); only genus 0 maps onto a ball-like domain");
}

void add_orientation_problems(const TetMeshData& mesh, const TetMeshCheckReport& r, std::vector<std::string>& out) {
  const TetSignCounts& s = r.signs;
  if (r.num_tets == 0) return;
  if (s.positive == 0 && s.negative > 0) {
    out.push_back(describe_orientation(s, "volmap-tetmesh-check --fix"));  // the opposite convention, in words
  } else if (s.negative > 0) {
    out.push_back(plural(s.negative, "tet is", "tets are") + " inverted among " + fmt(r.num_tets) +
                  " (exact orient3d < 0; first: tet " + fmt(first_tet_with_sign(mesh, -1)) +
                  "): the mesh is tangled, not fixable by a global flip");
  }
  const TopologyReport& topo = r.topology;
  if (topo.num_inconsistent_faces)
    out.push_back(plural(topo.num_inconsistent_faces, "interior face is", "interior faces are") +
                  " wound the same way by both of its tets, so their orientations disagree (first: " +
                  half_face(topo.example_inconsistent_face) + ")");
  if (s.zero > 0 && r.topology.num_degenerate_tets < s.zero)
    out.push_back(plural(s.zero, "tet is", "tets are") + " flat (zero volume, exact; first: tet " +
                  fmt(first_tet_with_sign(mesh, 0)) + ")");
}

void add_embedding_problems(const SelfIntersectionResult& si, std::vector<std::string>& out) {
  if (si.coincident_vertices)
    out.push_back(plural(si.coincident_vertices, "pair", "pairs") + " of boundary vertices sit at the same point" +
                  (si.first_coincident.empty() ? std::string()
                                               : " (first: vertices " + fmt(si.first_coincident[0].first) + " and " +
                                                     fmt(si.first_coincident[0].second) + ")") +
                  ": the mesh touches or duplicates itself");
  if (si.intersecting_pairs)
    out.push_back("the boundary intersects itself: " + plural(si.intersecting_pairs, "pair", "pairs") +
                  " of boundary triangles cross" +
                  (si.first_pairs.empty() ? std::string()
                                          : " (first: boundary triangles " + fmt(si.first_pairs[0].first) + " and " +
                                                fmt(si.first_pairs[0].second) + ")"));
  if (si.degenerate_triangles)
    out.push_back(plural(si.degenerate_triangles, "boundary triangle is", "boundary triangles are") +
                  " degenerate (collinear corners)");
}

}  // namespace

std::string InputMeshVerdict::reason() const {
  if (problems.empty()) return "";
  std::string r = problems.front();
  if (problems.size() > 1) r += "; and " + plural(problems.size() - 1, "more problem", "more problems");
  return r;
}

InputMeshVerdict judge_input_mesh(const TetMeshData& mesh) {
  InputMeshVerdict v;
  v.report = check_tet_mesh(mesh);
  const TetMeshCheckReport& r = v.report;
  if (r.num_tets == 0) {
    v.problems.push_back("it has no tets");
  } else {
    add_structure_problems(mesh, r.topology, v.problems);
    add_boundary_problems(r.topology, v.problems);
    add_embedding_problems(r.self_intersections, v.problems);
    const std::size_t before_orientation = v.problems.size();
    add_orientation_problems(mesh, r, v.problems);
    v.valid_up_to_orientation = before_orientation == 0 && r.signs.zero == 0 && r.topology.num_degenerate_tets == 0;
  }
  // The seven checks decide too: a failed check without a sentence above still makes the mesh invalid.
  for (const CheckItem& c : r.checks)
    if (!c.passed && v.problems.empty()) {
      v.problems.push_back(c.key + " check failed: " + c.detail);
      v.valid_up_to_orientation = false;
    }
  v.valid = v.problems.empty();
  v.valid_up_to_orientation = v.valid_up_to_orientation || v.valid;
  return v;
}

void require_valid_input_mesh(const TetMeshData& mesh, const std::string& path) {
  InputMeshVerdict v;
  try {
    v = judge_input_mesh(mesh);
  } catch (const Error& e) {
    if (!e.file().empty()) throw;
    throw Error(e.kind(), path, 0, e.reason());
  }
  if (!v.valid) throw Error(ErrorKind::BadInput, path, 0, "not a valid input tet mesh: " + v.reason());
}

}  // namespace volmap
