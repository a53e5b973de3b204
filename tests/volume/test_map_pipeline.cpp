// volmap-map stages on small cases: feasibility (all-boundary tets, chords), B0 chord splitting
// (children exactly positive, ids kept), the full pipeline on synthetic and real small maps (TLC
// cube, Floater–Pham-Trong 7-vertex Tutte counterexample), TLC, and the no-false-success property
// of the tool (a fixed inverted all-boundary tet with refinement disabled must give exit 1).
#include <doctest/doctest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/volume/chord_split.hpp>
#include <volmap/volume/feasibility.hpp>
#include <volmap/volume/ffm.hpp>
#include <volmap/io/io.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/tlc.hpp>
#include <volmap/volume/tutte3d.hpp>
#include <volmap/volume/volume_map.hpp>

#include "map_test_meshes.hpp"
#include "test_support.hpp"

#include <cstdlib>
#include <sys/wait.h>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

namespace {

std::filesystem::path temp_dir(const std::string& name) { return volmap_test::scratch_dir("map_" + name); }

}  // namespace

TEST_CASE("feasibility: Kuhn cube has one chord edge (the diagonal) and six chord faces, none blocking") {
  auto m = map_test::kuhn_grid(1);
  std::vector<std::uint8_t> bnd(8, 1);
  auto r = volmap::analyze_feasibility(m, bnd, m.xyz);
  CHECK(r.chord_edges.size() == 1);
  CHECK(r.chord_edges[0] == std::array<std::uint32_t, 2>{0, 7});
  CHECK(r.chord_faces.size() == 6);
  CHECK(r.blocking_chord_edges.empty());
  CHECK(r.blocking_chord_faces.empty());
  CHECK(r.all_boundary_tets == 6);
  CHECK(r.fixed_nonpositive_tets.empty());
  CHECK(!r.infeasible_at_fixed_connectivity());
  // Flatten the far corner (1,1,1) onto the plane z = 1 through (0,0,1)...: the diagonal's image
  // now lies in the top facet plane -> blocking chord edge, and tets become fixed non-positive.
  auto t = m.xyz;
  t[3 * 7 + 2] = 0.0;  // (1,1,1) -> (1,1,0): in the bottom facet plane with vertex 0 = (0,0,0)
  auto r2 = volmap::analyze_feasibility(m, bnd, t);
  CHECK(r2.blocking_chord_edges.size() == 1);
  CHECK(!r2.fixed_nonpositive_tets.empty());
  CHECK(r2.infeasible_at_fixed_connectivity());
}

TEST_CASE("feasibility: the exact sign of the volume enclosed by the boundary image") {
  const int n = 3;
  const auto m = map_test::kuhn_grid(n);
  const auto bnd = map_test::grid_boundary_flags(n);
  // Identity: the unit cube, positive.
  CHECK(volmap::analyze_feasibility(m, bnd, m.xyz).boundary_volume_sign == 1);
  // Mirrored (x -> 1 - x): the same cube enclosed with reversed orientation; impossible at any refinement.
  auto mirrored = m.xyz;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) mirrored[3 * v] = 1.0 - mirrored[3 * v];
  const auto r = volmap::analyze_feasibility(m, bnd, mirrored);
  CHECK(r.boundary_volume_sign == -1);
  CHECK(r.infeasible_with_any_refinement());
  CHECK(r.infeasible_at_fixed_connectivity());
  // Collapsed onto the plane z = 0.3 far from the origin (shifted by 1e8, where the double sum of
  // the triple products is pure rounding noise): exactly zero volume, decided by the rational sum.
  auto flat = m.xyz;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    flat[3 * v] += 1e8;
    flat[3 * v + 1] -= 1e8;
    flat[3 * v + 2] = 0.3;
  }
  CHECK(volmap::analyze_feasibility(m, bnd, flat).boundary_volume_sign == 0);
  // The unit cube shifted as far: still positive (the filter may not decide, the exact sum does).
  auto far = m.xyz;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    far[3 * v] += 1e8;
    far[3 * v + 1] -= 1e8;
    far[3 * v + 2] += 3e7;
  }
  CHECK(volmap::analyze_feasibility(m, bnd, far).boundary_volume_sign == 1);
}

TEST_CASE("B0: splitting the chord diagonal keeps ids, appends one interior vertex, children exactly positive") {
  auto m = map_test::kuhn_grid(1);
  std::vector<std::uint8_t> bnd(8, 1);
  const auto before = m;
  auto r = volmap::split_chords(m, bnd, {{{0, 7}}}, {});
  CHECK(r.edges_split == 1);
  CHECK(r.vertices_added == 1);
  CHECK(m.num_vertices() == 9);
  CHECK(m.num_tets() == 12);
  CHECK(bnd.size() == 9);
  CHECK(bnd[8] == 0);
  for (std::size_t i = 0; i < 24; ++i) CHECK(m.xyz[i] == before.xyz[i]);
  CHECK(m.xyz[24] == 0.5);
  CHECK(volmap::count_nonpositive(m.xyz, m.tets) == 0);
  // Volume is preserved (children tile the parents).
  auto vol = [](const volmap::TetMeshData& mm) {
    double s = 0;
    for (std::size_t t = 0; t < mm.num_tets(); ++t) {
      const double* p[4];
      for (int i = 0; i < 4; ++i) p[i] = &mm.xyz[3 * mm.tets[4 * t + i]];
      double e[3][3];
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) e[k][i] = p[k + 1][i] - p[0][i];
      s += -(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
             e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6;
    }
    return s;
  };
  CHECK(vol(m) == doctest::Approx(1.0));
  // The chord faces all contained the diagonal: none is left.
  auto f = volmap::analyze_feasibility(m, bnd, m.xyz);
  CHECK(f.chord_edges.empty());
  CHECK(f.chord_faces.empty());
}

TEST_CASE("B0: edge splits of sliver tets: every child exactly positive, or refused and unchanged") {
  // One tet, its fourth vertex a rounding step off the plane of the other three, at random
  // orientations: the children of an edge split have volumes of the order of the rounding of the
  // split point. Each split must give exactly positive children or be refused with the mesh as it
  // was (the fixture below is one that is refused).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::size_t split = 0, refused = 0;
  for (int trial = 0; trial < 400; ++trial) {
    volmap::TetMeshData m;
    double a[3], b[3], c[3];
    for (int i = 0; i < 3; ++i) a[i] = u(rng), b[i] = u(rng), c[i] = u(rng);
    const double s = u(rng), t = u(rng);
    double d[3];
    for (int i = 0; i < 3; ++i) d[i] = a[i] + s * (b[i] - a[i]) + t * (c[i] - a[i]);
    m.xyz = std::vector<double>{a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], d[0], d[1], d[2]};
    m.tets = std::vector<std::uint32_t>{0, 1, 2, 3};
    const int sign = volmap::orient3d(&m.xyz[0], &m.xyz[3], &m.xyz[6], &m.xyz[9]);
    if (sign == 0) continue;
    if (sign < 0) std::swap(m.tets[0], m.tets[1]);
    const auto before = m;
    std::vector<std::uint8_t> locked(4, 1);
    volmap::ChordSplitResult r;
    REQUIRE_NOTHROW(r = volmap::split_chords(m, locked, {{{m.tets[0], m.tets[1]}}}, {}));
    if (r.edges_split == 1) {
      ++split;
      CHECK(m.num_tets() == 2);
      CHECK(volmap::count_nonpositive(m.xyz, m.tets) == 0);
    } else {
      ++refused;
      CHECK(r.splits_refused == 1);
      CHECK(m.xyz == before.xyz);
      CHECK(m.tets == before.tets);
    }
  }
  CHECK(split > 0);
  MESSAGE("sliver edge splits: " << split << " split, " << refused << " refused");
}

TEST_CASE("B0: a chord face with no verified split point is left as it was, without an exception") {
  // Two tets of TetGen's remesh of the coarse limbs shape (pq3.0Y) around face (0, 1, 2), as B0 met
  // them: the face's vertices are collinear to 1e-17 of its edges (area 6e-20, edges 2e-3), so every
  // barycentric split point leaves a child non-positive in doubles. The split used to throw, which
  // ended the whole mapping run; now it is refused (counted) and the later stages go on.
  volmap::TetMeshData m;
  m.xyz = std::vector<double>{-0x1.ffbf7d84561a8p+1, 0x1.be7c674da4487p-5, -0x1.4066ed165dcb3p-1,
           -0x1.ff7d2c7297e4ep+1, 0x1.c512d1f1d7fdcp-5, -0x1.41ce118c0caeap-1,
           -0x1.ff5c03e9b8ca1p+1, 0x1.c85e0743f1d86p-5, -0x1.4281a3c6e4206p-1,
           -0x1.00eb57ab74bd4p+2, 0x1.cb68ae19458e6p-5, -0x1.4e7514cf1c2fap-1,
           -0x1.00bef7ebca22ap+2, -0x1.cbafe313f738cp-7, -0x1.343da6e9580b2p-1};
  m.tets = std::vector<std::uint32_t>{0, 3, 2, 1, 1, 2, 0, 4};
  REQUIRE(volmap::count_nonpositive(m.xyz, m.tets) == 0);
  const auto before = m;
  std::vector<std::uint8_t> locked(5, 1);
  volmap::ChordSplitResult r;
  REQUIRE_NOTHROW(r = volmap::split_chords(m, locked, {}, {{{0, 1, 2}}}));
  CHECK(r.faces_split == 0);
  CHECK(r.splits_refused == 1);
  CHECK(m.xyz == before.xyz);
  CHECK(m.tets == before.tets);
}

TEST_CASE("B0: face split 1->3 turns each of the two tets into three exactly positive children") {
  auto m = map_test::kuhn_grid(1);
  std::vector<std::uint8_t> bnd(8, 1);
  auto f = volmap::analyze_feasibility(m, bnd, m.xyz);
  REQUIRE(!f.chord_faces.empty());
  auto r = volmap::split_chords(m, bnd, {}, {f.chord_faces[0]});
  CHECK(r.faces_split == 1);
  CHECK(m.num_tets() == 6 + 4);
  CHECK(volmap::count_nonpositive(m.xyz, m.tets) == 0);
}

TEST_CASE("pipeline: scrambled grid interior, affine boundary -> certified, boundary bit-exact") {
  auto m = map_test::kuhn_grid(4);
  auto bnd = map_test::grid_boundary_flags(4);
  std::vector<double> target(m.xyz.size());
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    target[3 * v] = 3 * m.xyz[3 * v] + m.xyz[3 * v + 2];
    target[3 * v + 1] = m.xyz[3 * v + 1];
    target[3 * v + 2] = 0.5 * m.xyz[3 * v + 2];
  }
  const auto map = map_test::boundary_map_of(bnd, target);
  for (auto method : {volmap::MapMethod::Ffm, volmap::MapMethod::Tlc}) {
    volmap::VolumeMapOptions opt;
    opt.method = method;
    auto r = volmap::compute_volume_map(m, map, opt);
    CHECK(r.certified);
    CHECK(volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0);
    for (std::size_t k = 0; k < map.size(); ++k)
      for (int i = 0; i < 3; ++i) CHECK(r.target_xyz[3 * map.vids[k] + i] == map.xyz[3 * k + i]);
  }
}

TEST_CASE("TLC untangles scrambled interior vertices (exact stop)") {
  auto m = map_test::kuhn_grid(4);
  auto bnd = map_test::grid_boundary_flags(4);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  auto target = m.xyz;
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (!bnd[v])
      for (int i = 0; i < 3; ++i) target[3 * v + i] += u(rng);
  REQUIRE(volmap::count_nonpositive(target, m.tets) > 0);
  auto r = volmap::tlc_untangle(m.xyz, m.tets, bnd, target);
  CHECK(r.certified);
  CHECK(volmap::count_nonpositive(target, m.tets) == 0);
}

TEST_CASE("TLC: the in-order evaluation (one thread) and the parallel one give the same bits") {
  // One thread scatters each tet's gradient into its vertices in tet order; several threads
  // gather per vertex in the same order. Same sums, same order: the runs must agree exactly.
  auto m = map_test::kuhn_grid(5);
  auto bnd = map_test::grid_boundary_flags(5);
  const auto scrambled = map_test::scrambled_target(m, bnd, 11, 0.5);
  REQUIRE(volmap::count_nonpositive(scrambled, m.tets) > 0);
  volmap::TlcOptions o;
  o.max_evaluations = 40;  // stop mid-way: the trajectories, not only the end, must agree
  auto one = scrambled, many = scrambled;
  volmap::TlcResult r1, r2;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    r1 = volmap::tlc_untangle(m.xyz, m.tets, bnd, one, o);
  }
  tbb::task_arena(2).execute([&] { r2 = volmap::tlc_untangle(m.xyz, m.tets, bnd, many, o); });
  CHECK(r1.evaluations == r2.evaluations);
  CHECK(r1.nonpositive == r2.nonpositive);
  CHECK(one == many);
  CHECK(one != scrambled);
}

TEST_CASE("TLC finish callback: called at new lows within finish_max_bad; a true ends TLC with its map") {
  auto m = map_test::kuhn_grid(4);
  auto bnd = map_test::grid_boundary_flags(4);
  const auto scrambled = map_test::scrambled_target(m, bnd, 3, 0.6);
  const std::size_t start_bad = volmap::count_nonpositive(scrambled, m.tets);
  REQUIRE(start_bad > 4);
  SUBCASE("refusing finish: called only with strictly fewer non-positive tets each time, TLC unaffected") {
    std::vector<std::size_t> seen;
    volmap::TlcOptions o;
    o.finish_max_bad = start_bad;
    o.finish = [&](std::vector<double>& x) {
      seen.push_back(volmap::count_nonpositive(x, m.tets));
      x.assign(x.size(), 0.0);  // a refusing finish may scribble on its copy: TLC must not see it
      return false;
    };
    auto with = scrambled, without = scrambled;
    const auto r = volmap::tlc_untangle(m.xyz, m.tets, bnd, with, o);
    volmap::tlc_untangle(m.xyz, m.tets, bnd, without);
    CHECK(!r.finished);
    CHECK(with == without);
    REQUIRE(!seen.empty());
    for (std::size_t k = 1; k < seen.size(); ++k) CHECK(seen[k] < seen[k - 1]);
  }
  SUBCASE("accepting finish: TLC returns the finish's map at the first call") {
    int calls = 0;
    volmap::TlcOptions o;
    o.finish_max_bad = start_bad;
    o.finish = [&](std::vector<double>& x) {
      ++calls;
      x = m.xyz;  // the identity map of the grid: positive
      return true;
    };
    auto target = scrambled;
    const auto r = volmap::tlc_untangle(m.xyz, m.tets, bnd, target, o);
    CHECK(calls == 1);
    CHECK(r.finished);
    CHECK(r.certified);
    CHECK(target == m.xyz);
  }
}

TEST_CASE("Floater–Pham-Trong 7-vertex Tutte counterexample: Tutte inverts, the mapper certifies") {
  VOLMAP_REQUIRE_DATA(obj, "maps/galaxymaps/example_object.vtk");
  VOLMAP_REQUIRE_DATA(par, "maps/galaxymaps/example_parameter.vtk");
  const auto src = volmap::read_vtk(obj.string());
  const auto img = volmap::read_vtk(par.string());
  REQUIRE(src.num_vertices() == 7);
  REQUIRE(src.num_tets() == 10);
  std::vector<std::uint8_t> bnd(7, 0);
  for (auto v : volmap::boundary_vertex_ids(src)) bnd[v] = 1;
  auto tutte = img.xyz;
  volmap::solve_uniform_laplacian(bnd.size(), volmap::unique_tet_edges(src), bnd, tutte);
  CHECK(volmap::count_nonpositive(tutte, src.tets) > 0);  // the counterexample: uniform Tutte folds
  const auto map = map_test::boundary_map_of(bnd, img.xyz);
  volmap::VolumeMapOptions opt;
  opt.allow_refinement = false;
  auto r = volmap::compute_volume_map(src, map, opt);
  CHECK(r.certified);
  CHECK(r.source.num_tets() == 10);
}

TEST_CASE("fixed connectivity, few bad tets left: rounds of small-lift TLC and local FFM instead of global FFM") {
  // GalaxyMaps' rocker arm from its own initial map (8,682 tets): at fixed connectivity the
  // untangling phase leaves 2 non-positive tets and no local certificate. Global FFM restarts from
  // ε = 1 and was undone in every one of 290 calls on G1 and the wide sets (docs/mapping.md §10);
  // with few tets left the local rounds run instead, and the global stages only on request.
  VOLMAP_REQUIRE_DATA(obj, "maps/galaxymaps/cub_rockerarm291_object.vtk");
  VOLMAP_REQUIRE_DATA(par, "maps/galaxymaps/cub_rockerarm291_parameter.vtk");
  const auto src = volmap::read_vtk(obj.string());
  const auto img = volmap::read_vtk(par.string());
  std::vector<std::uint8_t> bnd(src.num_vertices(), 0);
  for (auto v : volmap::boundary_vertex_ids(src)) bnd[v] = 1;
  const auto map = map_test::boundary_map_of(bnd, img.xyz);
  auto stages_named = [](const volmap::VolumeMapResult& r, const std::string& name) {
    return std::count_if(r.stages.begin(), r.stages.end(), [&](const volmap::VolumeMapStage& s) { return s.name == name; });
  };
  for (const std::size_t local_rounds_max_bad : {std::size_t(200), std::size_t(0)}) {
    volmap::VolumeMapOptions opt;
    opt.allow_refinement = false;
    opt.max_threads = 1;
    opt.time_limit_seconds = 5;
    opt.quality_pass = false;
    opt.initial_xyz = img.xyz;
    opt.local_rounds_max_bad = local_rounds_max_bad;
    const auto r = volmap::compute_volume_map(src, map, opt);
    INFO("local_rounds_max_bad " << local_rounds_max_bad << ": certified " << r.certified << ", " << r.nonpositive << " left");
    CHECK(r.certified == (volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0));  // never a false success
    CHECK(r.infeasibility.empty());
    // The untangling phase ends with its local FFM stage; what follows is the phase under test.
    const auto first_local = std::find_if(r.stages.begin(), r.stages.end(), [](const auto& s) { return s.name == "ffm-local"; });
    REQUIRE(first_local != r.stages.end());
    REQUIRE(first_local->nonpositive_after > 0);
    REQUIRE(first_local->nonpositive_after <= 200);
    if (local_rounds_max_bad > 0) {
      CHECK(stages_named(r, "ffm-regular") == 0);
      CHECK(stages_named(r, "ffm-rest") == 0);
      CHECK(stages_named(r, "tlc-small-alpha") >= 2);  // the untangling phase's and at least one round's
      CHECK(stages_named(r, "ffm-local") >= 2);
    } else {
      CHECK(stages_named(r, "ffm-regular") == 1);
    }
  }
}

TEST_CASE("TLC example cube (custom text format): B0 + untangling certifies the refined pair") {
  VOLMAP_REQUIRE_DATA(p, "maps/tlc/input");
  std::ifstream in(p);
  std::size_t nv, d;
  in >> nv >> d;
  volmap::TetMeshData m;
  m.xyz.resize(3 * nv);
  for (auto& x : m.xyz) in >> x;
  std::vector<double> init(3 * nv);
  in >> nv >> d;
  for (auto& x : init) in >> x;
  std::size_t nt, k;
  in >> nt >> k;
  m.tets.resize(4 * nt);
  for (auto& t : m.tets) in >> t;
  std::size_t nh;
  in >> nh;
  std::vector<std::uint8_t> bnd(nv, 0);
  for (std::size_t i = 0; i < nh; ++i) {
    std::uint32_t h;
    in >> h;
    bnd[h] = 1;
  }
  REQUIRE(m.num_tets() == 162);
  CHECK(volmap::count_nonpositive(init, m.tets) == 36);
  auto f = volmap::analyze_feasibility(m, bnd, init);
  CHECK(f.chord_edges.size() == 24);
  CHECK(f.chord_faces.size() == 66);
  const auto map = map_test::boundary_map_of(bnd, init);
  // Fixed connectivity: must never claim success unless the exact check passes.
  volmap::VolumeMapOptions fixed;
  fixed.allow_refinement = false;
  auto r0 = volmap::compute_volume_map(m, map, fixed);
  CHECK(r0.certified == (volmap::count_nonpositive(r0.target_xyz, r0.source.tets) == 0));
  MESSAGE("TLC cube, fixed connectivity: certified " << r0.certified << ", non-positive " << r0.nonpositive
          << "; blocking chord edges " << f.blocking_chord_edges.size() << " faces " << f.blocking_chord_faces.size()
          << " fixed non-positive tets " << f.fixed_nonpositive_tets.size());
  if (f.infeasible_at_fixed_connectivity()) CHECK(!r0.certified);
  volmap::VolumeMapOptions refine;
  auto r1 = volmap::compute_volume_map(m, map, refine);
  MESSAGE("TLC cube, with refinement: certified " << r1.certified << ", tets " << r1.source.num_tets() << ", by " << r1.certified_by);
  CHECK(volmap::count_nonpositive(r1.source.xyz, r1.source.tets) == 0);  // the refined source stays valid
  CHECK(r1.certified == (volmap::count_nonpositive(r1.target_xyz, r1.source.tets) == 0));
}

TEST_CASE("volmap-map: no false success when a fixed all-boundary tet is inverted (exit 1), bad input exit 2") {
  const auto tool = volmap_test::tool("volmap-map");
  if (!std::filesystem::exists(tool)) {
    MESSAGE("skipped: volmap-map not built");
    return;
  }
  auto m = map_test::kuhn_grid(1);
  std::vector<std::uint8_t> bnd(8, 1);
  auto t = m.xyz;
  t[3 * 7 + 2] = 0.0;  // flatten: some all-boundary tets become degenerate/inverted, nothing can move
  const auto dir = temp_dir("nfs");
  volmap::write_medit((dir / "in.mesh").string(), m);
  volmap::write_boundary_map((dir / "map.txt").string(), map_test::boundary_map_of(bnd, t));
  const std::string base = tool.string() + " " + (dir / "in.mesh").string() + " " + (dir / "map.txt").string() + " " +
                           (dir / "out.mesh").string();
  int rc = std::system((base + " --no-refine > /dev/null 2>&1").c_str());
  CHECK(WEXITSTATUS(rc) == 1);
  rc = std::system((base + " --refined-input " + (dir / "ref.mesh").string() + " > /dev/null 2>&1").c_str());
  CHECK(WEXITSTATUS(rc) == 1);  // B1 cannot help either: every vertex is on the boundary
  rc = std::system((tool.string() + " " + (dir / "missing.mesh").string() + " x y > /dev/null 2>&1").c_str());
  CHECK(WEXITSTATUS(rc) == 2);
  // A feasible case certifies with exit 0 and bit-exact boundary in the written file.
  auto g = map_test::kuhn_grid(3);
  auto gb = map_test::grid_boundary_flags(3);
  volmap::write_medit((dir / "g.mesh").string(), g);
  volmap::write_boundary_map((dir / "gmap.txt").string(), map_test::boundary_map_of(gb, g.xyz));
  rc = std::system((tool.string() + " " + (dir / "g.mesh").string() + " " + (dir / "gmap.txt").string() + " " +
                    (dir / "gout.mesh").string() + " > /dev/null 2>&1").c_str());
  CHECK(WEXITSTATUS(rc) == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("G1 bone and duck onto the five domains" * doctest::test_suite("long")) {
  int certified = 0, pairs = 0;
  for (std::string name : {"bone", "duck"})
    for (std::string dom : {"cube", "tet", "pyr", "octa", "star"}) {
      VOLMAP_REQUIRE_DATA(mesh, "volmap/G1/" + name + ".mesh");
      VOLMAP_REQUIRE_DATA(mp, "volmap/G1_" + dom + "/" + name + "_" + dom + ".txt");
      const auto src = volmap::read_medit(mesh.string());
      const auto map = volmap::read_boundary_map(mp.string());
      volmap::VolumeMapOptions opt;
      opt.time_limit_seconds = 60;
      opt.allow_refinement = false;
      auto r = volmap::compute_volume_map(src, map, opt);
      MESSAGE(name << " " << dom << ": certified " << r.certified << " non-positive " << r.nonpositive << " by "
              << r.certified_by << " in " << r.seconds << " s");
      CHECK(r.certified == (volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0));  // never a false success
      ++pairs;
      certified += r.certified;
    }
  // Measured 2026-11-23 (loaded 2-core machine): 7 of 10 certified (bone cube/octa/star keep 2-4
  // tets that need B1 refinement, not implemented yet). Guard against regressions below that.
  if (pairs == 10) CHECK(certified >= 7);
}
