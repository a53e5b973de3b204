// VOLMAP layout discovery (see dataset.hpp for the layout).
#include "support/dataset.hpp"
#include <volmap/core/error.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace volmap {
namespace fs = std::filesystem;

const std::vector<std::string>& volmap_domain_suffixes() {
  static const std::vector<std::string> kSuffixes = {"cube", "tet", "pyr", "octa", "star", "sphere", "pc"};
  return kSuffixes;
}

namespace {
// "G12" -> 12, anything else -> -1.
int group_number(const std::string& name) {
  if (name.size() < 2 || name[0] != 'G') return -1;
  for (std::size_t i = 1; i < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return -1;
  return std::atoi(name.c_str() + 1);
}
bool contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}
}  // namespace

std::vector<BenchmarkCase> discover_cases(const std::string& root, const std::vector<std::string>& groups,
                                          const std::vector<std::string>& domains,
                                          const std::vector<std::string>& meshes) {
  std::error_code ec;
  if (!fs::is_directory(root, ec)) throw_io(root, "dataset folder does not exist");
  for (const auto& d : domains)
    if (!contains(volmap_domain_suffixes(), d))
      throw Error(ErrorKind::BadInput, "unknown domain '" + d + "' (expected cube, tet, pyr, octa, star, sphere or pc)");

  std::vector<std::pair<int, std::string>> group_dirs;
  for (const auto& entry : fs::directory_iterator(root, ec)) {
    const std::string name = entry.path().filename().string();
    const int number = group_number(name);
    if (number < 0 || !entry.is_directory()) continue;
    if (!groups.empty() && !contains(groups, name)) continue;
    group_dirs.emplace_back(number, name);
  }
  std::sort(group_dirs.begin(), group_dirs.end());

  std::vector<BenchmarkCase> cases;
  for (const auto& [number, group] : group_dirs) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(fs::path(root) / group, ec))
      if (entry.is_regular_file() && entry.path().extension() == ".mesh" &&
          (meshes.empty() || contains(meshes, entry.path().stem().string())))
        names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    for (const auto& mesh : names)
      for (const auto& dom : volmap_domain_suffixes()) {
        if (!domains.empty() && !contains(domains, dom)) continue;
        const fs::path map = fs::path(root) / (group + "_" + dom) / (mesh + "_" + dom + ".txt");
        if (!fs::is_regular_file(map, ec)) continue;
        const fs::path own = fs::path(root) / (group + "_" + dom) / (mesh + "_" + dom + ".mesh");
        const fs::path shared = fs::path(root) / group / (mesh + ".mesh");
        cases.push_back({group, mesh, dom, (fs::is_regular_file(own, ec) ? own : shared).string(), map.string()});
      }
  }
  return cases;
}

}  // namespace volmap
