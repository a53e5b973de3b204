// TetGen tetrahedralisation of a closed surface read with OpenMesh (see tetrahedralize.hpp).
// TetGen is called through its library interface (TETLIBRARY: errors are thrown as ints, decoded
// below) in a forked child with stdout on /dev/null (see tetrahedralize_surface for why).
#include <volmap/core/error.hpp>
#include <volmap/io/io_surface.hpp>
#include <volmap/predicates.hpp>
#include <volmap/surface/surface_map_check.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>

#include <tetgen.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <vector>

namespace volmap {
namespace {



std::string tetgen_reason(int code) {
  switch (code) {
    case 1: return "TetGen ran out of memory";
    case 2: return "TetGen internal error";
    case 3: return "TetGen detected a self-intersection of the surface";
    case 4: return "TetGen detected a very small input feature (tolerance)";
    case 5: return "TetGen detected two very close input facets";
    case 10: return "TetGen detected an input error";
    default: return "TetGen failed with code " + std::to_string(code);
  }
}

}  // namespace

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
  std::string switches = sw.str();
  // TetGen runs in a child process: Debian's libtet frees its pools twice when it throws an error
  // (terminatetetgen() frees, then the unwinding destructor frees again), which crashes the whole
  // process on bad input (typically self-intersecting surfaces). The child sends the result through a
  // pipe; a crash or an error code becomes Error(Failed) here.
  int fds[2];
  if (pipe(fds) != 0) throw Error(ErrorKind::Failed, "cannot create a pipe for TetGen");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw Error(ErrorKind::Failed, "cannot fork for TetGen");
  }
  if (pid == 0) {
    close(fds[0]);
    const int null_fd = open("/dev/null", O_WRONLY);
    if (null_fd >= 0) dup2(null_fd, 1), dup2(null_fd, 2);
    auto write_all = [&](const void* data, std::size_t bytes) {
      const char* p = static_cast<const char*>(data);
      while (bytes > 0) {
        const ssize_t w = write(fds[1], p, bytes);
        if (w <= 0) _exit(99);
        p += w;
        bytes -= static_cast<std::size_t>(w);
      }
    };
    std::int64_t header[3] = {0, 0, 0};
    try {
      tetrahedralize(&switches[0], &in, &out);
    } catch (int code) {
      header[0] = code;
      write_all(header, sizeof header);
      _exit(3);
    } catch (...) {
      header[0] = 2;
      write_all(header, sizeof header);
      _exit(3);
    }
    header[1] = out.numberofpoints;
    header[2] = out.numberofcorners == 4 ? out.numberoftetrahedra : 0;
    write_all(header, sizeof header);
    write_all(out.pointlist, sizeof(REAL) * 3 * static_cast<std::size_t>(header[1]));
    for (std::int64_t i = 0; i < 4 * header[2]; ++i) {
      const std::int32_t id = out.tetrahedronlist[i] - out.firstnumber;
      write_all(&id, sizeof id);
    }
    _exit(0);
  }
  close(fds[1]);
  std::vector<char> bytes;
  {
    char buffer[1 << 16];
    for (;;) {
      const ssize_t r = read(fds[0], buffer, sizeof buffer);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) break;
      bytes.insert(bytes.end(), buffer, buffer + r);
    }
    close(fds[0]);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::int64_t header[3] = {-1, 0, 0};
  if (bytes.size() >= sizeof header) std::memcpy(header, bytes.data(), sizeof header);
  if (header[0] > 0) throw Error(ErrorKind::Failed, tetgen_reason(static_cast<int>(header[0])));
  if (WIFSIGNALED(status) || header[0] < 0)
    throw Error(ErrorKind::Failed, "TetGen aborted on this surface (libtet aborts while cleaning up after an internal "
                "error; its fixed tolerances reject near-degenerate or badly scaled features)");
  const std::size_t np = static_cast<std::size_t>(header[1]), ntet = static_cast<std::size_t>(header[2]);
  if (ntet == 0) throw Error(ErrorKind::Failed, "TetGen produced no tetrahedra");
  if (bytes.size() != sizeof header + 24 * np + 16 * ntet)
    throw Error(ErrorKind::Failed, "TetGen's output was truncated");
  TetMeshData m;
  m.xyz.resize(3 * np);
  std::memcpy(m.xyz.data(), bytes.data() + sizeof header, 24 * np);
  m.vertex_labels.assign(np, 0);
  m.tets.resize(4 * ntet);
  m.tet_labels.assign(ntet, 0);
  const char* ids = bytes.data() + sizeof header + 24 * np;
  std::size_t flipped = 0;
  for (std::size_t t = 0; t < ntet; ++t) {
    std::uint32_t* q = &m.tets[4 * t];
    for (int k = 0; k < 4; ++k) {
      std::int32_t id;
      std::memcpy(&id, ids + 4 * (4 * t + k), 4);
      if (id < 0 || static_cast<std::size_t>(id) >= np)
        throw Error(ErrorKind::Failed, "TetGen returned a bad vertex id");
      q[k] = static_cast<std::uint32_t>(id);
    }
    const int sgn = orient3d(&m.xyz[3 * q[0]], &m.xyz[3 * q[1]], &m.xyz[3 * q[2]], &m.xyz[3 * q[3]]);
    if (sgn == 0) throw Error(ErrorKind::Failed, "TetGen produced a degenerate tet " + std::to_string(t));
    if (sgn < 0) {
      std::swap(q[0], q[1]);  // odd permutation: VOLMAP-positive
      ++flipped;
    }
  }
  (void)flipped;  // TetGen's tets are all negative in the VOLMAP convention: every one is flipped
  return m;
}

}  // namespace volmap
