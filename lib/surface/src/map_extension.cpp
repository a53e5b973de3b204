// Carrying a boundary map across midpoint edge splits (see map_extension.hpp).
// Replay on the original boundary as an OpenMesh surface (boundary_surface.hpp): for each new vertex
// v (increasing id, the order the splits were made in), its parent edge is the current surface edge
// whose rounded midpoint 0.5*(a+b) equals v's position bit for bit; OpenMesh's 2-to-4 split inserts
// v there and v gets the midpoint of the parents' images. At the end the replayed triangles must be
// exactly the refined mesh's boundary triangles, which certifies the parent recovery. The only index
// kept beside the mesh is geometric: rounded midpoint -> surface edge.
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/surface/boundary_surface.hpp>
#include <volmap/surface/map_extension.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <unordered_map>

namespace volmap {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

// A rounded midpoint as a hashable key (bit patterns of the three doubles; -0 folded into +0).
struct PointKey {
  std::uint64_t bits[3];
  bool operator==(const PointKey& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
};
struct PointKeyHash {
  std::size_t operator()(const PointKey& k) const {
    return std::hash<std::uint64_t>()(k.bits[0] * 0x9E3779B97F4A7C15ull ^ k.bits[1] * 0xC2B2AE3D27D4EB4Full ^ k.bits[2]);
  }
};
PointKey point_key(const double* p) {
  PointKey k;
  for (int i = 0; i < 3; ++i) {
    const double x = p[i] == 0.0 ? 0.0 : p[i];
    std::memcpy(&k.bits[i], &x, sizeof x);
  }
  return k;
}

// The original boundary surface, split edge by edge in the order of the refined mesh's new vertices.
class SplitReplay {
 public:
  SplitReplay(const TetMeshData& original, const TetMeshData& refined)
      : surface_(extract_boundary_surface(TetMesh(original))), xyz_(refined.xyz) {
    if (!surface_.complete()) throw Error(ErrorKind::Failed, "", 0, "the original boundary is not a manifold surface");
    SurfaceMesh& m = surface_.mesh;
    midpoints_.reserve(2 * m.n_edges());
    for (auto e : m.edges()) index_midpoint(e);
  }

  // The current edge whose rounded midpoint is at v's position, or an invalid handle.
  SurfaceMesh::EdgeHandle parent_edge(std::uint32_t v) const {
    const auto it = midpoints_.find(point_key(&xyz_[3 * v]));
    return it == midpoints_.end() ? SurfaceMesh::EdgeHandle() : it->second;
  }
  std::array<std::uint32_t, 2> ends(SurfaceMesh::EdgeHandle e) const {
    const auto h = surface_.mesh.halfedge_handle(e, 0);
    return {surface_.tet_vertex_of(surface_.mesh.from_vertex_handle(h)), surface_.tet_vertex_of(surface_.mesh.to_vertex_handle(h))};
  }

  void split(SurfaceMesh::EdgeHandle e, std::uint32_t v) {
    SurfaceMesh& m = surface_.mesh;
    midpoints_.erase(midpoint_key(e));
    const auto nv = m.add_vertex(SurfaceMesh::Point(xyz_[3 * v], xyz_[3 * v + 1], xyz_[3 * v + 2]));
    m.property(surface_.tet_vertex, nv) = v;
    m.split(e, nv);
    for (auto ve : m.ve_range(nv)) index_midpoint(ve);
  }

  std::vector<Triangle> triangles() const {
    std::vector<Triangle> tris;
    tris.reserve(surface_.mesh.n_faces());
    for (auto f : surface_.mesh.faces()) {
      Triangle t;
      int k = 0;
      for (auto v : surface_.mesh.fv_range(f)) t[k++] = surface_.tet_vertex_of(v);
      tris.push_back(t);
    }
    return tris;
  }

 private:
  PointKey midpoint_key(SurfaceMesh::EdgeHandle e) const {
    const auto [a, b] = ends(e);
    double mid[3];
    for (int k = 0; k < 3; ++k) mid[k] = 0.5 * (xyz_[3 * a + k] + xyz_[3 * b + k]);
    return point_key(mid);
  }
  void index_midpoint(SurfaceMesh::EdgeHandle e) { midpoints_[midpoint_key(e)] = e; }

  BoundarySurface surface_;
  const std::vector<double>& xyz_;
  std::unordered_map<PointKey, SurfaceMesh::EdgeHandle, PointKeyHash> midpoints_;
};

std::vector<Triangle> boundary_triangles(const TetMeshData& mesh) {
  std::vector<Triangle> tris;
  for (const auto hf : boundary_half_faces(mesh)) {
    const auto f = half_face_vertices(mesh, hf);
    tris.push_back({f[0], f[1], f[2]});
  }
  return tris;
}

// Triangles as sorted vertex triples, sorted: equal lists <=> same boundary up to winding/rotation.
std::vector<Triangle> canonical(std::vector<Triangle> tris) {
  for (auto& t : tris) std::sort(t.begin(), t.end());
  std::sort(tris.begin(), tris.end());
  return tris;
}

}  // namespace

BoundaryMap extend_boundary_map_over_splits(const BoundaryMap& map, const TetMeshData& original,
                                            const TetMeshData& refined) {
  const std::size_t old_nv = original.num_vertices(), nv = refined.num_vertices();
  if (nv < old_nv || !std::equal(original.xyz.begin(), original.xyz.end(), refined.xyz.begin()))
    throw Error(ErrorKind::Failed, "", 0, "the refined mesh does not start with the original vertices");
  std::vector<double> image(3 * nv, 0.0);
  std::vector<char> has_image(nv, 0);
  for (std::size_t i = 0; i < map.size(); ++i) {
    const std::uint32_t v = map.vids[i];
    if (v >= old_nv) throw Error(ErrorKind::BadInput, "", 0, "map vertex " + std::to_string(v) + " is not an original vertex");
    std::copy(&map.xyz[3 * i], &map.xyz[3 * i] + 3, &image[3 * v]);
    has_image[v] = 1;
  }

  SplitReplay replay(original, refined);
  for (auto v = static_cast<std::uint32_t>(old_nv); v < nv; ++v) {
    const auto e = replay.parent_edge(v);
    if (!e.is_valid()) continue;  // an interior vertex (checked below)
    const auto [a, b] = replay.ends(e);
    if (!has_image[a] || !has_image[b])
      throw Error(ErrorKind::Failed, "", 0, "boundary vertex without image while replaying splits");
    replay.split(e, v);
    for (int k = 0; k < 3; ++k) image[3 * v + k] = 0.5 * (image[3 * a + k] + image[3 * b + k]);
    has_image[v] = 1;
  }
  if (canonical(replay.triangles()) != canonical(boundary_triangles(refined)))
    throw Error(ErrorKind::Failed, "", 0, "the refined boundary is not the original one after midpoint edge splits");

  BoundaryMap extended;
  extended.vids = boundary_vertex_ids(refined);
  extended.xyz.reserve(3 * extended.vids.size());
  for (const std::uint32_t v : extended.vids) {
    if (!has_image[v]) throw Error(ErrorKind::Failed, "", 0, "boundary vertex " + std::to_string(v) + " has no image");
    extended.xyz.insert(extended.xyz.end(), &image[3 * v], &image[3 * v] + 3);
  }
  return extended;
}

}  // namespace volmap
