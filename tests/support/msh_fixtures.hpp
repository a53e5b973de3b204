// Tiny Gmsh .msh files written byte by byte from the format description (an oracle independent of
// volmap's writer): MSH 2.2 and 4.1, ASCII or binary, little- or big-endian, 4.1 with data-size 4 or 8.
// Every fixture holds the same mixed mesh:
//   nodes in file order, tags 3 1 7 2 5 9 at (0,0,0) (1,0,0) (5,5,5) (0,1,0) (0,0,1) (1,1,1/3)
//     (tag 7 is used by a line only, so the reader drops it);
//   one point, one line, two triangles, then tets [3 1 2 5] (physical 11, entity 1) and
//   [1 2 5 9] (physical 12, entity 2), both in Gmsh's orientation (orient3d < 0).
// kExpected is what read_msh must return.
#pragma once

#include <volmap/core/mesh_data.hpp>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace volmap_test {

struct MshFixture {
  int version = 41;         // 22 or 41
  bool binary = false;
  bool big_endian = false;
  int size_bytes = 8;       // 4.1 data-size
  bool physicals = true;    // false: no physical tags (labels then come from the entity tags)
};

// Values written as ASCII tokens or as binary words in the chosen byte order.
class MshBytes {
 public:
  MshBytes(bool binary, bool big_endian) : binary_(binary), big_(big_endian) {}
  void text(const std::string& s) { out_ += s; }
  void word(std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_.push_back(static_cast<char>((v >> (8 * (big_ ? bytes - 1 - i : i))) & 0xff));
  }
  void i32(long long v, const char* sep = " ") {
    if (binary_) return word(static_cast<std::uint32_t>(static_cast<std::int32_t>(v)), 4);
    out_ += std::to_string(v) + sep;
  }
  void size(unsigned long long v, int bytes, const char* sep = " ") {
    if (binary_) return word(v, bytes);
    out_ += std::to_string(v) + sep;
  }
  void f64(double v, const char* sep = " ") {
    if (binary_) {
      std::uint64_t b;
      std::memcpy(&b, &v, 8);
      return word(b, 8);
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    out_ += std::string(buf) + sep;
  }
  void end_payload(const std::string& end) { out_ += (binary_ ? "\n" : "") + end; }
  const std::string& str() const { return out_; }

 private:
  std::string out_;
  bool binary_, big_;
};

inline const double kThird = 1.0 / 3.0;
struct FixtureNode {
  unsigned tag;
  double x, y, z;
};
inline const FixtureNode kFixtureNodes[6] = {{3, 0, 0, 0}, {1, 1, 0, 0}, {7, 5, 5, 5},
                                             {2, 0, 1, 0}, {5, 0, 0, 1}, {9, 1, 1, kThird}};

inline volmap::TetMeshData msh_fixture_expected(bool physicals = true) {
  volmap::TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, kThird};
  m.vertex_labels = {0, 0, 0, 0, 0};
  m.tets = {0, 1, 2, 3, 1, 2, 3, 4};
  m.tet_labels = physicals ? std::vector<std::int32_t>{11, 12} : std::vector<std::int32_t>{1, 2};
  return m;
}

inline std::string msh_fixture(const MshFixture& f) {
  MshBytes b(f.binary, f.big_endian);
  const int sz = f.size_bytes;
  b.text(std::string("$MeshFormat\n") + (f.version == 22 ? "2.2 " : "4.1 ") + (f.binary ? "1 " : "0 ") +
         (f.version == 22 ? "8" : std::to_string(sz)) + "\n");
  if (f.binary) {
    b.word(1, 4);
    b.text("\n");
  }
  b.text("$EndMeshFormat\n$Comments\nwritten by a test; skipped by readers\n$EndComments\n");
  const long long phys[2] = {f.physicals ? 11 : 0, f.physicals ? 12 : 0};
  if (f.version == 22) {
    b.text("$PhysicalNames\n2\n3 11 \"left part\"\n3 12 \"right\"\n$EndPhysicalNames\n$Nodes\n6\n");
    for (const FixtureNode& n : kFixtureNodes) {
      b.i32(n.tag);
      b.f64(n.x), b.f64(n.y), b.f64(n.z, "\n");
    }
    b.end_payload("$EndNodes\n$Elements\n6\n");
    // tag, type, tags (physical, elementary), nodes
    struct El { int tag, type; long long physical; int entity; std::vector<int> nodes; };
    const El els[6] = {{1, 15, 0, 1, {3}},         {2, 1, 0, 1, {7, 3}},         {3, 2, 0, 1, {3, 1, 2}},
                       {4, 2, 0, 1, {1, 2, 5}},    {5, 4, phys[0], 1, {3, 1, 2, 5}}, {6, 4, phys[1], 2, {1, 2, 5, 9}}};
    if (f.binary) {  // blocks of equal type: header (type, count, ntags), then tag, tags, nodes
      const int blocks[4][2] = {{0, 1}, {1, 1}, {2, 2}, {4, 2}};
      for (const auto& blk : blocks) {
        b.i32(els[blk[0]].type), b.i32(blk[1]), b.i32(2);
        for (int e = blk[0]; e < blk[0] + blk[1]; ++e) {
          b.i32(els[e].tag), b.i32(els[e].physical), b.i32(els[e].entity);
          for (int n : els[e].nodes) b.i32(n);
        }
      }
    } else {
      for (const El& e : els) {
        b.text(std::to_string(e.tag) + " " + std::to_string(e.type) + " 2 " + std::to_string(e.physical) + " " +
               std::to_string(e.entity));
        for (int n : e.nodes) b.text(" " + std::to_string(n));
        b.text("\n");
      }
    }
    b.end_payload("$EndElements\n");
    return b.str();
  }
  // 4.1: entities (1 point, 1 curve, 1 surface, 2 volumes), nodes in 4 blocks, elements in 5 blocks.
  b.text("$Entities\n");
  b.size(1, sz), b.size(1, sz), b.size(1, sz), b.size(2, sz, "\n");
  b.i32(1), b.f64(0), b.f64(0), b.f64(0), b.size(0, sz, "\n");
  b.i32(1);
  for (int k = 0; k < 6; ++k) b.f64(k < 3 ? 0 : 5);
  b.size(0, sz), b.size(2, sz), b.i32(1), b.i32(-1, "\n");
  b.i32(1);
  for (int k = 0; k < 6; ++k) b.f64(k < 3 ? 0 : 1);
  b.size(0, sz), b.size(1, sz), b.i32(1, "\n");
  for (int v = 1; v <= 2; ++v) {
    b.i32(v);
    for (int k = 0; k < 6; ++k) b.f64(k < 3 ? 0 : 1);
    b.size(f.physicals ? 1 : 0, sz);
    if (f.physicals) b.i32(phys[v - 1]);
    b.size(1, sz), b.i32(1, "\n");
  }
  b.end_payload("$EndEntities\n$Nodes\n");
  b.size(4, sz), b.size(6, sz), b.size(1, sz), b.size(9, sz, "\n");
  struct NodeBlock { int dim, entity, parametric, first, count; };
  const NodeBlock nblocks[4] = {{0, 1, 0, 0, 1}, {3, 1, 0, 1, 1}, {1, 1, 1, 2, 1}, {3, 1, 0, 3, 3}};
  for (const NodeBlock& nb : nblocks) {
    b.i32(nb.dim), b.i32(nb.entity), b.i32(nb.parametric), b.size(nb.count, sz, "\n");
    for (int i = nb.first; i < nb.first + nb.count; ++i) b.size(kFixtureNodes[i].tag, sz, "\n");
    for (int i = nb.first; i < nb.first + nb.count; ++i) {
      b.f64(kFixtureNodes[i].x), b.f64(kFixtureNodes[i].y), b.f64(kFixtureNodes[i].z, nb.parametric ? " " : "\n");
      if (nb.parametric) b.f64(0.25, "\n");  // u on the curve
    }
  }
  b.end_payload("$EndNodes\n$Elements\n");
  b.size(5, sz), b.size(6, sz), b.size(1, sz), b.size(6, sz, "\n");
  struct ElBlock { int dim, entity, type; std::vector<std::vector<int>> elements; };  // each: tag, nodes
  const ElBlock eblocks[5] = {{0, 1, 15, {{1, 3}}},
                              {1, 1, 1, {{2, 7, 3}}},
                              {2, 1, 2, {{3, 3, 1, 2}, {4, 1, 2, 5}}},
                              {3, 1, 4, {{5, 3, 1, 2, 5}}},
                              {3, 2, 4, {{6, 1, 2, 5, 9}}}};
  for (const ElBlock& eb : eblocks) {
    b.i32(eb.dim), b.i32(eb.entity), b.i32(eb.type), b.size(eb.elements.size(), sz, "\n");
    for (const auto& e : eb.elements) {
      for (std::size_t k = 0; k < e.size(); ++k) b.size(static_cast<unsigned>(e[k]), sz, k + 1 == e.size() ? "\n" : " ");
    }
  }
  b.end_payload("$EndElements\n");
  return b.str();
}

}  // namespace volmap_test
