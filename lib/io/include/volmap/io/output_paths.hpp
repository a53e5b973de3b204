// volmap/io/output_paths.hpp — an output must never be one of the run's inputs or another output.
// Two paths name the same file when both exist and share device and inode (hard links, symlinks,
// "./a" vs "a"), or when their lexically normalised absolute forms (symlinks in existing parents
// resolved) are equal — which also catches two outputs that do not exist yet.
#pragma once

#include <string>
#include <vector>

namespace volmap {

struct NamedPath {
  std::string path;
  std::string role;  // how messages call it: "input mesh", "--refined", ...
};

bool same_file(const std::string& a, const std::string& b);

// Throws Error(BadInput) naming `output.path` when it is the same file as one of `inputs` or of
// `earlier_outputs` ("is the same file as the input mesh in.mesh: refusing to overwrite an input").
void check_output_path(const NamedPath& output, const std::vector<NamedPath>& inputs,
                       const std::vector<NamedPath>& earlier_outputs);

}  // namespace volmap
