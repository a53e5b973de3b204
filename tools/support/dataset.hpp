// tools/support/dataset.hpp — the VOLMAP folder layout: cases are (group, mesh, domain) triples found as
//   <root>/G<k>/<name>.mesh  with  <root>/G<k>_<dom>/<name>_<dom>.txt
// for dom in cube, tet, pyr, octa, star, sphere, pc (the benchmark's suffixes). Discovery is
// deterministic: groups by number, meshes by name, domains in the suffix order above.
// Extension (volmap-dataset --mesh-per-domain): a mesh <root>/G<k>_<dom>/<name>_<dom>.mesh beside the
// map is that case's mesh instead of <root>/G<k>/<name>.mesh.
#pragma once

#include <string>
#include <vector>

namespace volmap {

struct BenchmarkCase {
  std::string group;   // "G1"
  std::string name;    // "bone"
  std::string domain;  // "cube"
  std::string mesh_path;
  std::string map_path;
  std::string id() const { return group + "/" + name + "_" + domain; }
};

// The VOLMAP domain suffixes in canonical order.
const std::vector<std::string>& volmap_domain_suffixes();

// All cases under root. Empty `groups`/`domains`/`meshes` mean all. Throws Error(Io) when root is
// not a folder, Error(BadInput) for an unknown domain name in `domains`.
std::vector<BenchmarkCase> discover_cases(const std::string& root, const std::vector<std::string>& groups = {},
                                          const std::vector<std::string>& domains = {},
                                          const std::vector<std::string>& meshes = {});

}  // namespace volmap
