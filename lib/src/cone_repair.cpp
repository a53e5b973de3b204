// cone_repair.cpp — B1 star-patch cone repair (docs/mapping.md §7); see volmap/cone_repair.hpp.
#include <volmap/cone_repair.hpp>

namespace volmap {

ConeRepairResult cone_repair(TetMeshData& source, std::vector<std::uint8_t>&, std::vector<double>&, const ConeRepairOptions&) {
  ConeRepairResult r;
  r.tets_before = r.tets_after = source.num_tets();
  return r;  // not implemented yet
}

bool strict_kernel_point(const std::vector<double>&, double*) { return false; }

}  // namespace volmap
