// Boundary faces of raw tet arrays by sorting: every half-face is bucketed by its smallest vertex
// id (counting sort, O(#faces + #vertices)), then each bucket is sorted by the packed key of the
// other two (sorted) ids; runs of length 1 are boundary faces. No hashing, no per-face allocation.
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>

#include <algorithm>
#include <string>

namespace volmap {
namespace {

struct FaceKey {
  std::uint64_t rest;  // (middle id << 32) | largest id
  std::uint64_t hf;    // half-face id 4t+i
};

void check_tet_ids(const TetMeshData& mesh) {
  const std::size_t nv = mesh.num_vertices();
  for (std::size_t k = 0; k < mesh.tets.size(); ++k)
    if (mesh.tets[k] >= nv)
      throw Error(ErrorKind::BadInput, "tet " + std::to_string(k / 4) + " references vertex " + std::to_string(mesh.tets[k]) +
                      " but the mesh has " + std::to_string(nv) + " vertices");
}

inline void sorted_triple(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t& lo,
                          std::uint32_t& mid, std::uint32_t& hi) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  lo = a, mid = b, hi = c;
}

}  // namespace

std::vector<std::uint64_t> boundary_half_faces(const TetMeshData& mesh) {
  check_tet_ids(mesh);
  const std::size_t nv = mesh.num_vertices();
  const std::size_t nf = mesh.tets.size();  // 4 half-faces per tet
  const std::uint32_t* tets = mesh.tets.data();

  // Counting sort by the smallest vertex id of each face.
  std::vector<std::size_t> start(nv + 1, 0);
  for (std::size_t hf = 0; hf < nf; ++hf) {
    const std::uint32_t* t = tets + (hf & ~std::size_t(3));
    const std::uint8_t* l = kTetFace[hf & 3];
    std::uint32_t lo, mid, hi;
    sorted_triple(t[l[0]], t[l[1]], t[l[2]], lo, mid, hi);
    ++start[lo + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<FaceKey> keys(nf);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t hf = 0; hf < nf; ++hf) {
      const std::uint32_t* t = tets + (hf & ~std::size_t(3));
      const std::uint8_t* l = kTetFace[hf & 3];
      std::uint32_t lo, mid, hi;
      sorted_triple(t[l[0]], t[l[1]], t[l[2]], lo, mid, hi);
      keys[fill[lo]++] = FaceKey{(std::uint64_t(mid) << 32) | hi, hf};
    }
  }

  std::vector<std::uint64_t> boundary;
  for (std::size_t v = 0; v < nv; ++v) {
    FaceKey* first = keys.data() + start[v];
    FaceKey* last = keys.data() + start[v + 1];
    std::sort(first, last, [](const FaceKey& x, const FaceKey& y) {
      return x.rest < y.rest || (x.rest == y.rest && x.hf < y.hf);
    });
    for (FaceKey* run = first; run != last;) {
      FaceKey* end = run + 1;
      while (end != last && end->rest == run->rest) ++end;
      if (end - run == 1) boundary.push_back(run->hf);
      run = end;
    }
  }
  std::sort(boundary.begin(), boundary.end());
  return boundary;
}

std::vector<std::uint32_t> boundary_vertex_ids(const TetMeshData& mesh,
                                               const std::vector<std::uint64_t>& boundary_faces) {
  const std::size_t nv = mesh.num_vertices();
  std::vector<std::uint8_t> on_boundary(nv, 0);
  for (std::uint64_t hf : boundary_faces) {
    if (hf / 4 >= mesh.num_tets())
      throw Error(ErrorKind::BadInput, "half-face id " + std::to_string(hf) + " out of range");
    for (std::uint32_t v : half_face_vertices(mesh, hf)) {
      if (v >= nv)
        throw Error(ErrorKind::BadInput, "boundary face references vertex " + std::to_string(v) +
                                                    " out of range");
      on_boundary[v] = 1;
    }
  }
  std::vector<std::uint32_t> ids;
  for (std::size_t v = 0; v < nv; ++v)
    if (on_boundary[v]) ids.push_back(static_cast<std::uint32_t>(v));
  return ids;
}

std::vector<std::uint32_t> boundary_vertex_ids(const TetMeshData& mesh) {
  return boundary_vertex_ids(mesh, boundary_half_faces(mesh));
}

}  // namespace volmap
