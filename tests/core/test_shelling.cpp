// Shelling steps (shelling.hpp) against an independent oracle: a region of tets is a 3-ball when, as
// its own tet mesh, it is one face-connected piece whose boundary is one closed 2-manifold of genus 0
// (analyze_topology). Regions grow on Kuhn grids by random outside neighbours.
#include <doctest/doctest.h>

#include <volmap/core/shelling.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/core/topology.hpp>
#include <volmap/testing/generate.hpp>

#include <random>
#include <vector>

using namespace volmap;

namespace {

bool is_ball(const TetMesh& mesh, const std::vector<char>& in, TetId extra = TetId::kInvalid) {
  TetMeshData sub;
  sub.xyz = mesh.positions();
  for (std::size_t t = 0; t < in.size(); ++t)
    if (in[t] || TetId(std::uint32_t(t)) == extra)
      for (int i = 0; i < 4; ++i) sub.tets.push_back(mesh.tet_vertex(TetId(std::uint32_t(t)), i).idx());
  // Unused vertices are fine here: only the tets' topology matters.
  const TopologyReport r = analyze_topology(sub);
  return r.num_tet_components == 1 && r.boundary_genus_zero && r.single_boundary_component;
}

}  // namespace

TEST_CASE("attaches_along_disk: every step it accepts keeps a ball a ball (random ball growth on grids)") {
  // The region only takes steps that keep it a ball (oracle), so it stays a ball for long and wraps
  // around itself; every candidate step is judged by both the predicate and the oracle.
  std::mt19937 rng(5);
  std::size_t accepted = 0, broke[5] = {0, 0, 0, 0, 0};  // refused steps that broke the ball, by shared faces
  for (int round = 0; round < 30; ++round) {
    const TetMesh mesh(generate_kuhn_grid(4, 4, 3));
    const std::size_t nt = mesh.num_tets();
    std::vector<char> in(nt, 0);
    in[rng() % nt] = 1;
    std::vector<TetId> scratch;
    for (int step = 0; step < 400; ++step) {
      // A random tet outside the region with a face on it, and how many faces it shares.
      std::vector<std::pair<TetId, int>> candidates;
      for (std::uint32_t t = 0; t < nt; ++t) {
        if (in[t]) continue;
        int shared = 0;
        for (int i = 0; i < 4; ++i) {
          const TetId u = mesh.tet_neighbor(TetId(t), i);
          shared += u.is_valid() && in[u.idx()];
        }
        if (shared > 0) candidates.push_back({TetId(t), shared});
      }
      if (candidates.empty()) break;
      // Half of the steps among the candidates sharing two faces (the rarer rule).
      std::vector<std::pair<TetId, int>> two;
      for (const auto& c : candidates)
        if (c.second == 2) two.push_back(c);
      const auto& pool = !two.empty() && rng() % 2 ? two : candidates;
      const auto [t, shared] = pool[rng() % pool.size()];
      const bool disk = attaches_along_disk(mesh, t, [&](TetId u) { return in[u.idx()] != 0; }, scratch);
      const bool ball_after = is_ball(mesh, in, t);
      if (disk) {
        ++accepted;
        CHECK_MESSAGE(ball_after, "round " << round << " step " << step << ": accepted tet " << t.idx());
      } else if (!ball_after) {
        ++broke[shared];
      }
      if (ball_after) in[t.idx()] = 1;
    }
  }
  // Refusals that mattered with one and with two shared faces occur, so a predicate that skips either
  // rule (or accepts everything) fails above.
  CHECK(accepted > 1000);
  CHECK(broke[1] > 10);
  CHECK(broke[2] > 10);
  MESSAGE("accepted " << accepted << "; refused steps that broke the ball, by shared faces: " << broke[1] << ", " << broke[2]
                      << ", " << broke[3] << ", " << broke[4]);
}
