// Quadric edge-collapse decimation with OpenMesh (see decimate.hpp). Points are doubles; the
// output keeps OpenMesh's vertex order after garbage collection (deterministic). A collapse sequence
// that makes an embedded surface self-intersect is run again from the input towards a target
// kEmbeddedTargetGrowth times larger, until the result is embedded (exact test, self_intersection.hpp).
#include <volmap/tetgen/decimate.hpp>
#include <volmap/check/self_intersection.hpp>
#include <volmap/core/error.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <algorithm>
#include <vector>

namespace volmap {
namespace {

// Each retry of an embedding-keeping decimation aims at this many times the last target.
constexpr double kEmbeddedTargetGrowth = 1.25;

struct DoubleTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

// OpenMesh's error stream muted for the scope (the library prints nothing; the decimater warns).
struct MuteOpenMeshErrors {
  const bool was_enabled = omerr().is_enabled();
  MuteOpenMeshErrors() { omerr().disable(); }
  ~MuteOpenMeshErrors() {
    if (was_enabled) omerr().enable();
  }
};

std::string topology_problem(const SurfaceData& s) {
  TriangleSurface t;
  t.xyz = s.xyz;
  t.tris = s.tris;
  return surface_topology_problem(t);
}

Mesh build_mesh(const SurfaceData& s) {
  Mesh mesh;
  std::vector<Mesh::VertexHandle> vh(s.num_vertices());
  for (std::size_t v = 0; v < vh.size(); ++v)
    vh[v] = mesh.add_vertex(Mesh::Point(s.xyz[3 * v], s.xyz[3 * v + 1], s.xyz[3 * v + 2]));
  for (std::size_t f = 0; f < s.num_triangles(); ++f) {
    const auto h = mesh.add_face(vh[s.tris[3 * f]], vh[s.tris[3 * f + 1]], vh[s.tris[3 * f + 2]]);
    if (!h.is_valid()) throw Error(ErrorKind::BadInput, "", 0, "decimate: triangle " + std::to_string(f) + " is not manifold");
  }
  return mesh;
}

SurfaceData flatten(Mesh& mesh) {
  mesh.garbage_collection();
  SurfaceData s;
  s.xyz.reserve(3 * mesh.n_vertices());
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    s.xyz.insert(s.xyz.end(), {p[0], p[1], p[2]});
  }
  s.tris.reserve(3 * mesh.n_faces());
  for (const auto f : mesh.faces())
    for (const auto v : mesh.fv_range(f)) s.tris.push_back(static_cast<std::uint32_t>(v.idx()));
  return s;
}

bool embedded(const SurfaceData& s) {
  SelfIntersectionOptions options;
  options.max_reported = 0;
  return find_self_intersections(s.xyz, s.tris, options).clean();
}

// One run of the decimater from `surface` down to `target_faces` triangles.
SurfaceData collapse_to(const SurfaceData& surface, const DecimateOptions& options, std::size_t target_faces) {
  const MuteOpenMeshErrors mute;
  Mesh mesh = build_mesh(surface);
  mesh.update_face_normals();
  OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle normals;
  OpenMesh::Decimater::ModAspectRatioT<Mesh>::Handle aspect;
  decimater.add(quadric);
  decimater.add(normals);
  decimater.add(aspect);
  decimater.module(quadric).unset_max_err();
  decimater.module(normals).set_max_normal_deviation(options.max_normal_deviation_deg);
  decimater.module(aspect).set_aspect_ratio(static_cast<float>(options.min_aspect_ratio));
  if (!decimater.initialize()) throw Error(ErrorKind::Failed, "", 0, "decimate: OpenMesh decimater did not initialize");
  decimater.decimate_to_faces(0, target_faces);
  SurfaceData result = flatten(mesh);
  if (const std::string problem = topology_problem(result); !problem.empty())
    throw Error(ErrorKind::Failed, "", 0, "decimate: the decimated surface is broken: " + problem);
  return result;
}

}  // namespace

DecimateResult decimate_surface(const SurfaceData& surface, const DecimateOptions& options) {
  if (const std::string problem = topology_problem(surface); !problem.empty())
    throw Error(ErrorKind::BadInput, "", 0, "decimate: " + problem);
  DecimateResult result;
  result.faces_before = surface.num_triangles();
  result.target_used = options.target_faces;
  const bool keep_embedded = options.keep_embedded && result.faces_before > options.target_faces && embedded(surface);
  for (std::size_t target = options.target_faces; target < result.faces_before;
       target = std::max(target + 1, static_cast<std::size_t>(kEmbeddedTargetGrowth * double(target)))) {
    result.surface = collapse_to(surface, options, target);
    result.target_used = target;
    if (!keep_embedded || embedded(result.surface)) {
      result.faces_after = result.surface.num_triangles();
      result.reached_target = result.faces_after <= options.target_faces;
      return result;
    }
    ++result.embedding_retries;
  }
  result.surface = surface;  // at most target_faces triangles already, or no decimation stays embedded
  result.target_used = result.faces_before;
  result.faces_after = result.faces_before;
  result.reached_target = result.faces_after <= options.target_faces;
  return result;
}

}  // namespace volmap
