// Gmsh MSH 4.1 writer (ASCII, or binary little-endian with data-size 8), atomic (volmap-reference.md §2.7).
// Layout: $MeshFormat; $Entities with one volume entity per distinct tet label, in order of first
// appearance (entity tags 1..k; physical tag = the label when it is non-zero, none for label 0;
// bounding box of the entity's tets; no bounding surfaces); $Nodes as one block on entity 1, node tags
// 1..n; $Elements as one block of linear tets (type 4) per run of consecutive tets with the same
// label, element tags 1..m in tet order; $NodeData "label" (one component) when some vertex label is
// non-zero. read_msh reads all of it back: labels, vertex and tet order, and every double exactly
// (ASCII doubles are printed in shortest round-trip form).
#include <volmap/io/io.hpp>

#include "io_text.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>

namespace volmap {
namespace {

struct VolumeEntity {
  int tag = 0;
  std::int32_t label = 0;
  double box[6] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
};

struct TetRun {
  int entity;
  std::size_t first, count;
};

// Writes the values of one section either as text or as little-endian binary.
class MshOut {
 public:
  MshOut(io_detail::TextWriter& w, bool binary) : w_(w), binary_(binary) {}
  void text(std::string_view s) { w_.put(s); }
  void int32(std::int64_t v, char sep) {
    if (binary_) return raw(static_cast<std::uint32_t>(static_cast<std::int32_t>(v)), 4);
    w_.put_int(v);
    w_.put(sep);
  }
  void size(std::uint64_t v, char sep) {
    if (binary_) return raw(v, 8);
    w_.put_int(static_cast<std::int64_t>(v));
    w_.put(sep);
  }
  void real(double v, char sep) {
    if (binary_) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, 8);
      return raw(bits, 8);
    }
    w_.put_double(v);
    w_.put(sep);
  }
  // Binary payloads end with a newline before the $End line.
  void end(std::string_view end_line) {
    if (binary_) w_.put('\n');
    w_.put(end_line);
  }

 private:
  void raw(std::uint64_t v, int bytes) {
    char b[8];
    for (int i = 0; i < bytes; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xff);
    w_.put(std::string_view(b, static_cast<std::size_t>(bytes)));
  }
  io_detail::TextWriter& w_;
  bool binary_;
};

std::vector<VolumeEntity> volume_entities(const TetMeshData& mesh, std::vector<int>& entity_of_tet) {
  const std::size_t nt = mesh.num_tets();
  std::vector<VolumeEntity> entities;
  std::map<std::int32_t, int> by_label;
  entity_of_tet.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::int32_t label = mesh.tet_labels.size() == nt ? mesh.tet_labels[t] : 0;
    auto it = by_label.find(label);
    if (it == by_label.end()) {
      it = by_label.emplace(label, static_cast<int>(entities.size())).first;
      entities.push_back({static_cast<int>(entities.size()) + 1, label});
    }
    VolumeEntity& e = entities[static_cast<std::size_t>(it->second)];
    entity_of_tet[t] = e.tag;
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 3; ++k) {
        const double x = mesh.xyz[3 * std::size_t(mesh.tets[4 * t + c]) + k];
        e.box[k] = std::min(e.box[k], x);
        e.box[3 + k] = std::max(e.box[3 + k], x);
      }
  }
  if (entities.empty()) entities.push_back({1, 0});  // the nodes' entity, even without tets
  for (VolumeEntity& e : entities)
    if (e.box[0] > e.box[3]) std::fill(e.box, e.box + 6, 0.0);
  return entities;
}

void write_entities(MshOut& out, const std::vector<VolumeEntity>& entities) {
  out.text("$Entities\n");
  for (int d = 0; d < 3; ++d) out.size(0, ' ');
  out.size(entities.size(), '\n');
  for (const VolumeEntity& e : entities) {
    out.int32(e.tag, ' ');
    for (double b : e.box) out.real(b, ' ');
    out.size(e.label != 0 ? 1 : 0, ' ');
    if (e.label != 0) out.int32(e.label, ' ');
    out.size(0, '\n');  // no bounding surfaces
  }
  out.end("$EndEntities\n");
}

void write_nodes(MshOut& out, const TetMeshData& mesh) {
  const std::size_t nv = mesh.num_vertices();
  out.text("$Nodes\n");
  out.size(1, ' ');
  out.size(nv, ' ');
  out.size(nv == 0 ? 0 : 1, ' ');
  out.size(nv, '\n');
  out.int32(3, ' ');
  out.int32(1, ' ');
  out.int32(0, ' ');
  out.size(nv, '\n');
  for (std::size_t i = 0; i < nv; ++i) out.size(i + 1, '\n');
  for (std::size_t i = 0; i < nv; ++i) {
    out.real(mesh.xyz[3 * i], ' ');
    out.real(mesh.xyz[3 * i + 1], ' ');
    out.real(mesh.xyz[3 * i + 2], '\n');
  }
  out.end("$EndNodes\n");
}

void write_elements(MshOut& out, const TetMeshData& mesh, const std::vector<int>& entity_of_tet) {
  const std::size_t nt = mesh.num_tets();
  std::vector<TetRun> runs;
  for (std::size_t t = 0; t < nt; ++t) {
    if (runs.empty() || runs.back().entity != entity_of_tet[t])
      runs.push_back({entity_of_tet[t], t, 0});
    ++runs.back().count;
  }
  out.text("$Elements\n");
  out.size(runs.size(), ' ');
  out.size(nt, ' ');
  out.size(nt == 0 ? 0 : 1, ' ');
  out.size(nt, '\n');
  for (const TetRun& run : runs) {
    out.int32(3, ' ');
    out.int32(run.entity, ' ');
    out.int32(4, ' ');
    out.size(run.count, '\n');
    for (std::size_t t = run.first; t < run.first + run.count; ++t) {
      out.size(t + 1, ' ');
      for (int c = 0; c < 4; ++c) out.size(std::uint64_t(mesh.tets[4 * t + c]) + 1, c == 3 ? '\n' : ' ');
    }
  }
  out.end("$EndElements\n");
}

// Vertex labels as a one-component view; binary entries are a 4-byte node tag and a double.
void write_vertex_labels(MshOut& out, const TetMeshData& mesh) {
  const std::size_t nv = mesh.num_vertices();
  out.text("$NodeData\n1\n\"label\"\n1\n0\n3\n0\n1\n");
  out.text(std::to_string(nv) + "\n");
  for (std::size_t i = 0; i < nv; ++i) {
    out.int32(static_cast<std::int64_t>(i + 1), ' ');
    out.real(mesh.vertex_labels[i], '\n');
  }
  out.end("$EndNodeData\n");
}

}  // namespace

void write_msh(const std::string& path, const TetMeshData& mesh, MshEncoding encoding) {
  AtomicOutput file(path);
  write_msh(file, mesh, encoding);
  file.commit();
}

void write_msh(AtomicOutput& file, const TetMeshData& mesh, MshEncoding encoding) {
  const std::string& path = file.destination();
  io_detail::check_mesh_writable(mesh, path);
  if (mesh.num_vertices() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw Error(ErrorKind::Unsupported, path, 0, "cannot write: more vertices than $NodeData's 32-bit node tags can name");
  const bool binary = encoding == MshEncoding::Binary;
  std::vector<int> entity_of_tet;
  const std::vector<VolumeEntity> entities = volume_entities(mesh, entity_of_tet);
  const bool vertex_labels = std::any_of(mesh.vertex_labels.begin(), mesh.vertex_labels.end(), [](std::int32_t l) { return l != 0; });

  io_detail::TextWriter w(file);
  w.put(binary ? "$MeshFormat\n4.1 1 8\n" : "$MeshFormat\n4.1 0 8\n");
  if (binary) w.put(std::string_view("\x01\x00\x00\x00\n", 5));
  w.put("$EndMeshFormat\n");
  MshOut out(w, binary);
  write_entities(out, entities);
  write_nodes(out, mesh);
  write_elements(out, mesh, entity_of_tet);
  if (vertex_labels) write_vertex_labels(out, mesh);
  w.flush();
}

}  // namespace volmap
