// chord_cone.cpp — B0's vertex cone (docs/mapping.md §4; conventions in chord_cone.hpp). Faces of
// the star's boundary are listed in the outward order of the star tet they bound (kTetFace), so a
// point q sees one from inside iff orient3d(face, q) > 0 and the cone tet is (face, w).
#include <volmap/volume/chord_cone.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/chord_rules.hpp>
#include <volmap/volume/kernel_lp.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace volmap {

std::size_t boundary_faces_at(const TetMesh& mesh, std::uint32_t v) {
  if (!mesh.vertex_is_boundary(VertexId(v))) return 0;
  thread_local std::vector<TetId> star;
  mesh.vertex_star(VertexId(v), star);
  std::size_t n = 0;
  for (TetId t : star)
    for (int i = 0; i < 4; ++i)
      n += mesh.half_face_is_boundary(HalfFaceId(t, i)) && mesh.tet_vertex(t, i).idx() != v;
  return n;
}

bool cone_vertex_star(TetMesh& mesh, std::uint32_t v) {
  if (!mesh.vertex_is_boundary(VertexId(v))) return false;
  std::vector<TetId> star;
  mesh.vertex_star(VertexId(v), star);
  // ∂R: each star tet's face opposite v, and its faces on ∂M through v.
  std::vector<std::array<VertexId, 3>> faces;
  std::vector<TetId> parents;
  double worst = std::numeric_limits<double>::infinity();
  for (TetId t : star) {
    const auto tv = mesh.tet_vertices(t);
    const double* p[4];
    for (int i = 0; i < 4; ++i) p[i] = mesh.vertex_position(tv[i]);
    worst = std::min(worst, tet_shape(p[0], p[1], p[2], p[3]));
    for (int i = 0; i < 4; ++i) {
      const bool opposite = tv[i].idx() == v;
      if (!opposite && !mesh.half_face_is_boundary(HalfFaceId(t, i))) continue;
      faces.push_back(mesh.half_face_vertices(HalfFaceId(t, i)));
      parents.push_back(t);
    }
  }
  std::vector<double> triangles;
  triangles.reserve(9 * faces.size());
  for (const auto& f : faces)
    for (VertexId x : f) triangles.insert(triangles.end(), mesh.vertex_position(x), mesh.vertex_position(x) + 3);
  double w[3];
  if (!strict_kernel_point(triangles, w)) return false;  // exact: w strictly inside every face
  for (const auto& f : faces) {
    if (tet_shape(mesh.vertex_position(f[0]), mesh.vertex_position(f[1]), mesh.vertex_position(f[2]), w) < kFixShapeRatio * worst) return false;
  }
  std::vector<CavityTet> fill;
  fill.reserve(faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k) fill.push_back({{faces[k][0], faces[k][1], faces[k][2], CavityTet::new_vertex(0)}, parents[k]});
  try {
    mesh.replace_cavity(star, fill, {w[0], w[1], w[2]});
  } catch (const Error&) {  // refused (e.g. a pinched vertex whose star is not a ball): untouched
    return false;
  }
  return true;
}

}  // namespace volmap
