// InputMeshes: tet-mesh inputs read with their reader notes (see input_mesh.hpp).
#include "support/input_mesh.hpp"

#include <cstdio>

namespace volmap_tools {

void InputMeshes::keep(const std::string& path, volmap::TetMeshReadNotes notes) {
  if (notes.empty()) return;
  if (!(json_mode_ && *json_mode_))
    for (const std::string& m : notes.messages) std::fprintf(stderr, "%s: note: %s: %s\n", tool_.c_str(), path.c_str(), m.c_str());
  notes_.emplace_back(path, std::move(notes));
}

volmap::TetMeshData InputMeshes::read(const std::string& path) {
  volmap::TetMeshReadNotes notes;
  volmap::TetMeshData mesh = volmap::read_tet_mesh(path, notes);
  keep(path, std::move(notes));
  return mesh;
}

const volmap::TetMeshReadNotes* InputMeshes::notes(const std::string& path) const {
  for (const auto& [p, n] : notes_)
    if (p == path) return &n;
  return nullptr;
}

nlohmann::json InputMeshes::json() const {
  nlohmann::json all = nlohmann::json::object();
  for (const auto& [path, n] : notes_) {
    nlohmann::json ignored = nlohmann::json::object();
    for (const auto& e : n.ignored_elements) ignored[e.type] = e.count;
    all[path] = {{"format", n.format},
                 {"ignored_elements", ignored},
                 {"dropped_vertices", n.dropped_vertices},
                 {"renumbered", !n.source_vertex_ids.empty()},
                 {"messages", n.messages}};
  }
  return all;
}

}  // namespace volmap_tools
