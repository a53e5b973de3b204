// link_kernel.cpp — link-kernel relocation (docs/mapping.md §7 pre-step); conventions in link_kernel.hpp.
#include <volmap/volume/link_kernel.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/kernel_lp.hpp>

namespace volmap {

RelocationResult relocate_into_link_kernels(const TetMesh& mesh, const std::vector<std::uint8_t>& locked,
                                            std::vector<double>& X, int max_sweeps) {
  const std::size_t nv = mesh.num_vertex_slots(), nt = mesh.num_tet_slots();
  if (mesh.num_free_tet_slots() != 0 || mesh.num_vertices() != nv)
    throw Error(ErrorKind::BadInput, "", 0, "relocate_into_link_kernels: the mesh has tombstones (compact it first)");
  if (locked.size() != nv || X.size() != 3 * nv) throw Error(ErrorKind::BadInput, "", 0, "relocate_into_link_kernels: inconsistent array sizes");
  const std::vector<std::uint32_t>& tets = mesh.tet_vertex_array();
  RelocationResult res;
  std::vector<std::int8_t> sign(nt);
  auto count_bad = [&] { return count_nonpositive(X.data(), nv, tets.data(), nt, sign.data()); };
  res.nonpositive_before = count_bad();
  std::size_t bad = res.nonpositive_before;
  std::vector<double> tri;
  std::vector<std::uint8_t> mark(nv, 0);
  const FpEnvironmentScope fp;  // one MXCSR check for all kernel verifications below
  for (int sweep = 0; sweep < max_sweeps && bad > 0; ++sweep) {
    res.sweeps = sweep + 1;
    std::vector<std::uint32_t> cand;
    for (std::size_t t = 0; t < nt; ++t)
      if (sign[t] <= 0)
        for (int i = 0; i < 4; ++i) {
          const std::uint32_t v = tets[4 * t + i];
          if (!locked[v] && !mark[v]) {
            mark[v] = 1;
            cand.push_back(v);
          }
        }
    for (auto v : cand) mark[v] = 0;
    std::size_t moved = 0;
    for (std::uint32_t v : cand) {
      // The link of v: the face opposite v in every tet of its star.
      tri.clear();
      for (TetId t : mesh.vertex_tets(VertexId(v))) {
        const auto face = mesh.half_face_vertices(HalfFaceId(t, mesh.tet_local_index(t, VertexId(v))));
        for (VertexId u : face)
          for (int i = 0; i < 3; ++i) tri.push_back(X[3 * std::size_t(u.idx()) + i]);
      }
      double q[3];
      if (!strict_kernel_point(fp, tri, q)) continue;
      for (int i = 0; i < 3; ++i) X[3 * std::size_t(v) + i] = q[i];
      ++moved;
    }
    res.moved += moved;
    bad = count_bad();
    if (moved == 0) break;
  }
  res.nonpositive_after = bad;
  return res;
}

}  // namespace volmap
