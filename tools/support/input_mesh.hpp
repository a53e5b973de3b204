// Reading the tools' tet-mesh inputs through the format dispatcher while keeping what each reader
// noted (skipped Gmsh elements, dropped or renumbered nodes, how labels were chosen). Without --json
// the notes go to stderr as they arrive ("<tool>: note: <file>: <sentence>"); with --json they are
// reported under "input_notes" (one object per file that has notes).
#pragma once

#include <nlohmann/json.hpp>
#include <volmap/io/io.hpp>

#include <string>
#include <utility>
#include <vector>

namespace volmap_tools {

class InputMeshes {
 public:
  // `tool` prefixes the stderr lines; `json_mode` (read when a mesh is read) silences them.
  InputMeshes(std::string tool, const bool* json_mode) : tool_(std::move(tool)), json_mode_(json_mode) {}

  volmap::TetMeshData read(const std::string& path);
  // Keeps the notes of a mesh read elsewhere (printed now unless in JSON mode).
  void keep(const std::string& path, volmap::TetMeshReadNotes notes);
  const volmap::TetMeshReadNotes* notes(const std::string& path) const;
  bool empty() const { return notes_.empty(); }
  // {"<path>": {"format", "ignored_elements": {"<type>": count}, "dropped_vertices", "renumbered", "messages"}}
  nlohmann::json json() const;

 private:
  std::string tool_;
  const bool* json_mode_;
  std::vector<std::pair<std::string, volmap::TetMeshReadNotes>> notes_;  // files with notes only
};

}  // namespace volmap_tools
