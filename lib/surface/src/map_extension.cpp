// Carrying a boundary map across midpoint edge splits (see map_extension.hpp).
// Replay: start from the original boundary triangles; for each new vertex v (increasing id, the order
// the splits were made in), its parent edge is the current boundary edge whose rounded midpoint
// 0.5*(a+b) equals v's position bit for bit; split that edge in the triangle list and give v the
// midpoint of the parents' images. At the end the replayed triangles must be exactly the refined
// mesh's boundary triangles, which certifies the parent recovery.
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/surface/map_extension.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <unordered_map>

namespace volmap {
namespace {

constexpr std::uint32_t kNone = 0xFFFFFFFFu;
using Triangle = std::array<std::uint32_t, 3>;

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

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

class SplitReplay {
 public:
  SplitReplay(const TetMeshData& refined, std::vector<Triangle> triangles) : xyz_(refined.xyz), tris_(std::move(triangles)) {
    edges_.reserve(3 * tris_.size());
    midpoints_.reserve(3 * tris_.size());
    for (std::uint32_t t = 0; t < tris_.size(); ++t)
      for (int k = 0; k < 3; ++k) attach(tris_[t][k], tris_[t][(k + 1) % 3], t);
  }

  // The current edge whose rounded midpoint is at v's position, or false.
  bool find_parent_edge(std::uint32_t v, std::uint32_t& a, std::uint32_t& b) const {
    const auto it = midpoints_.find(point_key(&xyz_[3 * v]));
    if (it == midpoints_.end()) return false;
    a = static_cast<std::uint32_t>(it->second >> 32);
    b = static_cast<std::uint32_t>(it->second & 0xFFFFFFFFu);
    return true;
  }

  void split(std::uint32_t a, std::uint32_t b, std::uint32_t v) {
    const auto incident = edges_.at(edge_key(a, b));
    edges_.erase(edge_key(a, b));
    midpoints_.erase(midpoint_key(a, b));
    for (const std::uint32_t t : incident) {
      if (t == kNone) continue;
      // Rotate (p,q,r) so that (p,q) is the split edge in the triangle's own direction.
      Triangle tri = tris_[t];
      while (!((tri[0] == a && tri[1] == b) || (tri[0] == b && tri[1] == a))) std::rotate(tri.begin(), tri.begin() + 1, tri.end());
      const std::uint32_t p = tri[0], q = tri[1], r = tri[2];
      const auto n = static_cast<std::uint32_t>(tris_.size());
      tris_[t] = {p, v, r};
      tris_.push_back({v, q, r});
      auto& qr = edges_.at(edge_key(q, r));
      std::replace(qr.begin(), qr.end(), t, n);
      attach(p, v, t);
      attach(v, q, n);
      attach(v, r, t);
      attach(v, r, n);
    }
  }

  std::vector<Triangle>& triangles() { return tris_; }

 private:
  PointKey midpoint_key(std::uint32_t a, std::uint32_t b) const {
    double m[3];
    for (int k = 0; k < 3; ++k) m[k] = 0.5 * (xyz_[3 * a + k] + xyz_[3 * b + k]);
    return point_key(m);
  }
  void attach(std::uint32_t a, std::uint32_t b, std::uint32_t t) {
    auto [it, inserted] = edges_.try_emplace(edge_key(a, b), std::array<std::uint32_t, 2>{kNone, kNone});
    auto& slots = it->second;
    if (slots[0] == t || slots[1] == t) return;
    if (slots[0] == kNone) slots[0] = t;
    else if (slots[1] == kNone) slots[1] = t;
    else throw Error(ErrorKind::Failed, "", 0, "boundary edge with more than two triangles while replaying splits");
    if (inserted) midpoints_.emplace(midpoint_key(a, b), edge_key(a, b));
  }

  const std::vector<double>& xyz_;
  std::vector<Triangle> tris_;
  std::unordered_map<std::uint64_t, std::array<std::uint32_t, 2>> edges_;
  std::unordered_map<PointKey, std::uint64_t, PointKeyHash> midpoints_;
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

  SplitReplay replay(refined, boundary_triangles(original));
  for (auto v = static_cast<std::uint32_t>(old_nv); v < nv; ++v) {
    std::uint32_t a, b;
    if (!replay.find_parent_edge(v, a, b)) continue;  // an interior vertex (checked below)
    if (!has_image[a] || !has_image[b])
      throw Error(ErrorKind::Failed, "", 0, "boundary vertex without image while replaying splits");
    replay.split(a, b, v);
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
