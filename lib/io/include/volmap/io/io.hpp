// volmap/io/io.hpp — reading and writing tet meshes, boundary maps and rationals files.
// All readers throw volmap::Error with file, line and reason (BadInput for malformed content, Io for
// a missing/unreadable path or a directory, Unsupported for valid input outside what we handle);
// they validate declared sizes against the file size before allocating, refuse binary data (NUL
// bytes) in text formats and streams longer than 1 GiB as the bytes arrive, and ignore a leading
// UTF-8 byte-order mark. All writers are atomic (temp file + rename; nothing appears on error; the
// AtomicOutput overloads write into a prepared output, e.g. of an OutputTransaction, without
// committing) and print doubles in shortest round-trip form (std::to_chars), so every double read
// back is bit-identical.
// Vertex ids in files: Medit 1-based, maps/VTK/VTU 0-based; in memory 0-based. Tet order and each
// tet's vertex order are kept exactly as in the file (Gmsh and OpenVolumeMesh files come out in the
// opposite orientation convention; the checks say so and `volmap-tetmesh-check --fix` flips them).
#pragma once

#include <volmap/core/error.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/io/atomic_file.hpp>
#include <volmap/io/read_notes.hpp>
#include <volmap/predicates_rational.hpp>

#include <string>
#include <vector>

namespace volmap {

// Medit .mesh (keywords/counts on any lines, # comments, CRLF, optional End, MeshVersionFormatted
// 1-3, Triangles/Edges/Corners/... skipped by count, unknown sections skipped up to the next
// keyword, labels kept). Rejects ids outside [1,nv], Dimension != 3, truncated blocks, NaN/Inf,
// malformed or overlong numbers, counts that cannot fit in the file; Hexahedra/Prisms/Pyramids with
// a non-zero count are Unsupported.
TetMeshData read_medit(const std::string& path);
void write_medit(const std::string& path, const TetMeshData& mesh);
void write_medit(AtomicOutput& out, const TetMeshData& mesh);

// Legacy VTK unstructured grid (ASCII or BINARY big-endian, 4.x and 5.1 layouts), tets only. Cells of
// type 10 are kept in order, lower-dimensional cells (types 1-9) skipped, other types rejected
// (Unsupported). Without CELL_TYPES every cell must have 4 ids. FIELD/CELL_DATA/POINT_DATA/METADATA
// are skipped except int SCALARS "label". Writer: 4.x layout, double points, labels as int SCALARS
// "label" in CELL_DATA/POINT_DATA when not all zero (read back by read_vtk).
TetMeshData read_vtk(const std::string& path);
void write_vtk(const std::string& path, const TetMeshData& mesh, bool binary = false);
void write_vtk(AtomicOutput& out, const TetMeshData& mesh, bool binary = false);

// VTK XML .vtu (read: ascii, inline base64, appended raw/base64, any byte order; compressed files
// are Unsupported). Write: Float64 points, Int64 connectivity/offsets, UInt8 types, Int32 "label"
// point/cell arrays when labels are not all zero, optional per-cell Float64 arrays.
struct CellDataArray {
  std::string name;
  std::vector<double> values;  // one per tet
};
TetMeshData read_vtu(const std::string& path);
// Same, also returning the one-component CellData arrays other than "label", as doubles.
TetMeshData read_vtu(const std::string& path, std::vector<CellDataArray>& cell_data);
// Writes appended raw binary (compact, exact).
void write_vtu(const std::string& path, const TetMeshData& mesh, const std::vector<CellDataArray>& cell_data = {});
enum class VtuEncoding { AppendedRaw /* little-endian raw, UInt64 headers */, Ascii /* shortest round-trip doubles */ };
void write_vtu(const std::string& path, const TetMeshData& mesh, const std::vector<CellDataArray>& cell_data,
               VtuEncoding encoding);
void write_vtu(AtomicOutput& out, const TetMeshData& mesh, const std::vector<CellDataArray>& cell_data,
               VtuEncoding encoding = VtuEncoding::AppendedRaw);

// Gmsh .msh, versions 2.2 (also 2.0/2.1) and 4.1, ASCII or binary (either byte order, as the file's
// endianness marker says; 4.1's data-size 4 or 8). Linear tetrahedra (type 4) are read in file order;
// points, lines, triangles and quadrangles of any order are skipped and counted in `notes`; any other
// 3D element (hexahedra, prisms, pyramids, curved tets) is Unsupported. Nodes are renumbered 0..n-1 in
// file order, nodes used by no tet are dropped (both noted). Tet labels: the physical tag (4.1: the
// first physical tag of the tet's volume entity; 0 when it has none); a file without any physical
// tag on its tets but with several volume entities gets the entity tags instead. Vertex labels come
// from a one-component $NodeData named "label" (what write_msh stores), else 0.
TetMeshData read_msh(const std::string& path, TetMeshReadNotes* notes = nullptr);
// Writes MSH 4.1 (ASCII, or little-endian binary with data-size 8): one volume entity per distinct tet
// label (physical tag = the label when non-zero), one element block per run of equal labels, node
// tags 1..n, element tags 1..m, vertex labels as $NodeData "label" when not all zero. Tets are
// written in our vertex order, so Gmsh sees VOLMAP-positive tets as negative (see io.hpp header).
enum class MshEncoding { Ascii, Binary };
void write_msh(const std::string& path, const TetMeshData& mesh, MshEncoding encoding = MshEncoding::Ascii);
void write_msh(AtomicOutput& out, const TetMeshData& mesh, MshEncoding encoding = MshEncoding::Ascii);

// OpenVolumeMesh text format (`OVM ASCII`: Vertices, Edges, Faces as half-edge ids 2e/2e+1,
// Polyhedra as half-face ids 2f/2f+1; property sections after Polyhedra are ignored). Every cell
// must be a tetrahedron: 4 triangular half-faces forming a closed, consistently oriented surface;
// other cells are Unsupported, naming the cell. Tet vertex order is OpenVolumeMesh's: the vertices
// of the cell's first half-face, then the remaining vertex; half-face normals point into the cell,
// so these tets have orient3d < 0. Vertices keep their file index (0-based, as boundary maps use).
TetMeshData read_ovm(const std::string& path);

// By extension (.mesh, .vtk, .vtu, .msh, .ovm; case-insensitive); throws Error(Unsupported) for
// anything else. .ovm is read-only.
enum class TetMeshFormat { Medit, Vtk, Vtu, Msh, Ovm, Unknown };
TetMeshFormat tet_mesh_format(const std::string& path);
// Throws Error(Unsupported) naming `path` unless its extension names a format read_tet_mesh reads
// (or, `for_writing`, one write_tet_mesh writes: .mesh, .vtk, .vtu, .msh). Tools check it before any work.
void require_tet_mesh_extension(const std::string& path, bool for_writing = false);
const char* tet_mesh_format_name(TetMeshFormat format);  // "mesh", "vtk", "vtu", "msh", "ovm", "unknown"
TetMeshData read_tet_mesh(const std::string& path);
// Same, also returning what the reader skipped or renumbered (notes.format is always set).
TetMeshData read_tet_mesh(const std::string& path, TetMeshReadNotes& notes);
void write_tet_mesh(const std::string& path, const TetMeshData& mesh);  // .vtk ascii, .vtu appended raw
struct TetMeshWriteOptions {
  bool vtk_binary = false;
  VtuEncoding vtu_encoding = VtuEncoding::AppendedRaw;
  MshEncoding msh_encoding = MshEncoding::Ascii;
};
void write_tet_mesh(const std::string& path, const TetMeshData& mesh, const TetMeshWriteOptions& options);
// Into a prepared output, by the extension of out.destination() (no commit).
void write_tet_mesh(AtomicOutput& out, const TetMeshData& mesh, const TetMeshWriteOptions& options = {});

// Boundary map `vid x y z` (0-based, any whitespace, blank lines ignored), kept in file order with
// each entry's line in BoundaryMap::source_lines. Rejects duplicates (naming the later line),
// negative or non-integer vids, non-finite or malformed coordinates, lines without exactly 4 values.
BoundaryMap read_boundary_map(const std::string& path);
enum class MapPrecision { Full /* shortest round-trip, exact */, Volmap6 /* %f: the dataset's 6 decimals */ };
// Sorted by vid.
void write_boundary_map(const std::string& path, const BoundaryMap& map, MapPrecision precision = MapPrecision::Full);
void write_boundary_map(AtomicOutput& out, const BoundaryMap& map, MapPrecision precision = MapPrecision::Full);
// Throws Error(BadInput) naming `map_path` and the offending entry's line unless the map's vids are
// exactly the mesh's boundary vertices (boundary_vertex_ids): each once, no interior or
// out-of-range ids; a missing boundary vertex is named (line 0).
void validate_boundary_map(const BoundaryMap& map, const TetMeshData& mesh, const std::string& map_path);

// Rationals file: one `num/den` (or `num`) token per line, 3 per vertex in mesh order, read exactly
// and canonicalised (2/4 -> 1/2). Rejects den = 0, malformed tokens and a count != 3*expected_vertices.
// Written as mpq_out_str does: `num/den`, or `num` when den = 1.
std::vector<Rational> read_rationals(const std::string& path, std::size_t expected_vertices);

// A whole text file, vetted like the readers above do (NUL bytes refused, streams capped at 1 GiB,
// lines longer than `max_line_bytes` refused when it is nonzero, a UTF-8 byte-order mark dropped).
// For text formats parsed elsewhere (custom domains, results logs).
std::string read_text_file(const std::string& path, std::size_t max_line_bytes = 0);
void write_rationals(const std::string& path, const std::vector<Rational>& xyz);
void write_rationals(AtomicOutput& out, const std::vector<Rational>& xyz);

}  // namespace volmap
