// Format dispatch by file extension (.mesh, .vtk, .vtu, .msh, .ovm; case-insensitive).
#include <volmap/io/io.hpp>

#include <algorithm>
#include <cctype>

namespace volmap {
namespace {
const char* const kKnownReadExtensions = "expected .mesh, .vtk, .vtu, .msh or .ovm";
}  // namespace

TetMeshFormat tet_mesh_format(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return TetMeshFormat::Unknown;
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "mesh") return TetMeshFormat::Medit;
  if (ext == "vtk") return TetMeshFormat::Vtk;
  if (ext == "vtu") return TetMeshFormat::Vtu;
  if (ext == "msh") return TetMeshFormat::Msh;
  if (ext == "ovm") return TetMeshFormat::Ovm;
  return TetMeshFormat::Unknown;
}

void require_tet_mesh_extension(const std::string& path, bool for_writing) {
  const TetMeshFormat f = tet_mesh_format(path);
  if (f == TetMeshFormat::Unknown)
    throw Error(ErrorKind::Unsupported, path, 0, std::string("unknown tet mesh extension (") + kKnownReadExtensions + ")");
  if (for_writing && f == TetMeshFormat::Ovm)
    throw Error(ErrorKind::Unsupported, path, 0, "cannot write .ovm (read-only format; write .mesh, .vtk, .vtu or .msh)");
}

const char* tet_mesh_format_name(TetMeshFormat format) {
  switch (format) {
    case TetMeshFormat::Medit: return "mesh";
    case TetMeshFormat::Vtk: return "vtk";
    case TetMeshFormat::Vtu: return "vtu";
    case TetMeshFormat::Msh: return "msh";
    case TetMeshFormat::Ovm: return "ovm";
    default: return "unknown";
  }
}

TetMeshData read_tet_mesh(const std::string& path) {
  TetMeshReadNotes notes;
  return read_tet_mesh(path, notes);
}

TetMeshData read_tet_mesh(const std::string& path, TetMeshReadNotes& notes) {
  notes = TetMeshReadNotes{};
  const TetMeshFormat format = tet_mesh_format(path);
  notes.format = tet_mesh_format_name(format);
  switch (format) {
    case TetMeshFormat::Medit: return read_medit(path);
    case TetMeshFormat::Vtk: return read_vtk(path);
    case TetMeshFormat::Vtu: return read_vtu(path);
    case TetMeshFormat::Msh: return read_msh(path, &notes);
    case TetMeshFormat::Ovm: return read_ovm(path);
    default: break;
  }
  throw Error(ErrorKind::Unsupported, path, 0, std::string("unknown tet mesh extension (") + kKnownReadExtensions + ")");
}

void write_tet_mesh(const std::string& path, const TetMeshData& mesh) { write_tet_mesh(path, mesh, TetMeshWriteOptions{}); }

void write_tet_mesh(const std::string& path, const TetMeshData& mesh, const TetMeshWriteOptions& options) {
  require_tet_mesh_extension(path, /*for_writing=*/true);
  AtomicOutput out(path);
  write_tet_mesh(out, mesh, options);
  out.commit();
}

void write_tet_mesh(AtomicOutput& out, const TetMeshData& mesh, const TetMeshWriteOptions& options) {
  require_tet_mesh_extension(out.destination(), /*for_writing=*/true);
  switch (tet_mesh_format(out.destination())) {
    case TetMeshFormat::Medit: write_medit(out, mesh); return;
    case TetMeshFormat::Vtk: write_vtk(out, mesh, options.vtk_binary); return;
    case TetMeshFormat::Vtu: write_vtu(out, mesh, {}, options.vtu_encoding); return;
    case TetMeshFormat::Msh: write_msh(out, mesh, options.msh_encoding); return;
    default: break;
  }
}

}  // namespace volmap
