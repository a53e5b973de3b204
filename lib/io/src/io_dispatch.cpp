// Format dispatch by file extension (.mesh, .vtk, .vtu; case-insensitive).
#include <volmap/io/io.hpp>

#include <algorithm>
#include <cctype>

namespace volmap {

TetMeshFormat tet_mesh_format(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return TetMeshFormat::Unknown;
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "mesh") return TetMeshFormat::Medit;
  if (ext == "vtk") return TetMeshFormat::Vtk;
  if (ext == "vtu") return TetMeshFormat::Vtu;
  return TetMeshFormat::Unknown;
}

void require_tet_mesh_extension(const std::string& path, bool for_writing) {
  const TetMeshFormat f = tet_mesh_format(path);
  const bool written = f == TetMeshFormat::Medit || f == TetMeshFormat::Vtk || f == TetMeshFormat::Vtu;
  if (f == TetMeshFormat::Unknown || (for_writing && !written))
    throw Error(ErrorKind::Unsupported, path, 0,
                std::string(for_writing ? "cannot write a tet mesh with this extension" : "unknown tet mesh extension") +
                    " (expected .mesh, .vtk or .vtu)");
}

TetMeshData read_tet_mesh(const std::string& path) {
  switch (tet_mesh_format(path)) {
    case TetMeshFormat::Medit: return read_medit(path);
    case TetMeshFormat::Vtk: return read_vtk(path);
    case TetMeshFormat::Vtu: return read_vtu(path);
    default: break;
  }
  throw Error(ErrorKind::Unsupported, path, 0, "unknown tet mesh extension (expected .mesh, .vtk or .vtu)");
}

void write_tet_mesh(const std::string& path, const TetMeshData& mesh) { write_tet_mesh(path, mesh, TetMeshWriteOptions{}); }

void write_tet_mesh(const std::string& path, const TetMeshData& mesh, const TetMeshWriteOptions& options) {
  require_tet_mesh_extension(path, /*for_writing=*/true);
  AtomicOutput out(path);
  write_tet_mesh(out, mesh, options);
  out.commit();
}

void write_tet_mesh(AtomicOutput& out, const TetMeshData& mesh, const TetMeshWriteOptions& options) {
  switch (tet_mesh_format(out.destination())) {
    case TetMeshFormat::Medit: write_medit(out, mesh); return;
    case TetMeshFormat::Vtk: write_vtk(out, mesh, options.vtk_binary); return;
    case TetMeshFormat::Vtu: write_vtu(out, mesh, {}, options.vtu_encoding); return;
    default: break;
  }
  require_tet_mesh_extension(out.destination(), /*for_writing=*/true);
}

}  // namespace volmap
