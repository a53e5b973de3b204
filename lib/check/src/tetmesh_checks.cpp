// tetmesh_checks.cpp — the seven VOLMAP tet-mesh checks and the five surface checks
// (see tetmesh_checks.hpp). Orientation uses the exact batch orient3d_tets over every tet; topology
// comes from analyze_topology (raw arrays, robust to non-manifold input); the boundary triangles are
// the boundary half-faces 4t+i listed with kTetFace[i] (outward for VOLMAP-positive tets) and go
// through the exact self-intersection test.
#include <volmap/check/tetmesh_checks.hpp>

#include <volmap/core/error.hpp>
#include <volmap/core/local_tables.hpp>

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace volmap {
namespace {

std::string fmt(std::size_t n) { return std::to_string(n); }

std::string self_intersection_detail(const SelfIntersectionResult& r) {
  if (r.clean()) return "no self-intersections";
  std::string s;
  if (r.intersecting_pairs > 0) {
    s += fmt(r.intersecting_pairs) + " intersecting triangle pairs";
    if (!r.first_pairs.empty())
      s += " (first: " + fmt(r.first_pairs[0].first) + "-" + fmt(r.first_pairs[0].second) + ")";
  }
  if (r.coincident_vertices > 0) {
    if (!s.empty()) s += ", ";
    s += fmt(r.coincident_vertices) + " coincident vertex pairs";
    if (!r.first_coincident.empty())
      s += " (first: " + fmt(r.first_coincident[0].first) + "=" + fmt(r.first_coincident[0].second) + ")";
  }
  if (r.degenerate_triangles > 0) {
    if (!s.empty()) s += ", ";
    s += fmt(r.degenerate_triangles) + " degenerate triangles";
  }
  return s;
}

const CheckItem& find_check(const std::vector<CheckItem>& checks, const std::string& key) {
  for (const CheckItem& c : checks)
    if (c.key == key) return c;
  throw std::out_of_range("no check named " + key);
}

}  // namespace

bool TetMeshCheckReport::all_passed() const {
  if (checks.empty()) return false;
  for (const CheckItem& c : checks)
    if (!c.passed) return false;
  return true;
}
const CheckItem& TetMeshCheckReport::check(const std::string& key) const { return find_check(checks, key); }
bool SurfaceCheckReport::all_passed() const {
  if (checks.empty()) return false;
  for (const CheckItem& c : checks)
    if (!c.passed) return false;
  return true;
}
const CheckItem& SurfaceCheckReport::check(const std::string& key) const { return find_check(checks, key); }

void flip_all_tets(TetMeshData& mesh) {
  for (std::size_t t = 0; t + 4 <= mesh.tets.size(); t += 4) std::swap(mesh.tets[t], mesh.tets[t + 1]);
}

TetMeshCheckReport check_tet_mesh(const TetMeshData& mesh, const TetMeshCheckOptions& options) {
  if (mesh.xyz.size() % 3 != 0) throw Error(ErrorKind::BadInput, "coordinate array size is not a multiple of 3");
  if (mesh.tets.size() % 4 != 0) throw Error(ErrorKind::BadInput, "tet array size is not a multiple of 4");
  TetMeshCheckReport r;
  r.num_vertices = mesh.num_vertices();
  r.num_tets = mesh.num_tets();

  // Orientation (exact, every tet) and topology are independent: run them side by side.
  tbb::parallel_invoke(
      [&] { r.signs = orient3d_tets(mesh.xyz.data(), r.num_vertices, mesh.tets.data(), r.num_tets, nullptr); },
      [&] { r.topology = analyze_topology(mesh); });
  if (!r.signs.ok) throw Error(ErrorKind::BadInput, std::string("orientation: ") + r.signs.error);

  // Boundary triangles (outward for VOLMAP-positive tets) -> exact self-intersection test.
  const TopologyReport& topo = r.topology;
  std::vector<std::uint32_t> boundary_tris(3 * topo.boundary_half_faces.size());
  for (std::size_t f = 0; f < topo.boundary_half_faces.size(); ++f) {
    const std::uint32_t hf = topo.boundary_half_faces[f];
    const std::uint32_t* tet = &mesh.tets[4 * std::size_t(hf / 4)];
    for (int k = 0; k < 3; ++k) boundary_tris[3 * f + k] = tet[kTetFace[hf % 4][k]];
  }
  r.self_intersections = find_self_intersections(mesh.xyz.data(), r.num_vertices, boundary_tris.data(),
                                                 topo.boundary_half_faces.size(), options.self_intersection);

  const TetSignCounts& s = r.signs;
  r.orientation = classify_orientation(s);
  // 1. orientation
  r.checks.push_back({"orientation", r.orientation == OrientationClass::AllPositive, describe_orientation(s, "--fix")});
  // 2. volume
  r.checks.push_back({"volume", s.zero == 0 && r.num_tets > 0,
                      r.num_tets == 0 ? std::string("no tets")
                                      : fmt(s.zero) + " zero-volume tets of " + fmt(r.num_tets) +
                                            (topo.num_degenerate_tets ? " (" + fmt(topo.num_degenerate_tets) + " repeat a vertex id)" : "")});
  // 3. genus
  {
    CheckItem c{"genus", topo.boundary_genus_defined && topo.boundary_genus == 0 && topo.num_boundary_faces > 0, ""};
    const std::string chi = "chi=" + std::to_string(topo.boundary_euler);
    if (topo.num_boundary_faces == 0)
      c.detail = "no boundary faces";
    else if (topo.boundary_genus_defined)
      c.detail = "boundary genus " + std::to_string(topo.boundary_genus) + " (" + chi + ", " + fmt(topo.num_boundary_components) + " components)";
    else
      c.detail = "genus undefined: boundary is not a closed 2-manifold (" + chi + ")";
    r.checks.push_back(c);
  }
  // 4. components
  r.checks.push_back({"components",
                      topo.num_tet_components == 1 && topo.num_boundary_components == 1 && topo.num_unused_vertices == 0,
                      fmt(topo.num_tet_components) + " tet components, " + fmt(topo.num_boundary_components) +
                          " boundary components, " + fmt(topo.num_unused_vertices) + " vertices in no tet"});
  // 5. manifold
  r.checks.push_back({"manifold",
                      topo.num_nonmanifold_faces == 0 && topo.num_overshared_edges == 0 &&
                          topo.num_nonmanifold_boundary_vertices == 0,
                      fmt(topo.num_nonmanifold_faces) + " faces on >2 tets, " + fmt(topo.num_overshared_edges) +
                          " boundary edges on >2 faces, " + fmt(topo.num_nonmanifold_boundary_vertices) +
                          " non-manifold boundary vertices"});
  // 6. closed
  r.checks.push_back({"closed", topo.num_border_edges == 0 && topo.num_boundary_faces > 0,
                      topo.num_boundary_faces == 0 ? std::string("no boundary faces")
                                                   : fmt(topo.num_border_edges) + " border edges (" +
                                                         fmt(topo.num_boundary_faces) + " boundary faces, " +
                                                         fmt(topo.num_boundary_edges) + " edges, " +
                                                         fmt(topo.num_boundary_vertices) + " vertices)"});
  // 7. self-intersections
  r.checks.push_back({"self_intersections", r.self_intersections.clean() && topo.num_boundary_faces > 0,
                      self_intersection_detail(r.self_intersections)});
  return r;
}

// ------------------------------------------------------------------------------------ surfaces --
SurfaceCheckReport check_triangle_surface(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tris,
                                          const SelfIntersectionOptions& options) {
  if (xyz.size() % 3 != 0) throw Error(ErrorKind::BadInput, "coordinate array size is not a multiple of 3");
  SurfaceCheckReport r;
  r.topology = analyze_surface_topology(xyz.size() / 3, tris);
  r.self_intersections = find_self_intersections(xyz, tris, options);
  const SurfaceTopology& st = r.topology;
  const std::string chi = "chi=" + std::to_string(st.euler);
  {
    CheckItem c{"genus", st.genus_defined && st.genus == 0, ""};
    if (st.num_triangles == 0)
      c.detail = "no triangles";
    else if (st.genus_defined)
      c.detail = "genus " + std::to_string(st.genus) + " (" + chi + ", " + fmt(st.num_components) + " components)";
    else
      c.detail = "genus undefined: not a closed 2-manifold (" + chi + ")";
    r.checks.push_back(c);
  }
  r.checks.push_back({"components", st.num_components == 1,
                      fmt(st.num_components) + " components (" + fmt(st.num_used_vertices) + " of " +
                          fmt(st.num_vertices) + " vertices used)"});
  r.checks.push_back({"manifold",
                      st.num_overshared_edges == 0 && st.num_nonmanifold_vertices == 0 && st.num_repeated_id_triangles == 0 &&
                          st.num_triangles > 0,
                      fmt(st.num_overshared_edges) + " edges on >2 triangles, " + fmt(st.num_nonmanifold_vertices) +
                          " non-manifold vertices, " + fmt(st.num_repeated_id_triangles) +
                          " triangles repeating a vertex, " + fmt(st.num_inconsistent_edges) +
                          " inconsistently oriented edges"});
  r.checks.push_back({"closed", st.num_border_edges == 0 && st.num_triangles > 0,
                      fmt(st.num_border_edges) + " border edges (" + fmt(st.num_triangles) + " triangles, " +
                          fmt(st.num_edges) + " edges)"});
  r.checks.push_back({"self_intersections", r.self_intersections.clean() && st.num_triangles > 0,
                      self_intersection_detail(r.self_intersections)});
  return r;
}

SurfaceCheckReport check_surface(const SurfaceData& surface, const SelfIntersectionOptions& options) {
  return check_triangle_surface(surface.xyz, surface.tris, options);
}

}  // namespace volmap
