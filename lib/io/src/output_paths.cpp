// Output-path identity (output_paths.hpp).
#include <volmap/io/output_paths.hpp>
#include <volmap/core/error.hpp>

#include <filesystem>
#include <sys/stat.h>

namespace volmap {

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  std::error_code ea, eb;
  const auto ca = std::filesystem::weakly_canonical(std::filesystem::absolute(a), ea);
  const auto cb = std::filesystem::weakly_canonical(std::filesystem::absolute(b), eb);
  return !ea && !eb && ca == cb;
}

void check_output_path(const NamedPath& output, const std::vector<NamedPath>& inputs,
                       const std::vector<NamedPath>& earlier_outputs) {
  for (const NamedPath& in : inputs)
    if (!in.path.empty() && same_file(output.path, in.path))
      throw Error(ErrorKind::BadInput, output.path, 0,
                  output.role + " is the same file as the " + in.role + " " + in.path +
                      ": refusing to overwrite an input");
  for (const NamedPath& other : earlier_outputs)
    if (!other.path.empty() && same_file(output.path, other.path))
      throw Error(ErrorKind::BadInput, output.path, 0,
                  output.role + " is the same file as the " + other.role + " " + other.path +
                      ": every output needs its own path");
}

}  // namespace volmap
