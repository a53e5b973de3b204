// The interior-remesh last resort of the mapper (volume_map.hpp, interior_remesh.hpp): the exact
// contract check refuses every broken remesh, the remesher is asked only when the runs from the
// input end uncertified with refinement allowed, a refused or failing remesh is a failed stage after
// which the time left continues the first result (never an exception, never the user's bad input),
// and a remeshed result reports growth against the input. The remeshers here are plain functions,
// so no mesher is needed.
#include <doctest/doctest.h>

#include <volmap/predicates.hpp>
#include <volmap/volume/interior_remesh.hpp>
#include <volmap/volume/volume_map.hpp>

#include "map_test_meshes.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <utility>

namespace {

// The Kuhn grid with an affine boundary image (convex: Tutte 3D maps it validly).
struct AffineCase {
  volmap::TetMeshData mesh;
  std::vector<std::uint8_t> boundary;
  volmap::BoundaryMap map;
  std::vector<double> scrambled;  // the target with the interior moved randomly (tangled)
};

AffineCase affine_case(int n) {
  AffineCase c;
  c.mesh = map_test::kuhn_grid(n);
  c.boundary = map_test::grid_boundary_flags(n);
  c.scrambled = map_test::scrambled_target(c.mesh, c.boundary, 7, 0.4);
  c.map = map_test::boundary_map_of(c.boundary, c.scrambled);
  return c;
}

const volmap::VolumeMapStage* find_stage(const volmap::VolumeMapResult& r, const std::string& name) {
  for (const auto& s : r.stages)
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace

TEST_CASE("interior remesh contract: the input itself passes, each broken remesh is named") {
  const auto c = affine_case(3);
  CHECK(volmap::interior_remesh_problem(c.mesh, c.mesh).empty());

  auto moved = c.mesh;
  moved.xyz[3 * 5 + 1] += 1e-12;  // one input vertex moved by a rounding step
  CHECK(volmap::interior_remesh_problem(c.mesh, moved).find("moved") != std::string::npos);

  auto flipped = c.mesh;
  std::swap(flipped.tets[0], flipped.tets[1]);  // one inverted tet
  CHECK(volmap::interior_remesh_problem(c.mesh, flipped).find("positive") != std::string::npos);

  auto fewer = c.mesh;
  fewer.xyz.resize(fewer.xyz.size() - 3);
  CHECK(!volmap::interior_remesh_problem(c.mesh, fewer).empty());

  // A split of one boundary face (1 -> 3 with a new vertex at its centroid) changes the boundary.
  auto split = c.mesh;
  const auto hf = [&] {
    for (std::size_t t = 0; t < split.num_tets(); ++t)
      for (int i = 0; i < 4; ++i) {
        int on_boundary = 0;
        for (int k = 0; k < 4; ++k)
          if (k != i) on_boundary += c.boundary[split.tets[4 * t + std::size_t(k)]];
        if (on_boundary == 3) return std::pair<std::size_t, int>(t, i);
      }
    return std::pair<std::size_t, int>(0, -1);
  }();
  REQUIRE(hf.second >= 0);
  const std::uint32_t* tv = &split.tets[4 * hf.first];
  std::array<std::uint32_t, 3> face{};
  for (int k = 0, j = 0; k < 4; ++k)
    if (k != hf.second) face[std::size_t(j++)] = tv[k];
  const std::uint32_t w = std::uint32_t(split.num_vertices());
  for (int d = 0; d < 3; ++d)
    split.xyz.push_back((split.xyz[3 * face[0] + d] + split.xyz[3 * face[1] + d] + split.xyz[3 * face[2] + d]) / 3.0);
  std::vector<std::uint32_t> old(tv, tv + 4);
  split.tets.erase(split.tets.begin() + long(4 * hf.first), split.tets.begin() + long(4 * hf.first + 4));
  for (int k = 0; k < 4; ++k) {
    if (k == hf.second) continue;
    std::vector<std::uint32_t> child = old;
    child[std::size_t(k)] = w;  // the face vertex k replaced by the centroid: same orientation
    split.tets.insert(split.tets.end(), child.begin(), child.end());
  }
  REQUIRE(volmap::count_nonpositive(split.xyz, split.tets) == 0);
  if (!split.tet_labels.empty()) {
    CHECK(volmap::interior_remesh_problem(c.mesh, split).find("labels") != std::string::npos);  // one label per tet
    split.tet_labels.assign(split.num_tets(), 0);
  }
  CHECK(volmap::interior_remesh_problem(c.mesh, split).find("boundary") != std::string::npos);
}

TEST_CASE("interior remesh: asked only when the runs from the input end uncertified, with refinement") {
  const auto c = affine_case(3);
  int calls = 0;
  volmap::VolumeMapOptions opt;
  opt.time_limit_seconds = 20;
  opt.remesh_interior = [&](const volmap::TetMeshData& m, double) {
    ++calls;
    return m;
  };
  auto certified = volmap::compute_volume_map(c.mesh, c.map, opt);  // Tutte 3D maps the convex image
  CHECK(certified.certified);
  CHECK(calls == 0);
  CHECK_FALSE(certified.remeshed);

  opt.allow_refinement = false;  // fixed connectivity never remeshes, even uncertified
  opt.initial_xyz = c.scrambled;
  opt.time_limit_seconds = 1e-4;
  opt.quality_pass = false;
  auto fixed = volmap::compute_volume_map(c.mesh, c.map, opt);
  CHECK(calls == 0);
  CHECK_FALSE(fixed.remeshed);
  CHECK(find_stage(fixed, "remesh") == nullptr);
}

TEST_CASE("interior remesh: an uncertified start hands the rest of the limit to the remeshed source") {
  const auto c = affine_case(6);
  int calls = 0;
  volmap::VolumeMapOptions opt;
  opt.time_limit_seconds = 30;
  opt.remesh_share = 1e-6;         // the runs from the input stop at once...
  opt.initial_xyz = c.scrambled;   // ... on a tangled start
  opt.whole_mesh_cone = false;     // no time held back for the last resort: the runs get the whole limit
  REQUIRE(volmap::count_nonpositive(c.scrambled, c.mesh.tets) > 50);
  double remesh_seconds = -1;
  opt.remesh_interior = [&](const volmap::TetMeshData& m, double seconds) {
    ++calls;
    remesh_seconds = seconds;
    return m;  // the identity keeps the contract; the remeshed run starts from Tutte 3D
  };
  const auto r = volmap::compute_volume_map(c.mesh, c.map, opt);
  CHECK(calls == 1);
  // The remesher may take four fifths of the time left (almost all 30 s here), the rest maps the
  // remeshed source.
  CHECK(remesh_seconds > 0.7 * opt.time_limit_seconds);
  CHECK(remesh_seconds <= 0.8 * opt.time_limit_seconds);
  CHECK(r.certified);
  CHECK(r.remeshed);
  CHECK(r.refined);
  CHECK(r.input_tets == c.mesh.num_tets());
  CHECK(r.growth() == doctest::Approx(double(r.source.num_tets()) / double(c.mesh.num_tets()) - 1.0));
  const auto* stage = find_stage(r, "remesh");
  REQUIRE(stage != nullptr);
  CHECK(stage->failure.empty());
  CHECK(stage->nonpositive_after > 0);  // what the runs from the input had left
  CHECK(volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0);
  for (std::size_t k = 0; k < c.map.size(); ++k)
    for (int i = 0; i < 3; ++i) CHECK(r.target_xyz[3 * c.map.vids[k] + std::size_t(i)] == c.map.xyz[3 * k + std::size_t(i)]);
}

TEST_CASE("interior remesh: a refused or throwing remesher is a failed stage; the time left continues the first run") {
  const auto c = affine_case(6);
  volmap::VolumeMapOptions opt;
  opt.time_limit_seconds = 5;
  opt.remesh_share = 1e-6;
  opt.initial_xyz = c.scrambled;
  opt.quality_pass = false;
  SUBCASE("a vertex moved") {
    opt.remesh_interior = [](const volmap::TetMeshData& m, double) {
      auto moved = m;
      moved.xyz[0] += 0.5;
      return moved;
    };
    const auto r = volmap::compute_volume_map(c.mesh, c.map, opt);
    CHECK_FALSE(r.remeshed);
    const auto* stage = find_stage(r, "remesh");
    REQUIRE(stage != nullptr);
    CHECK(stage->failure.find("remesh refused") != std::string::npos);
    CHECK(r.source.num_vertices() >= c.mesh.num_vertices());
    CHECK(r.source.xyz[0] == c.mesh.xyz[0]);
    // The runs from the input stopped at once on the tangled start; the continuation from their
    // map, with the rest of the 5 s, untangles it on the (unremeshed) source.
    CHECK(stage->nonpositive_after > 0);
    CHECK(r.certified);
    CHECK(volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0);
    CHECK(r.input_tets == c.mesh.num_tets());
    const auto after = std::find_if(r.stages.begin(), r.stages.end(), [](const auto& s) { return s.name == "remesh"; });
    CHECK(std::next(after) != r.stages.end());  // the continuation's stages follow the failed remesh
    CHECK(r.refined == (r.source.tets != c.mesh.tets || r.source.xyz != c.mesh.xyz));  // refined iff changed
  }
  SUBCASE("the mesher throws") {
    opt.remesh_interior = [](const volmap::TetMeshData&, double) -> volmap::TetMeshData { throw std::runtime_error("mesher down"); };
    const auto r = volmap::compute_volume_map(c.mesh, c.map, opt);
    CHECK_FALSE(r.remeshed);
    const auto* stage = find_stage(r, "remesh");
    REQUIRE(stage != nullptr);
    CHECK(stage->failure.find("mesher down") != std::string::npos);
    CHECK(r.certified);
  }
}
