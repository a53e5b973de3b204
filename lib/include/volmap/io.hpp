// volmap/io.hpp — reading and writing tet meshes, boundary maps and rationals files.
// All readers throw volmap::Error with file, line and reason; they validate declared sizes before
// allocating. All writers are atomic (temp file + rename) and write doubles with %.17g so they
// round-trip bit-exactly. Vertex ids in files: Medit 1-based, maps/VTK 0-based; in memory 0-based.
#pragma once

#include <volmap/error.hpp>
#include <volmap/mesh_data.hpp>
#include <volmap/predicates.hpp>

#include <string>
#include <vector>

namespace volmap {

// Medit .mesh (keywords/counts on any lines, # comments, unknown sections skipped, labels kept).
TetMeshData read_medit(const std::string& path);
void write_medit(const std::string& path, const TetMeshData& mesh);

// Legacy VTK unstructured grid (ASCII or BINARY, 4.x and 5.1 layouts), tets only. Cells of type
// 10 are kept in order, lower-dimensional cells (types 1-9) skipped, other types rejected
// (Unsupported). Without CELL_TYPES every cell must have 4 ids. Writer: 4.x layout, double points,
// labels as int SCALARS "label" in CELL_DATA/POINT_DATA when not all zero (read back by read_vtk).
TetMeshData read_vtk(const std::string& path);
void write_vtk(const std::string& path, const TetMeshData& mesh, bool binary = false);

// VTK XML .vtu (ascii, inline base64, appended raw); optional per-cell double arrays on write.
struct CellDataArray {
  std::string name;
  std::vector<double> values;  // one per tet
};
TetMeshData read_vtu(const std::string& path);
// Same, also returning the CellData arrays with one component (except "label") as doubles.
TetMeshData read_vtu(const std::string& path, std::vector<CellDataArray>& cell_data);
// Writes appended raw binary (compact, exact). Medit labels go to Int32 "label" arrays when not all 0.
void write_vtu(const std::string& path, const TetMeshData& mesh, const std::vector<CellDataArray>& cell_data = {});
enum class VtuEncoding { AppendedRaw /* little-endian raw, UInt64 headers */, Ascii /* shortest round-trip doubles */ };
void write_vtu(const std::string& path, const TetMeshData& mesh, const std::vector<CellDataArray>& cell_data,
               VtuEncoding encoding);

// By extension (.mesh, .vtk, .vtu, case-insensitive); throws Error(Unsupported) for anything else.
enum class TetMeshFormat { Medit, Vtk, Vtu, Unknown };
TetMeshFormat tet_mesh_format(const std::string& path);
TetMeshData read_tet_mesh(const std::string& path);
void write_tet_mesh(const std::string& path, const TetMeshData& mesh);  // .vtk ascii, .vtu appended raw
struct TetMeshWriteOptions {
  bool vtk_binary = false;
  VtuEncoding vtu_encoding = VtuEncoding::AppendedRaw;
};
void write_tet_mesh(const std::string& path, const TetMeshData& mesh, const TetMeshWriteOptions& options);

// Boundary map `vid x y z` (0-based, any whitespace). Rejects duplicates and malformed lines.
BoundaryMap read_boundary_map(const std::string& path);
enum class MapPrecision { Full /* %.17g, sorted by vid */, Volmap6 /* %lf, the dataset's 6 decimals */ };
void write_boundary_map(const std::string& path, const BoundaryMap& map, MapPrecision precision = MapPrecision::Full);
// Throws Error(BadInput) naming `map_path` unless the map's vids are exactly the mesh's boundary
// vertices (each once; no interior or out-of-range ids).
void validate_boundary_map(const BoundaryMap& map, const TetMeshData& mesh, const std::string& map_path);

// Rationals file: one `num/den` (or `num`) per line, 3 per vertex in mesh order, canonicalised.
std::vector<Rational> read_rationals(const std::string& path, std::size_t expected_vertices);
void write_rationals(const std::string& path, const std::vector<Rational>& xyz);

}  // namespace volmap
