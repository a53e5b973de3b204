// volmap/surface/polycube.hpp — polycube domains: unions of unit grid cells (VOLMAP's G6 targets).
//
// Conventions (volmap-reference.md §3.1):
//  - A cell is an integer triple (i, j, k); with cell size S it is the box
//    [S·i, S·(i+1)] × [S·j, S·(j+1)] × [S·k, S·(k+1)].
//  - Cells file: one cell per line, three integers `i j k` (|i|, |j|, |k| <= 10^6), any whitespace,
//    `#` starts a comment, blank lines ignored. At most kMaxPolycubeCells cells, no duplicates.
//  - Built-in polycubes: `cross7` (the cell (1,1,1) and its 6 face neighbours) and `L3` (cells
//    (0,0,0), (1,0,0), (0,1,0)).
//  - Boundary surface: every cell face without a neighbour cell is one unit square, corners
//    counter-clockwise seen from outside; all corners are grid points, so the squares meet edge to
//    edge (no T-junctions). Each square is split into the triangles (q0,q1,q2), (q0,q2,q3).
//  - As a Domain (kind Polycube): nodes = square corners (sorted by grid coordinates), arcs = square
//    edges (from the smaller node id), faces = the squares; the kernel point is the centre of the
//    strict kernel (an open box, see polycube_kernel) and the map is judged about it.
//  - Refusals (Error(BadInput) naming the source and the offending cells): duplicate cells, a union
//    that is not face-connected, an edge shared by four squares (cells touching along an edge only),
//    and a union that is not strictly star-shaped.
#pragma once

#include <volmap/surface/domain.hpp>

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace volmap {

using PolycubeCell = std::array<int, 3>;

inline constexpr std::size_t kMaxPolycubeCells = 512;
inline constexpr double kDefaultPolycubeCellSize = 100;
// Domain names `polycube:<cells file or built-in name>` (domain_from_name_or_file, the tools).
inline constexpr std::string_view kPolycubePrefix = "polycube:";

struct PolycubeSurface {
  std::vector<PolycubeCell> corners;          // grid points, sorted
  std::vector<std::array<int, 4>> squares;    // corner ids, counter-clockwise seen from outside
  std::vector<std::size_t> square_cell;       // index of the cell each square bounds
  std::vector<int> square_axis;               // outward normal: +(axis+1) or -(axis+1), axis 0..2
  // The triangles of the squares: (q0,q1,q2), (q0,q2,q3) for every square, in square order.
  std::vector<std::array<int, 3>> triangles() const;
};

// Cells from a cells file's text (`source` names it in errors, with the line).
std::vector<PolycubeCell> parse_polycube_cells(const std::string& text, const std::string& source);
bool is_builtin_polycube_name(const std::string& name);
// `cross7`, `L3`, or a cells file path.
std::vector<PolycubeCell> polycube_cells(const std::string& name_or_path);

// The boundary squares of the union. Throws Error(BadInput) naming `source` for duplicate cells, a
// union that is not face-connected or an edge shared by four squares.
PolycubeSurface polycube_surface(const std::vector<PolycubeCell>& cells, const std::string& source);

// The strict kernel of the union, in cell units: every boundary square has a plane x_a = c with an
// inner side; the kernel is the intersection of those open half-spaces, an open axis-aligned box
// (lo, hi) per axis. Throws Error(BadInput) naming `source` and the two cells whose squares leave no
// room on some axis when the box is empty (the union is not strictly star-shaped).
struct PolycubeKernel {
  std::array<int, 3> lo{}, hi{};
};
PolycubeKernel polycube_kernel(const std::vector<PolycubeCell>& cells, const PolycubeSurface& surface,
                               const std::string& source);

// The polycube as a surface-mapper domain (cell size `cell_size` > 0): nodes, arcs, faces and
// rotations as for the other domains (finalize_domain, which also checks exactly that every
// triangle sees the kernel point strictly on its inner side), node probes = the targets projected
// from the kernel point onto the targets' bounding box, as bbox fractions.
Domain polycube_domain(const std::vector<PolycubeCell>& cells, double cell_size, const std::string& source);
// The same from a built-in name or a cells file path.
Domain polycube_domain(const std::string& name_or_path, double cell_size = kDefaultPolycubeCellSize);

}  // namespace volmap
