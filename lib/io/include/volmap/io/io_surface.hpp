// volmap/io/io_surface.hpp — triangle surfaces (OBJ, OFF, STL ascii/binary, PLY ascii/binary) as flat
// arrays. Vertex ids 0-based in file order; triangles keep the file's orientation. Polygons with
// n > 3 corners are fan-triangulated from their first corner: (c0,c1,c2), (c0,c2,c3), ...
// (deterministic). Coordinates are read in double precision (correctly rounded from the text).
// Every format is parsed here (OpenMesh 9's OFF/OBJ readers round coordinates to float even into a
// Vec3d mesh, its PLY reader has no triangle strips and its STL reader merges NaN corners and
// accepts a binary STL whose triangle count disagrees with its size): exact file vertex lists,
// non-manifold input kept as is. STL (float by format): binary iff the size is 84 + 50 * count,
// else ASCII (`solid`); corners welded by exact coordinates in order of first appearance; non-finite
// corners refused. A leading UTF-8 byte-order mark is ignored in the text formats.
#pragma once

#include <volmap/io/atomic_file.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

struct SurfaceData {
  std::vector<double> xyz;          // 3 * num_vertices
  std::vector<std::uint32_t> tris;  // 3 * num_triangles, 0-based
  std::size_t num_vertices() const { return xyz.size() / 3; }
  std::size_t num_triangles() const { return tris.size() / 3; }
};

// Throws Error(Io) when the file cannot be opened, Error(Unsupported) for an unknown extension,
// Error(BadInput) when it cannot be parsed, it has no faces, or a coordinate is not finite.
SurfaceData read_surface(const std::string& path);
// Format by extension (.obj, .off, .stl (binary), .ply (binary)); atomic. Throws Error(BadInput) for
// ids out of range or non-finite coordinates.
void write_surface(const std::string& path, const SurfaceData& surface);
// Same into a prepared output (format by out.destination()'s extension; no commit).
void write_surface(AtomicOutput& out, const SurfaceData& surface);

}  // namespace volmap
