// TetGen tetrahedralisation of a closed surface read with OpenMesh (see tetrahedralize.hpp).
// TetGen runs in a forked child (tetgen_child.hpp).
#include <volmap/core/error.hpp>
#include <volmap/io/io_surface.hpp>
#include <volmap/surface/surface_map_check.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>

#include "tetgen_child.hpp"

#include <tetgen.h>

#include <algorithm>
#include <cstring>
#include <sstream>
#include <vector>

namespace volmap {

TriangleSurface read_triangle_surface(const std::string& path) {
  // io_surface parses OBJ/OFF/PLY (incl. tristrips) in double precision and STL through OpenMesh.
  SurfaceData d = read_surface(path);
  TriangleSurface s;
  s.xyz = std::move(d.xyz);
  s.tris = std::move(d.tris);
  return s;
}

std::string surface_topology_problem(const TriangleSurface& s) {
  const std::size_t nv = s.num_vertices(), nt = s.num_triangles();
  if (s.rejected_faces)
    return "the surface is not manifold (" + std::to_string(s.rejected_faces) +
           " faces have a complex edge or vertex and could not be added)";
  // Directed edges: each undirected edge must appear exactly once in each direction (closed,
  // edge-manifold, consistently oriented).
  std::vector<std::uint64_t> directed;
  directed.reserve(3 * nt);
  std::vector<std::uint32_t> valence(nv, 0);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = s.tris[3 * t + k], b = s.tris[3 * t + (k + 1) % 3];
      if (a >= nv || b >= nv) return "a triangle references a missing vertex";
      if (a == b) return "a triangle has a repeated vertex";
      directed.push_back((static_cast<std::uint64_t>(a) << 32) | b);
      ++valence[a];
    }
  std::sort(directed.begin(), directed.end());
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end())
    return "the surface is not manifold or not consistently oriented (an edge is used twice in the same direction)";
  for (auto e : directed) {
    const std::uint64_t rev = ((e & 0xffffffffu) << 32) | (e >> 32);
    if (!std::binary_search(directed.begin(), directed.end(), rev))
      return "the surface is not closed (it has border edges)";
  }
  // Vertex manifoldness: the triangles around every vertex form one fan (one cycle).
  std::vector<std::uint32_t> offset(nv + 1, 0);
  for (auto v : valence) (void)v;
  for (std::size_t v = 0; v < nv; ++v) offset[v + 1] = offset[v] + valence[v];
  std::vector<std::uint32_t> next_of(offset[nv]), from_of(offset[nv]);
  std::vector<std::uint32_t> fill(offset.begin(), offset.end() - 1);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = s.tris[3 * t + k];
      from_of[fill[v]] = s.tris[3 * t + (k + 1) % 3];
      next_of[fill[v]++] = s.tris[3 * t + (k + 2) % 3];
    }
  std::size_t used_vertices = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const std::uint32_t b = offset[v], e = offset[v + 1];
    if (b == e) continue;
    ++used_vertices;
    std::uint32_t x = from_of[b];
    std::uint32_t steps = 0;
    do {
      std::uint32_t k = b;
      while (k < e && from_of[k] != x) ++k;
      if (k == e) return "the surface is not manifold at vertex " + std::to_string(v);
      x = next_of[k];
      ++steps;
    } while (x != from_of[b] && steps <= e - b);
    if (steps != e - b) return "the surface is not manifold at vertex " + std::to_string(v) + " (pinched)";
  }
  // Components (union-find over triangle vertices).
  std::vector<std::uint32_t> parent(nv);
  for (std::uint32_t v = 0; v < nv; ++v) parent[v] = v;
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 1; k < 3; ++k) parent[find(s.tris[3 * t + k])] = find(s.tris[3 * t]);
  std::size_t components = 0;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (offset[v + 1] > offset[v] && find(v) == v) ++components;
  if (components != 1) return "the surface has " + std::to_string(components) + " connected components (expected 1)";
  const long long chi = static_cast<long long>(used_vertices) - static_cast<long long>(directed.size() / 2) +
                        static_cast<long long>(nt);
  if (chi != 2) return "the surface has genus " + std::to_string((2 - chi) / 2) + " (expected a genus-0 sphere)";
  return "";
}

TetMeshData tetrahedralize_surface(const TriangleSurface& s, const TetrahedralizeOptions& options) {
  const std::string problem = surface_topology_problem(s);
  if (!problem.empty()) throw Error(ErrorKind::BadInput, problem);
  if (!options.coarse && !(options.quality >= 1.0)) throw Error(ErrorKind::BadInput, "quality bound must be >= 1");
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(s.num_vertices());
  in.pointlist = new REAL[s.xyz.size()];
  std::copy(s.xyz.begin(), s.xyz.end(), in.pointlist);
  in.numberoffacets = static_cast<int>(s.num_triangles());
  in.facetlist = new tetgenio::facet[in.numberoffacets];
  for (int f = 0; f < in.numberoffacets; ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) facet.polygonlist[0].vertexlist[k] = static_cast<int>(s.tris[3 * f + k]);
  }
  std::ostringstream sw;
  sw.precision(17);
  sw << "p";
  if (!options.coarse) sw << "q" << options.quality;
  sw << "YQz";
  if (options.max_volume > 0) sw << "a" << options.max_volume;
  return run_tetgen_in_child(sw.str(), in, options.time_limit_seconds);
}

}  // namespace volmap
