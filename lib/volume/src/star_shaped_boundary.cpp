// star_shaped_boundary.cpp — ∂M star-shaped in the source and in the map's image (conventions in
// star_shaped_boundary.hpp): one kernel LP per space over the boundary faces, each point verified
// exactly.
#include <volmap/volume/star_shaped_boundary.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/volume/kernel_lp.hpp>

#include <vector>

namespace volmap {

namespace {

// The map's position of every vertex (0 where it prescribes none); `prescribed` marks the ones it
// does. False when the map's arrays disagree or an id is out of range.
bool map_positions(const TetMeshData& source, const BoundaryMap& map, std::vector<double>& xyz, std::vector<bool>& prescribed) {
  const std::size_t nv = source.num_vertices();
  if (map.xyz.size() != 3 * map.vids.size()) return false;
  xyz.assign(3 * nv, 0.0);
  prescribed.assign(nv, false);
  for (std::size_t k = 0; k < map.vids.size(); ++k) {
    const std::uint32_t v = map.vids[k];
    if (v >= nv) return false;
    prescribed[v] = true;
    for (int d = 0; d < 3; ++d) xyz[3 * v + d] = map.xyz[3 * k + d];
  }
  return true;
}

}  // namespace

bool boundary_star_shaped_in_both_spaces(const TetMeshData& source, const BoundaryMap& map) {
  double p[3], q[3];
  return boundary_kernel_points(source, map, p, q);
}

bool boundary_kernel_points(const TetMeshData& source, const BoundaryMap& map, double* source_point, double* image_point) {
  std::vector<double> image;
  std::vector<bool> prescribed;
  if (!map_positions(source, map, image, prescribed)) return false;
  std::vector<std::uint64_t> faces;
  try {
    faces = boundary_half_faces(source);
  } catch (const Error&) {
    return false;
  }
  if (faces.empty()) return false;
  std::vector<double> in_source, in_image;
  in_source.reserve(9 * faces.size());
  in_image.reserve(9 * faces.size());
  for (const std::uint64_t hf : faces)
    for (const std::uint32_t v : half_face_vertices(source, hf)) {
      if (!prescribed[v]) return false;
      for (int d = 0; d < 3; ++d) {
        in_source.push_back(source.xyz[3 * v + d]);
        in_image.push_back(image[3 * v + d]);
      }
    }
  return strict_kernel_point(in_image, image_point) && strict_kernel_point(in_source, source_point);
}

}  // namespace volmap
