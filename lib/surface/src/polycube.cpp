// Polycube domains (see polycube.hpp; volmap-reference.md §3.1). Everything before the Domain is
// built is decided on integers (cell coordinates): the boundary squares, their edges, the kernel box.
// The Domain then goes through finalize_domain like every other domain, which re-derives the faces
// from the geometry around the kernel point and checks exactly (orient3d) that every square's two
// triangles see the kernel point strictly on their inner side.
#include <volmap/surface/polycube.hpp>
#include <volmap/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

namespace volmap {
namespace {

constexpr long kMaxCellCoordinate = 1000000;

[[noreturn]] void refuse(const std::string& source, std::size_t line, const std::string& reason) {
  throw Error(ErrorKind::BadInput, source, line, "invalid polycube: " + reason);
}

std::string cell_text(const PolycubeCell& c) {
  return "(" + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + ")";
}

PolycubeCell offset(PolycubeCell c, int axis, int delta) {
  c[axis] += delta;
  return c;
}

// Index of every cell, refusing duplicates.
std::map<PolycubeCell, std::size_t> index_cells(const std::vector<PolycubeCell>& cells, const std::string& source) {
  std::map<PolycubeCell, std::size_t> index;
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (!index.emplace(cells[i], i).second) refuse(source, 0, "cell " + cell_text(cells[i]) + " is listed twice");
  return index;
}

// Breadth-first search over shared faces from the first cell.
void require_face_connected(const std::vector<PolycubeCell>& cells, const std::map<PolycubeCell, std::size_t>& index,
                            const std::string& source) {
  std::vector<char> seen(cells.size(), 0);
  std::vector<std::size_t> queue{0};
  seen[0] = 1;
  for (std::size_t q = 0; q < queue.size(); ++q)
    for (int axis = 0; axis < 3; ++axis)
      for (int delta : {-1, 1}) {
        const auto it = index.find(offset(cells[queue[q]], axis, delta));
        if (it != index.end() && !seen[it->second]) seen[it->second] = 1, queue.push_back(it->second);
      }
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (!seen[i])
      refuse(source, 0, "cell " + cell_text(cells[i]) + " shares no chain of faces with cell " + cell_text(cells[0]));
}

// The four corners of the face of cell c normal to `axis` on side `positive`, counter-clockwise seen
// from outside: with (u, w) the next axes in cyclic order, e_u × e_w = e_axis.
std::array<PolycubeCell, 4> square_corners(const PolycubeCell& c, int axis, bool positive) {
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  const PolycubeCell p0 = positive ? offset(c, axis, 1) : c;
  const PolycubeCell pu = offset(p0, u, 1), pw = offset(p0, w, 1), puw = offset(pu, w, 1);
  if (positive) return {p0, pu, puw, pw};
  return {p0, pw, puw, pu};
}

// Every grid edge must bound exactly two squares; four means two cells touch along the edge only.
void require_manifold_edges(const PolycubeSurface& s, const std::vector<PolycubeCell>& cells, const std::string& source) {
  std::map<std::pair<int, int>, std::vector<std::size_t>> squares_of_edge;
  for (std::size_t q = 0; q < s.squares.size(); ++q)
    for (int i = 0; i < 4; ++i) {
      const int a = s.squares[q][i], b = s.squares[q][(i + 1) % 4];
      squares_of_edge[{std::min(a, b), std::max(a, b)}].push_back(q);
    }
  for (const auto& [edge, squares] : squares_of_edge)
    if (squares.size() != 2)
      refuse(source, 0, "cells " + cell_text(cells[s.square_cell[squares.front()]]) + " and " +
                            cell_text(cells[s.square_cell[squares.back()]]) + " touch along an edge only (the grid edge " +
                            cell_text(s.corners[edge.first]) + "-" + cell_text(s.corners[edge.second]) +
                            " bounds " + std::to_string(squares.size()) + " squares)");
}

const std::vector<PolycubeCell>& builtin_cells(const std::string& name) {
  static const std::vector<PolycubeCell> cross7 = {{1, 1, 1}, {0, 1, 1}, {2, 1, 1}, {1, 0, 1},
                                                   {1, 2, 1}, {1, 1, 0}, {1, 1, 2}};
  static const std::vector<PolycubeCell> l3 = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  return name == "cross7" ? cross7 : l3;
}

// Probe fractions: the target seen from the kernel point, pushed along that ray onto the targets'
// bounding box (distinct nodes lie on distinct rays of a strictly star-shaped domain).
void set_radial_probes(Domain& d) {
  Point3 lo = d.targets[0], hi = d.targets[0];
  for (const auto& t : d.targets)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], t[k]), hi[k] = std::max(hi[k], t[k]);
  for (std::size_t n = 0; n < d.num_nodes(); ++n) {
    Point3 r;
    for (int k = 0; k < 3; ++k) r[k] = d.targets[n][k] - d.kernel[k];
    double s = HUGE_VAL;
    for (int k = 0; k < 3; ++k)
      if (r[k] != 0) s = std::min(s, ((r[k] > 0 ? hi[k] : lo[k]) - d.kernel[k]) / r[k]);
    for (int k = 0; k < 3; ++k) d.probe_fraction[n][k] = (d.kernel[k] + s * r[k] - lo[k]) / (hi[k] - lo[k]);
  }
}

}  // namespace

std::vector<std::array<int, 3>> PolycubeSurface::triangles() const {
  std::vector<std::array<int, 3>> t;
  t.reserve(2 * squares.size());
  for (const auto& q : squares) {
    t.push_back({q[0], q[1], q[2]});
    t.push_back({q[0], q[2], q[3]});
  }
  return t;
}

std::vector<PolycubeCell> parse_polycube_cells(const std::string& text, const std::string& source) {
  std::vector<PolycubeCell> cells;
  std::istringstream in(text);
  std::string line;
  std::size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string t; ls >> t;) tok.push_back(t);
    if (tok.empty()) continue;
    if (tok.size() != 3) refuse(source, lineno, "a cell line needs exactly 3 integers, got " + std::to_string(tok.size()));
    PolycubeCell c;
    for (int k = 0; k < 3; ++k) {
      char* end = nullptr;
      const long v = std::strtol(tok[k].c_str(), &end, 10);
      if (*end != '\0' || v < -kMaxCellCoordinate || v > kMaxCellCoordinate)
        refuse(source, lineno, "bad cell coordinate '" + tok[k] + "' (an integer of at most 10^6 in absolute value)");
      c[k] = static_cast<int>(v);
    }
    if (cells.size() == kMaxPolycubeCells)
      refuse(source, lineno, "more than " + std::to_string(kMaxPolycubeCells) + " cells");
    cells.push_back(c);
  }
  if (cells.empty()) refuse(source, 0, "no cells");
  return cells;
}

bool is_builtin_polycube_name(const std::string& name) { return name == "cross7" || name == "L3"; }

std::vector<PolycubeCell> polycube_cells(const std::string& name_or_path) {
  if (is_builtin_polycube_name(name_or_path)) return builtin_cells(name_or_path);
  std::ifstream f(name_or_path, std::ios::binary);
  if (!f) throw_io(name_or_path, "cannot open polycube cells file (or unknown built-in polycube; expected cross7 or L3)");
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_polycube_cells(ss.str(), name_or_path);
}

PolycubeSurface polycube_surface(const std::vector<PolycubeCell>& cells, const std::string& source) {
  if (cells.empty()) refuse(source, 0, "no cells");
  const auto index = index_cells(cells, source);
  require_face_connected(cells, index, source);
  PolycubeSurface s;
  std::vector<std::array<PolycubeCell, 4>> squares;
  for (std::size_t c = 0; c < cells.size(); ++c)
    for (int axis = 0; axis < 3; ++axis)
      for (bool positive : {false, true}) {
        if (index.count(offset(cells[c], axis, positive ? 1 : -1))) continue;
        squares.push_back(square_corners(cells[c], axis, positive));
        s.square_cell.push_back(c);
        s.square_axis.push_back(positive ? axis + 1 : -(axis + 1));
      }
  for (const auto& q : squares) s.corners.insert(s.corners.end(), q.begin(), q.end());
  std::sort(s.corners.begin(), s.corners.end());
  s.corners.erase(std::unique(s.corners.begin(), s.corners.end()), s.corners.end());
  for (const auto& q : squares) {
    std::array<int, 4> ids;
    for (int i = 0; i < 4; ++i)
      ids[i] = static_cast<int>(std::lower_bound(s.corners.begin(), s.corners.end(), q[i]) - s.corners.begin());
    s.squares.push_back(ids);
  }
  require_manifold_edges(s, cells, source);
  return s;
}

PolycubeKernel polycube_kernel(const std::vector<PolycubeCell>& cells, const PolycubeSurface& s,
                               const std::string& source) {
  // A square normal to axis a at coordinate c bounds the open half-space x_a < c (outward +a) or
  // x_a > c (outward -a): the constraints of different axes are independent, so the kernel is the
  // box (max of the lower bounds, min of the upper bounds) on every axis.
  PolycubeKernel k;
  std::array<std::size_t, 3> lo_square{}, hi_square{};
  std::array<bool, 3> have_lo{}, have_hi{};
  for (std::size_t q = 0; q < s.squares.size(); ++q) {
    const int axis = std::abs(s.square_axis[q]) - 1;
    const int c = s.corners[s.squares[q][0]][axis];
    if (s.square_axis[q] > 0 && (!have_hi[axis] || c < k.hi[axis])) k.hi[axis] = c, hi_square[axis] = q, have_hi[axis] = true;
    if (s.square_axis[q] < 0 && (!have_lo[axis] || c > k.lo[axis])) k.lo[axis] = c, lo_square[axis] = q, have_lo[axis] = true;
  }
  static const char* names = "xyz";
  for (int a = 0; a < 3; ++a)
    if (k.lo[a] >= k.hi[a]) {
      const std::string axis(1, names[a]);
      refuse(source, 0, "not strictly star-shaped: cell " + cell_text(cells[s.square_cell[lo_square[a]]]) +
                            " needs the kernel at " + axis + " > " + std::to_string(k.lo[a]) + " (its -" + axis +
                            " face) and cell " + cell_text(cells[s.square_cell[hi_square[a]]]) + " at " + axis +
                            " < " + std::to_string(k.hi[a]) + " (its +" + axis + " face)");
    }
  return k;
}

Domain polycube_domain(const std::vector<PolycubeCell>& cells, double cell_size, const std::string& source) {
  if (!(cell_size > 0) || !std::isfinite(cell_size)) refuse(source, 0, "the cell size must be positive and finite");
  const PolycubeSurface s = polycube_surface(cells, source);
  const PolycubeKernel kernel = polycube_kernel(cells, s, source);
  Domain d;
  d.kind = DomainKind::Polycube;
  d.name = "polycube";
  for (const auto& c : s.corners) d.targets.push_back({cell_size * c[0], cell_size * c[1], cell_size * c[2]});
  for (int k = 0; k < 3; ++k) d.kernel[k] = cell_size * (0.5 * kernel.lo[k] + 0.5 * kernel.hi[k]);
  std::vector<std::pair<int, int>> edges;
  for (const auto& q : s.squares)
    for (int i = 0; i < 4; ++i) edges.emplace_back(std::min(q[i], q[(i + 1) % 4]), std::max(q[i], q[(i + 1) % 4]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [a, b] : edges) d.arcs.push_back({a, b});
  d.probe_corners.assign(d.num_nodes(), {});
  d.probe_fraction.assign(d.num_nodes(), {0, 0, 0});
  set_radial_probes(d);
  finalize_domain(d, source);
  return d;
}

Domain polycube_domain(const std::string& name_or_path, double cell_size) {
  return polycube_domain(polycube_cells(name_or_path), cell_size,
                         is_builtin_polycube_name(name_or_path) ? "polycube " + name_or_path : name_or_path);
}

}  // namespace volmap
