// B0 (docs/mapping.md §4): blocking chords removed by flips or cone patches where admissible, split
// otherwise. Generated cases: a Kuhn cube and a cube coned from a corner (no interior vertex) whose
// boundary is projected onto a regular tetrahedron (their blocking chord edges join two points of one
// facet of the image), a bipyramid whose middle face lies in a facet of the target, cones over
// single vertex stars, one cone region over a convex box with no interior vertex. Oracles
// independent of ChordRules: membership in the planes of all boundary image triangles, exact
// positivity (check_invariants), the oriented boundary before and after, and the old split-only B0
// (split_chords) as the growth to beat; the mapper must certify.
#include <doctest/doctest.h>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/volume/chord_cone.hpp>
#include <volmap/volume/chord_split.hpp>
#include <volmap/volume/feasibility.hpp>
#include <volmap/volume/map_stages.hpp>
#include <volmap/volume/map_state.hpp>
#include <volmap/volume/volume_map.hpp>
#include <volmap/predicates.hpp>

#include "map_test_meshes.hpp"
#include "mesh_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace {

using Plane = std::array<double, 4>;  // n·x <= d, unit n, about the cube centre

// A regular tetrahedron around the centre of the unit cube, inradius 0.5.
std::vector<Plane> tetrahedron() {
  const double s = 1 / std::sqrt(3.0);
  return {{s, s, s, 0.5}, {s, -s, -s, 0.5}, {-s, s, -s, 0.5}, {-s, -s, s, 0.5}};
}

// The boundary of the Kuhn cube projected from its centre onto the polytope.
volmap::BoundaryMap projected_map(const volmap::TetMeshData& m, const std::vector<Plane>& planes) {
  volmap::BoundaryMap map;
  for (std::uint32_t v : volmap::boundary_vertex_ids(m)) {
    double u[3], t = 1e300;
    for (int i = 0; i < 3; ++i) u[i] = m.xyz[3 * v + i] - 0.5;
    for (const Plane& h : planes) {
      const double d = h[0] * u[0] + h[1] * u[1] + h[2] * u[2];
      if (d > 0) t = std::min(t, h[3] / d);
    }
    map.vids.push_back(v);
    for (int i = 0; i < 3; ++i) map.xyz.push_back(0.5 + t * u[i]);
  }
  return map;
}

// Interior edges with both ends locked whose images lie in the plane of one boundary image triangle
// (distance < 1e-9): the image polyhedron is convex here, so such an edge's image runs in its
// boundary. (Not the tetrahedron's four facets: a boundary triangle whose corners land on two facets
// cuts a corner of the tetrahedron, and its plane is a facet of the image polyhedron.)
std::size_t edges_in_boundary_planes(const volmap::TetMesh& mesh, const std::vector<std::uint8_t>& locked,
                                     const std::vector<double>& target) {
  auto P = [&](std::uint32_t v) { return &target[3 * std::size_t(v)]; };
  std::vector<std::array<double, 4>> planes;  // unit normal, offset
  for (volmap::HalfFaceId h : mesh.boundary_half_faces()) {
    const auto f = mesh.half_face_vertices(h);
    const double *a = P(f[0].idx()), *b = P(f[1].idx()), *c = P(f[2].idx());
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n) x /= len;
    planes.push_back({n[0], n[1], n[2], n[0] * a[0] + n[1] * a[1] + n[2] * a[2]});
  }
  auto on = [&](std::uint32_t v, const std::array<double, 4>& h) {
    return std::abs(h[0] * P(v)[0] + h[1] * P(v)[1] + h[2] * P(v)[2] - h[3]) < 1e-9;
  };
  std::size_t n = 0;
  for (std::size_t e = 0; e < mesh.num_edges(); ++e) {
    const auto ends = mesh.edge_vertices(volmap::EdgeId(std::uint32_t(e)));
    const std::uint32_t a = ends[0].idx(), b = ends[1].idx();
    if (!locked[a] || !locked[b] || !mesh.edge_star(volmap::EdgeId(std::uint32_t(e)), [](volmap::TetId) {})) continue;
    n += std::any_of(planes.begin(), planes.end(), [&](const auto& h) { return on(a, h) && on(b, h); });
  }
  return n;
}

// The unit cube as the cone from its corner (0,0,0) over the triangles of its three far faces (those
// of the n×n×n Kuhn grid's boundary on x = 1, y = 1 or z = 1): every vertex on the boundary, every
// interior edge and face a chord.
volmap::TetMeshData corner_cone_cube(int n) {
  const volmap::TetMeshData grid = map_test::kuhn_grid(n);
  const volmap::TetMesh g(grid);
  std::vector<std::uint32_t> id(grid.num_vertices(), volmap::kInvalidIndex);
  volmap::TetMeshData out;
  auto vertex = [&](std::uint32_t v) {
    if (id[v] == volmap::kInvalidIndex) {
      id[v] = std::uint32_t(out.num_vertices());
      out.xyz.insert(out.xyz.end(), &grid.xyz[3 * v], &grid.xyz[3 * v] + 3);
    }
    return id[v];
  };
  const std::uint32_t corner = vertex(0);  // (0,0,0)
  for (volmap::HalfFaceId h : g.boundary_half_faces()) {
    const auto f = g.half_face_vertices(h);
    bool far = false;
    for (int axis = 0; axis < 3; ++axis)
      far = far || std::all_of(f.begin(), f.end(), [&](volmap::VertexId v) { return grid.xyz[3 * v.idx() + axis] == 1.0; });
    if (far) out.tets.insert(out.tets.end(), {vertex(f[0].idx()), vertex(f[1].idx()), vertex(f[2].idx()), corner});
  }
  return out;
}

}  // namespace

TEST_CASE("B0: a coarse cube onto a tetrahedron — chord edges inside a facet are flipped away, not split, and the map certifies") {
  const volmap::TetMeshData cube = map_test::kuhn_grid(2);  // 48 tets, one interior vertex
  const auto planes = tetrahedron();
  const volmap::BoundaryMap map = projected_map(cube, planes);
  volmap::MapState state(cube, map);
  const std::vector<std::uint8_t> locked = state.locked.data();
  const volmap::FeasibilityReport report = volmap::analyze_feasibility(state);
  const std::size_t within = edges_in_boundary_planes(state.source, locked, state.target_xyz());
  REQUIRE(within > 0);
  CHECK(report.blocking_chord_edges.size() == within);
  CHECK(!report.fixed_nonpositive_tets.empty());

  // The old B0 splits every blocking chord: one new tet per tet around each edge.
  volmap::TetMesh split_only(state.source);
  const auto old_b0 = volmap::split_chords(split_only, report.blocking_chord_edges, report.blocking_chord_faces);
  CHECK(old_b0.tets_after > cube.num_tets() + within);

  const auto boundary = mesh_test::oriented_boundary(state.source);
  const auto b0 = volmap::remove_blocking_chords(state, report);
  MESSAGE("coarse cube -> tet: " << within << " blocking chord edges; split-only B0 " << old_b0.tets_after << " tets, flips "
                                  << b0.tets_after << " (removed " << b0.edges_removed << ", split " << b0.edges_split << ")");
  CHECK(b0.edges_removed > 0);
  CHECK(b0.tets_after < old_b0.tets_after);
  // The refined source is a valid tet mesh with the same boundary and no blocking simplex left.
  const volmap::InvariantReport inv = state.source.check_invariants(true);
  INFO(inv.problem);
  CHECK(inv.ok);
  CHECK(mesh_test::oriented_boundary(state.source) == boundary);
  std::vector<std::uint8_t> locked_now = state.locked.data();
  CHECK(edges_in_boundary_planes(state.source, locked_now, state.target_xyz()) == 0);
  const volmap::FeasibilityReport after = volmap::analyze_feasibility(state);
  CHECK(after.blocking_chord_edges.empty());
  CHECK(after.blocking_chord_faces.empty());
  CHECK(after.fixed_nonpositive_tets.empty());

  volmap::VolumeMapOptions options;
  options.max_threads = 1;
  const auto r = volmap::compute_volume_map(cube, map, options);
  CHECK(r.certified);
  CHECK(r.chord_edges_removed == b0.edges_removed);
  CHECK(r.source.num_tets() < old_b0.tets_after);
  CHECK(volmap::count_nonpositive(r.source.xyz, r.source.tets) == 0);
  CHECK(volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0);
}

TEST_CASE("B0: a bipyramid whose middle face lies in a facet — one 2-3 flip instead of a face split, certified without a new vertex") {
  // Source: tets (a,b,c,d) and (c,b,a,e), d below and e above the triangle abc. Target: the
  // tetrahedron (a,b,c,e) with d mapped into its face abc, so the face abc blocks and (a,b,c,d) is
  // flat; the segment de crosses abc, so the 2-3 flip gives three tets, all fixed and positive.
  volmap::TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, -1, 0.3, 0.3, 1};
  m.tets = {0, 1, 2, 3, 2, 1, 0, 4};
  std::vector<double> target = m.xyz;
  target[3 * 3 + 2] = 0;  // d -> (0.3, 0.3, 0), inside the face abc
  const std::vector<std::uint8_t> all(5, 1);
  const auto map = map_test::boundary_map_of(all, target);
  volmap::MapState state(m, map);
  const auto report = volmap::analyze_feasibility(state);
  REQUIRE(report.blocking_chord_faces.size() == 1);
  CHECK(report.fixed_nonpositive_tets.size() == 1);
  volmap::TetMesh split_only(state.source);
  CHECK(volmap::split_chords(split_only, {}, report.blocking_chord_faces).tets_after == 6);
  const auto b0 = volmap::remove_blocking_chords(state, report);
  CHECK(b0.faces_flipped == 1);
  CHECK(b0.faces_split == 0);
  CHECK(b0.tets_after == 3);
  CHECK(b0.vertices_added == 0);
  CHECK(state.source.check_invariants(true).ok);
  const auto after = volmap::analyze_feasibility(state);
  CHECK(after.blocking_chord_faces.empty());
  CHECK(after.fixed_nonpositive_tets.empty());
  CHECK(after.chord_edges.size() == 1);  // the new edge de, whose image runs inside the target
  CHECK(after.blocking_chord_edges.empty());

  const auto r = volmap::compute_volume_map(m, map);
  CHECK(r.certified);
  CHECK(r.source.num_tets() == 3);
  CHECK(r.source.num_vertices() == 5);
}

TEST_CASE("B0 cone patch over one star: the star of a boundary vertex becomes the cone from one interior vertex, +1 tet per face of ∂M at it") {
  const volmap::TetMeshData grid = map_test::kuhn_grid(3);
  const auto bnd = map_test::grid_boundary_flags(3);
  int coned = 0;
  for (std::uint32_t v = 0; v < grid.num_vertices(); ++v) {
    if (!bnd[v]) continue;
    volmap::TetMesh m(grid);
    const auto boundary = mesh_test::oriented_boundary(m);
    std::vector<volmap::TetId> star;
    m.vertex_star(volmap::VertexId(v), star);
    const std::size_t s = volmap::boundary_faces_at(m, v);
    // Brute force: the faces of ∂M (tets' boundary half-faces) through v.
    std::size_t brute = 0;
    for (volmap::HalfFaceId h : m.boundary_half_faces())
      for (volmap::VertexId x : m.half_face_vertices(h)) brute += x.idx() == v;
    CHECK(s == brute);
    if (!volmap::cone_vertex_star(m, v)) continue;  // no verified strict kernel point: left alone
    ++coned;
    const volmap::InvariantReport inv = m.check_invariants(true);
    INFO(inv.problem);
    CHECK(inv.ok);
    CHECK(m.num_tets() == grid.num_tets() + s);
    CHECK(m.num_vertices() == grid.num_vertices() + 1);
    CHECK(mesh_test::oriented_boundary(m) == boundary);
    const volmap::VertexId w(std::uint32_t(grid.num_vertices()));
    CHECK(!m.vertex_is_boundary(w));
    // Every edge left at v is an edge of ∂M (or the one to w): no interior edge of v's old star.
    m.vertex_star(volmap::VertexId(v), star);
    CHECK(star.size() == s);
    for (volmap::TetId t : star) CHECK(m.tet_local_index(t, w) >= 0);
  }
  MESSAGE("coned " << coned << " boundary vertices of the 3x3x3 Kuhn cube");
  CHECK(coned > 0);
}

TEST_CASE("B0 cone patch: a cube coned from a corner (no interior vertex) onto a tetrahedron — no flip helps, one cone does") {
  const volmap::TetMeshData cube = corner_cone_cube(4);  // 96 tets, 62 vertices, all on the boundary
  REQUIRE(cube.num_tets() == 96);
  const volmap::BoundaryMap map = projected_map(cube, tetrahedron());
  volmap::MapState state(cube, map);
  const auto report = volmap::analyze_feasibility(state);
  const std::size_t within = edges_in_boundary_planes(state.source, state.locked.data(), state.target_xyz());
  REQUIRE(within > 0);
  CHECK(report.blocking_chord_edges.size() == within);
  volmap::TetMesh split_only(state.source);
  const auto old_b0 = volmap::split_chords(split_only, report.blocking_chord_edges, report.blocking_chord_faces);
  const auto boundary = mesh_test::oriented_boundary(state.source);
  const std::size_t faces_of_boundary = boundary.size();
  const auto b0 = volmap::remove_blocking_chords(state, report);
  MESSAGE("corner-coned cube -> tet: split-only B0 " << old_b0.tets_after << " tets, B0 " << b0.tets_after << " (cone patches "
                                                      << b0.cone_patches << ", removals " << b0.edges_removed << ", splits "
                                                      << b0.edges_split + b0.faces_split << ")");
  CHECK(b0.cone_patches >= 1);
  CHECK(b0.tets_after < old_b0.tets_after);
  // The whole cube is star-shaped: one patch from an interior point over the 120 faces of ∂M.
  CHECK(b0.tets_after == faces_of_boundary);
  CHECK(b0.vertices_added == b0.cone_patches);
  CHECK(state.source.check_invariants(true).ok);
  CHECK(mesh_test::oriented_boundary(state.source) == boundary);
  CHECK(edges_in_boundary_planes(state.source, state.locked.data(), state.target_xyz()) == 0);
  const auto after = volmap::analyze_feasibility(state);
  CHECK(after.blocking_chord_edges.empty());
  CHECK(after.blocking_chord_faces.empty());

  volmap::VolumeMapOptions options;
  options.max_threads = 1;
  const auto r = volmap::compute_volume_map(cube, map, options);
  CHECK(r.certified);
  CHECK(r.chord_cone_patches == b0.cone_patches);
  CHECK(r.source.num_tets() < old_b0.tets_after);
}

TEST_CASE("B0 cone region: on a convex box with every vertex on the boundary, one region takes the stars of all 98 vertices") {
  // A Kuhn grid of 6×6×1 cells stretched to a cube: 216 tets, 98 vertices, none inside. With every
  // vertex carrying a costly pending chord, the region grows star by star until a limit or the shape
  // rule stops it; the box is convex, so the default limits must let one cone replace all of it (192
  // tets, one per boundary face). The limits of an earlier B0 (400 tets, 24 stars) stop after 66
  // vertices: on coarse meshes that left many small hubs whose couplings stalled the repair
  // (docs/mapping.md §4).
  volmap::TetMeshData box = volmap::generate_kuhn_grid(6, 6, 1);
  for (std::size_t v = 0; v < box.num_vertices(); ++v) box.xyz[3 * v + 2] *= 6;  // a cube of 6×6×1 cells, 1×1×6 each
  REQUIRE(box.num_tets() == 216);
  struct Patch {
    std::size_t vertices = 0, tets = 0;  // R's vertices; the mesh's tets after the patch
  };
  auto cone_from_vertex_0 = [&](const volmap::ConeRegionLimits& limits) {
    volmap::TetMesh mesh(box);
    const auto boundary = mesh_test::oriented_boundary(mesh);
    const volmap::PendingChordsAt chords = [](std::uint32_t v) { return std::vector<std::pair<std::size_t, long long>>{{v, 1000}}; };
    long long added = 0;
    std::vector<std::uint32_t> touched;
    REQUIRE(volmap::cone_region(mesh, 0, chords, limits, &added, &touched));
    CHECK(mesh.check_invariants(true).ok);
    CHECK(mesh_test::oriented_boundary(mesh) == boundary);
    std::sort(touched.begin(), touched.end());
    return Patch{std::size_t(std::unique(touched.begin(), touched.end()) - touched.begin()), mesh.num_tets()};
  };
  const Patch wide = cone_from_vertex_0(volmap::ConeRegionLimits{});
  CHECK(wide.vertices == box.num_vertices());
  CHECK(wide.tets == 192);
  const Patch small = cone_from_vertex_0(volmap::ConeRegionLimits{400, 24});
  MESSAGE("box: one region takes " << small.vertices << " of 98 vertices with the limits 400 tets / 24 stars");
  CHECK(small.vertices < box.num_vertices());
}

TEST_CASE("B0: a fixed inverted tet under a dent — one 2-3 flip towards the free vertex across it, then a certified map") {
  // Source: a tetrahedron (p0,p1,p2,p3) coned from its interior point e, and the tet (p0,p1,p2,d) on
  // its face p0p1p2, d below. Target: d lifted above that face (a dent), the rest as in the source.
  // (p0,p1,p2,d) is then fixed and inverted. No chord edge blocks, and its interior face p0p1p2 has
  // the free e across, but that face's image lies below the dent, outside the target solid: it
  // blocks (boundary_image_solid.hpp). The flip of p0p1p2 leaves the cone from e over the six faces
  // of ∂M, which maps validly with e in the dented polyhedron's kernel (near p3).
  volmap::TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, 1, 0.3, 0.3, -0.5, 0.325, 0.325, 0.25};
  const std::uint32_t e = 5, d = 4;
  const std::vector<std::array<std::uint32_t, 4>> tets = {{e, 0, 1, 3}, {e, 1, 2, 3}, {e, 2, 0, 3}, {e, 0, 1, 2}, {d, 0, 1, 2}};
  for (auto t : tets) {
    if (volmap::orient3d(&m.xyz[3 * t[0]], &m.xyz[3 * t[1]], &m.xyz[3 * t[2]], &m.xyz[3 * t[3]]) < 0) std::swap(t[0], t[1]);
    m.tets.insert(m.tets.end(), t.begin(), t.end());
  }
  std::vector<double> target = m.xyz;
  target[3 * d + 2] = 0.2;  // d -> (0.3, 0.3, 0.2), above p0p1p2
  const auto map = map_test::boundary_map_of({1, 1, 1, 1, 1, 0}, target);
  volmap::MapState state(m, map);
  const auto report = volmap::analyze_feasibility(state);
  REQUIRE(report.fixed_nonpositive_tets.size() == 1);
  CHECK(report.blocking_chord_edges.empty());
  REQUIRE(report.blocking_chord_faces.size() == 1);
  CHECK(report.blocking_chord_faces[0] == std::array<std::uint32_t, 3>{0, 1, 2});
  CHECK(report.boundary_volume_sign > 0);

  const auto boundary = mesh_test::oriented_boundary(state.source);
  const auto b0 = volmap::remove_blocking_chords(state, report);
  CHECK(b0.faces_flipped == 1);
  CHECK(b0.vertices_added == 0);
  CHECK(b0.tets_after == 6);
  CHECK(state.source.check_invariants(true).ok);
  CHECK(mesh_test::oriented_boundary(state.source) == boundary);
  CHECK(volmap::analyze_feasibility(state).fixed_nonpositive_tets.empty());

  const auto r = volmap::compute_volume_map(m, map);
  CHECK(r.certified);
  CHECK(r.source.num_tets() == 6);
  CHECK(volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0);
}
