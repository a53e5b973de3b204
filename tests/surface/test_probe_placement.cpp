// Node probe placements (domain.hpp with_rotated_probes, with_pulled_probes) and the surface map's
// search over them (surface_map.hpp steps 6 and 7): the 24 rotations are distinct proper rotations
// of the probes, a pull moves each probe towards the box centre by its fraction, and a coarse mesh
// whose unrotated map needs many splits gets the map of the search recomputed here one placement
// at a time, which passes the exact check.
#include <doctest/doctest.h>
#include <volmap/io/io.hpp>
#include <volmap/surface/domain.hpp>
#include <volmap/surface/surface_map.hpp>
#include <volmap/surface/surface_map_check.hpp>

#include "test_support.hpp"

#include <algorithm>
#include <set>
#include <string>
#include <vector>

using namespace volmap;

// det[p1 − p0, p2 − p0, p3 − p0] of four nodes' probes in the unit box.
static double probe_volume(const Domain& d, int n0, int n1, int n2, int n3) {
  const Point3 m{0, 0, 0}, M{1, 1, 1};
  const Point3 p0 = d.probe(n0, m, M), p1 = d.probe(n1, m, M), p2 = d.probe(n2, m, M), p3 = d.probe(n3, m, M);
  double a[3], b[3], c[3];
  for (int k = 0; k < 3; ++k) a[k] = p1[k] - p0[k], b[k] = p2[k] - p0[k], c[k] = p3[k] - p0[k];
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

TEST_CASE("the 24 probe rotations are distinct, proper and keep the probes in the box") {
  for (const char* name : {"cube", "tet", "pyr", "octa", "star"}) {
    CAPTURE(name);
    const Domain d = builtin_domain(name);
    // Four probed nodes spanning a volume.
    int quad[4] = {-1, -1, -1, -1};
    const Point3 m{0, 0, 0}, M{1, 1, 1};
    const int n = int(d.num_nodes());
    for (int a = 0; a < n && quad[0] < 0; ++a)
      for (int b = a + 1; b < n && quad[0] < 0; ++b)
        for (int c = b + 1; c < n && quad[0] < 0; ++c)
          for (int e = c + 1; e < n && quad[0] < 0; ++e)
            if (d.has_probe(a) && d.has_probe(b) && d.has_probe(c) && d.has_probe(e) && probe_volume(d, a, b, c, e) != 0)
              quad[0] = a, quad[1] = b, quad[2] = c, quad[3] = e;
    REQUIRE(quad[0] >= 0);
    const double volume = probe_volume(d, quad[0], quad[1], quad[2], quad[3]);
    std::set<std::vector<double>> placements;
    for (int r = 0; r < kNumProbeRotations; ++r) {
      CAPTURE(r);
      const Domain rd = with_rotated_probes(d, r);
      // A rotation keeps volumes, sign included (a reflection would mirror the node arrangement).
      CHECK(probe_volume(rd, quad[0], quad[1], quad[2], quad[3]) == doctest::Approx(volume));
      std::vector<double> all;
      for (std::size_t n = 0; n < d.num_nodes(); ++n) {
        CHECK(rd.has_probe(int(n)) == d.has_probe(int(n)));
        if (!d.has_probe(int(n))) continue;
        const Point3 p = rd.probe(int(n), m, M);
        for (int k = 0; k < 3; ++k) {
          CHECK(p[k] >= -1e-12);
          CHECK(p[k] <= 1 + 1e-12);
          all.push_back(p[k]);
        }
      }
      if (r == 0)
        for (std::size_t n = 0; n < d.num_nodes(); ++n)
          if (d.has_probe(int(n))) CHECK(rd.probe(int(n), m, M) == d.probe(int(n), m, M));
      placements.insert(all);
      CHECK(rd.targets == d.targets);
    }
    // The tet's and pyramid's probes have symmetries of their own; the cube's, octahedron's and
    // star's corner and face probes give 24 different placements.
    if (std::string(name) == "cube" || std::string(name) == "octa" || std::string(name) == "star")
      CHECK(placements.size() == std::size_t(kNumProbeRotations));
  }
  CHECK_THROWS(with_rotated_probes(builtin_domain("cube"), kNumProbeRotations));
}

TEST_CASE("pulled probes lie on the segment from the box centre to the original probe, at the pull's fraction") {
  const Point3 m{-2, 1, 10}, M{6, 3, 11};  // not a unit box: the pull is per axis of the bounding box
  const Point3 centre{2, 2, 10.5};
  for (const char* name : {"cube", "tet", "pyr", "octa", "star"}) {
    CAPTURE(name);
    const Domain d = builtin_domain(name);
    for (double pull : {1.0, 0.75, 0.5, 0.25}) {
      CAPTURE(pull);
      const Domain pd = with_pulled_probes(d, pull);
      CHECK(pd.targets == d.targets);
      for (std::size_t n = 0; n < d.num_nodes(); ++n) {
        REQUIRE(pd.has_probe(int(n)) == d.has_probe(int(n)));
        if (!d.has_probe(int(n))) continue;
        const Point3 p = d.probe(int(n), m, M), q = pd.probe(int(n), m, M);
        for (int k = 0; k < 3; ++k) CHECK(q[k] == doctest::Approx(centre[k] + pull * (p[k] - centre[k])));
      }
      // Pulls and rotations compose: a pulled placement turned keeps its distance to the centre.
      const Domain turned = with_rotated_probes(pd, 7);
      for (std::size_t n = 0; n < d.num_nodes(); ++n) {
        if (!d.has_probe(int(n))) continue;
        const Point3 a = pd.probe(int(n), {0, 0, 0}, {1, 1, 1}), b = turned.probe(int(n), {0, 0, 0}, {1, 1, 1});
        double ra = 0, rb = 0;
        for (int k = 0; k < 3; ++k) ra += (a[k] - 0.5) * (a[k] - 0.5), rb += (b[k] - 0.5) * (b[k] - 0.5);
        CHECK(rb == doctest::Approx(ra));
      }
    }
  }
  CHECK_THROWS(with_pulled_probes(builtin_domain("cube"), 0.0));
  CHECK_THROWS(with_pulled_probes(builtin_domain("cube"), 1.5));
}

TEST_CASE("a coarse octopus onto the star and the octahedron: the search over rotated, then pulled placements") {
  VOLMAP_REQUIRE_DATA(path, "tetmeshes/libigl_tutorial/octopus-low.mesh");
  TetMeshData mesh = read_tet_mesh(path.string());
  // libigl's tutorial meshes are wound the other way: flip them into VOLMAP's convention.
  const auto input_signs = orient3d_tets(mesh.xyz.data(), mesh.num_vertices(), mesh.tets.data(), mesh.num_tets(), nullptr);
  if (input_signs.negative == mesh.num_tets())
    for (std::size_t t = 0; t < mesh.num_tets(); ++t) std::swap(mesh.tets[4 * t], mesh.tets[4 * t + 1]);
  const double small = 1.01 * double(mesh.num_tets());  // a map adding at most 1 % ends a search
  for (const char* name : {"star", "octa"}) {
    CAPTURE(name);
    const Domain d = builtin_domain(name);
    SurfaceMapOptions single;
    single.search_placements = false;
    auto tets_at = [&](const Domain& placed) -> std::size_t {
      try {
        return map_surface_to_domain(mesh, placed, single).mesh.num_tets();
      } catch (const Error&) {
        return 0;  // no map at this placement
      }
    };
    // The search recomputed one placement at a time (surface_map.hpp steps 6 and 7).
    const std::size_t unrotated = tets_at(d);
    REQUIRE(unrotated > small);
    std::size_t rotated = unrotated;
    for (int r = 1; r < kNumProbeRotations; ++r)
      if (const std::size_t t = tets_at(with_rotated_probes(d, r)); t > 0 && t < rotated) rotated = t;
    REQUIRE(double(rotated) > small);  // on this mesh the pulls run
    std::size_t fewest = rotated;
    for (double pull : kProbePulls)
      for (int r = 0; r < kNumProbeRotations && double(fewest) > small; ++r)
        if (const std::size_t t = tets_at(with_rotated_probes(with_pulled_probes(d, pull), r)); t > 0 && t < fewest) fewest = t;
    const SurfaceMapResult best = map_surface_to_domain(mesh, d);
    CHECK(best.mesh.num_tets() == fewest);
    CHECK(rotated < unrotated);  // on this mesh both searches pay
    CHECK(fewest < rotated);
    CHECK(best.attempt.find("probes pulled") != std::string::npos);
    CHECK(check_surface_map(best.mesh, best.map, &d).ok);
    const auto signs = orient3d_tets(best.mesh.xyz.data(), best.mesh.num_vertices(), best.mesh.tets.data(),
                                     best.mesh.num_tets(), nullptr);
    CHECK(signs.positive == best.mesh.num_tets());
    MESSAGE(std::string(name) << ": " << mesh.num_tets() << " input tets; " << unrotated << " unrotated, " << rotated
                              << " rotated, " << fewest << " pulled");
  }
}
