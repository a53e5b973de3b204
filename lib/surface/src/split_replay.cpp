// The mapper's source tet mesh and the replay of boundary edge splits (see split_replay.hpp).
#include "split_replay.hpp"

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <string>

namespace volmap::surface_detail {
namespace {

[[noreturn]] void fail(const std::string& reason) { throw Error(ErrorKind::Failed, "", 0, reason); }

}  // namespace

SourceTetMesh::SourceTetMesh(const TetMeshData& mesh) : data_(mesh) {
  const std::size_t nv = mesh.num_vertices();
  std::vector<char> used(nv, 0);
  for (std::size_t k = 0; k < mesh.tets.size(); ++k) {
    if (mesh.tets[k] >= nv)
      throw Error(ErrorKind::BadInput, "", 0,
                  "tet " + std::to_string(k / 4) + " has an out-of-range vertex id " + std::to_string(mesh.tets[k]));
    used[mesh.tets[k]] = 1;
  }
  all_used_ = std::find(used.begin(), used.end(), 0) == used.end();
  if (!all_used_) {
    compact_of_.assign(nv, kInvalidIndex);
    for (std::uint32_t v = 0; v < nv; ++v)
      if (used[v]) {
        compact_of_[v] = static_cast<std::uint32_t>(original_of_.size());
        original_of_.push_back(v);
      }
  }
  build_tet_mesh();
}

void SourceTetMesh::build_tet_mesh() {
  edited_ = false;
  if (all_used_) {
    tm_ = TetMesh(data_);
    return;
  }
  TetMeshData compact;
  for (auto v : original_of_) compact.xyz.insert(compact.xyz.end(), &data_.xyz[3 * std::size_t(v)], &data_.xyz[3 * std::size_t(v)] + 3);
  compact.tets = data_.tets;
  for (auto& v : compact.tets) v = compact_of_[v];
  compact.tet_labels = data_.tet_labels;
  tm_ = TetMesh(compact);
}

std::uint32_t SourceTetMesh::to_tet_mesh(std::uint32_t vid) const {
  if (all_used_) return vid;
  const auto nv = num_input_vertices();
  return vid < nv ? compact_of_[vid] : static_cast<std::uint32_t>(original_of_.size() + (vid - nv));
}

std::uint32_t SourceTetMesh::to_output(std::uint32_t tid) const {
  if (all_used_) return tid;
  const auto nu = static_cast<std::uint32_t>(original_of_.size());
  return tid < nu ? original_of_[tid] : num_input_vertices() + (tid - nu);
}

BoundarySurface SourceTetMesh::boundary_surface() const {
  if (edited_) fail("internal: the boundary surface asked for after a replay");
  BoundarySurface b = extract_boundary_surface(tm_);
  if (!all_used_)
    for (auto v : b.mesh.vertices()) b.mesh.property(b.tet_vertex, v) = to_output(b.mesh.property(b.tet_vertex, v));
  return b;
}

SourceTetMesh::Refined SourceTetMesh::refine(const std::vector<EdgeSplit>& splits) {
  Refined out;
  if (edited_) build_tet_mesh();
  edited_ = !splits.empty();
  TetMesh& tm = tm_;
  for (const EdgeSplit& sp : splits) {
    const VertexId m = tm.split_edge(VertexId(to_tet_mesh(sp.a)), VertexId(to_tet_mesh(sp.b)), sp.p.data());
    if (m.idx() != to_tet_mesh(sp.m))
      fail("internal: the tet mesh numbered split vertex " + std::to_string(sp.m) + " differently");
  }
  const std::size_t nv0 = data_.num_vertices();
  if (splits.empty()) {
    out.mesh = data_;
  } else {
    // Splits reuse the parent's slot and append the other child: no tombstones, slot = tet id.
    if (tm.num_tet_slots() != tm.num_tets()) fail("internal: the split replay left tombstones");
    out.mesh.xyz.reserve(data_.xyz.size() + 3 * splits.size());
    out.mesh.xyz = data_.xyz;
    for (const EdgeSplit& sp : splits) out.mesh.xyz.insert(out.mesh.xyz.end(), sp.p.begin(), sp.p.end());
    out.mesh.vertex_labels = data_.vertex_labels;
    out.mesh.vertex_labels.resize(nv0 + splits.size(), 0);
    out.mesh.tets = tm.tet_vertex_array();
    if (!all_used_)
      for (auto& v : out.mesh.tets) v = to_output(v);
    out.mesh.tet_labels = tm.tet_labels();
    out.mesh.tet_labels.resize(tm.num_tets(), 0);
    const auto& xyz = out.mesh.xyz;
    for (std::size_t t = 0; t < out.mesh.num_tets(); ++t) {
      const std::uint32_t* q = &out.mesh.tets[4 * t];
      if (q[0] < nv0 && q[1] < nv0 && q[2] < nv0 && q[3] < nv0) continue;
      if (orient3d(&xyz[3 * q[0]], &xyz[3 * q[1]], &xyz[3 * q[2]], &xyz[3 * q[3]]) <= 0)
        fail("splitting a boundary edge produced a non-positive tet " + std::to_string(t) + " (midpoint rounding)");
    }
  }
  const auto faces = tm.boundary_half_faces();
  out.boundary.reserve(faces.size());
  for (HalfFaceId h : faces) {
    const auto f = tm.half_face_vertices(h);
    out.boundary.push_back({to_output(f[0].idx()), to_output(f[1].idx()), to_output(f[2].idx())});
  }
  return out;
}

}  // namespace volmap::surface_detail
