// orientation.cpp — orientation class and sentence from exact tet sign counts (see orientation.hpp).
#include <volmap/check/orientation.hpp>

#include <volmap/core/count_text.hpp>

namespace volmap {

const char* to_string(OrientationClass c) {
  switch (c) {
    case OrientationClass::AllPositive: return "positive";
    case OrientationClass::CoherentlyOpposite: return "coherently_opposite";
    case OrientationClass::Mixed: return "mixed";
    case OrientationClass::Empty: return "empty";
  }
  return "?";
}

OrientationClass classify_orientation(const TetSignCounts& s) {
  if (s.positive > 0 && s.negative > 0) return OrientationClass::Mixed;
  if (s.negative > 0) return OrientationClass::CoherentlyOpposite;
  if (s.positive > 0) return OrientationClass::AllPositive;
  return OrientationClass::Empty;
}

std::string describe_orientation(const TetSignCounts& s, const std::string& fix) {
  const std::size_t total = s.positive + s.negative + s.zero;
  const std::string zeros = s.zero == 0 ? "" : " and " + grouped(s.zero) + " have zero volume";
  // "all 6,059 tets are" when every tet is in the class, else "6,050 of 6,059 tets are".
  auto subject = [&](std::size_t n) {
    if (total == 1) return std::string("the one tet is");
    return (n == total ? "all " + count_of(total, "tet") : grouped(n) + " of " + count_of(total, "tet")) + " are";
  };
  switch (classify_orientation(s)) {
    case OrientationClass::AllPositive:
      return subject(s.positive) + " in the VOLMAP orientation convention (orient3d > 0)" + zeros;
    case OrientationClass::CoherentlyOpposite:
      return subject(s.negative) + " in the opposite orientation convention (orient3d < 0, as Gmsh and OpenVolumeMesh order them)" +
             zeros + "; " + fix + (total == 1 ? " flips it" : " flips them");
    case OrientationClass::Mixed:
      return "orientation is mixed: " + grouped(s.positive) + " of " + count_of(total, "tet") +
             " are in the VOLMAP convention (orient3d > 0) and " + grouped(s.negative) +
             " in the opposite one" + zeros + "; no global flip fixes that";
    case OrientationClass::Empty:
      if (total == 0) return "the mesh has no tets";
      return total == 1 ? "the one tet has zero volume" : "all " + count_of(total, "tet") + " have zero volume";
  }
  return "";
}

}  // namespace volmap
