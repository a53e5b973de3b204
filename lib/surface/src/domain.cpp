// Base domains: the five VOLMAP built-ins (volmap-reference.md §3, replicating the reference code,
// including the TET apex (33.3, 50, 33.3)) and custom domain files. Rotations and faces are derived
// from the target geometry around the kernel point: every arc leaving a node is projected on the
// plane orthogonal to (target - kernel) and sorted by angle (counter-clockwise around the outward
// direction); faces are traced from that rotation system (next dart after u->v is v->w with w the
// neighbour just clockwise of u at v, which keeps the face on the left). Validity is then decided with
// exact orient3d on the targets.
#include <volmap/surface/domain.hpp>
#include <volmap/surface/polycube.hpp>
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace volmap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }

// Reference bbox corner numbering (kBboxCornerBits): 0 (m,m,m) 1 (m,m,M) 2 (M,m,M) 3 (M,m,m)
// 4 (m,M,m) 5 (m,M,M) 6 (M,M,M) 7 (M,M,m).
Point3 bbox_corner(int c, const Point3& m, const Point3& M) {
  const int* sel = kBboxCornerBits[c];
  return {sel[0] ? M[0] : m[0], sel[1] ? M[1] : m[1], sel[2] ? M[2] : m[2]};
}

Domain make_base(DomainKind kind, const std::string& name, std::vector<Point3> targets,
                 std::vector<std::pair<int, int>> arcs) {
  Domain d;
  d.kind = kind;
  d.name = name;
  d.targets = std::move(targets);
  d.probe_corners.assign(d.targets.size(), {});
  d.probe_fraction.assign(d.targets.size(), {kNaN, kNaN, kNaN});
  for (auto& a : arcs) d.arcs.push_back({a.first, a.second});
  return d;
}

Domain make_cube_like(DomainKind kind, const std::string& name) {
  std::vector<Point3> t = {{0, 0, 0},       {0, 0, 100},     {100, 0, 100}, {100, 0, 0},
                           {0, 100, 0},     {0, 100, 100},   {100, 100, 100}, {100, 100, 0}};
  Domain d = make_base(kind, name, t,
                       {{0, 1}, {1, 2}, {2, 3}, {0, 3}, {0, 4}, {1, 5}, {2, 6}, {3, 7}, {4, 5}, {5, 6}, {6, 7}, {4, 7}});
  for (int i = 0; i < 8; ++i) d.probe_corners[i] = {i};
  return d;
}

Domain make_star() {
  Domain d = make_cube_like(DomainKind::Star, "star");
  const Point3 face_targets[6] = {{-100, 50, 50}, {50, -100, 50}, {50, 50, 200},
                                  {50, 200, 50},  {50, 50, -100}, {200, 50, 50}};
  const int diag[6][2] = {{5, 0}, {0, 2}, {5, 2}, {5, 7}, {0, 7}, {6, 3}};
  for (int k = 0; k < 6; ++k) {
    d.targets.push_back(face_targets[k]);
    d.probe_corners.push_back({});
    d.probe_fraction.push_back({kNaN, kNaN, kNaN});
  }
  for (int k = 0; k < 6; ++k) {
    DomainDiagonal g;
    g.from = diag[k][0];
    g.to = diag[k][1];
    g.middle_node = 8 + k;
    g.first_arc = static_cast<int>(d.arcs.size());
    d.arcs.push_back({g.from, g.middle_node});
    g.second_arc = static_cast<int>(d.arcs.size());
    d.arcs.push_back({g.middle_node, g.to});
    d.diagonals.push_back(g);
  }
  const int rest[12][2] = {{8, 1},  {8, 4},  {9, 1},  {9, 3},  {10, 1}, {10, 6},
                           {11, 4}, {11, 6}, {12, 3}, {12, 4}, {13, 2}, {13, 7}};
  for (auto& a : rest) d.arcs.push_back({a[0], a[1]});
  return d;
}

[[noreturn]] void invalid(const std::string& source, std::size_t line, const std::string& reason) {
  throw Error(ErrorKind::BadInput, source, line, "invalid domain: " + reason);
}

bool three_connected(const Domain& d) {
  const int n = static_cast<int>(d.num_nodes());
  std::vector<std::vector<int>> adj(n);
  for (auto& a : d.arcs) {
    adj[a.from].push_back(a.to);
    adj[a.to].push_back(a.from);
  }
  std::vector<char> seen(n);
  std::vector<int> stack;
  for (int r1 = -1; r1 < n; ++r1)
    for (int r2 = r1 + 1; r2 < n; ++r2) {
      std::fill(seen.begin(), seen.end(), 0);
      if (r1 >= 0) seen[r1] = 1;
      seen[r2] = 1;
      int start = 0;
      while (start < n && seen[start]) ++start;
      if (start == n) continue;
      int count = 0, removed = (r1 >= 0) + 1;
      stack.assign(1, start);
      seen[start] = 1;
      while (!stack.empty()) {
        int u = stack.back();
        stack.pop_back();
        ++count;
        for (int v : adj[u])
          if (!seen[v]) seen[v] = 1, stack.push_back(v);
      }
      if (count != n - removed) return false;
    }
  return true;
}

}  // namespace

bool Domain::has_probe(int node) const {
  return !probe_corners[node].empty() || !std::isnan(probe_fraction[node][0]);
}

Point3 Domain::probe(int node, const Point3& m, const Point3& M) const {
  if (!probe_corners[node].empty()) {
    Point3 s{0, 0, 0};
    for (int c : probe_corners[node]) {
      Point3 p = bbox_corner(c, m, M);
      for (int k = 0; k < 3; ++k) s[k] += p[k];
    }
    const double n = static_cast<double>(probe_corners[node].size());
    return {s[0] / n, s[1] / n, s[2] / n};
  }
  Point3 p;
  for (int k = 0; k < 3; ++k) {
    const double f = probe_fraction[node][k];
    if (f == 0.5)
      p[k] = (m[k] + M[k]) / 2;  // the reference's mid
    else if (f == 1.0 / 3.0)
      p[k] = m[k] + (M[k] - m[k]) / 3;  // the reference's tet apex probe
    else
      p[k] = m[k] + f * (M[k] - m[k]);
  }
  return p;
}

std::vector<int> Domain::trace_order() const {
  std::vector<int> order;
  std::vector<char> in_diag(arcs.size(), 0);
  for (auto& g : diagonals) in_diag[g.first_arc] = in_diag[g.second_arc] = 1;
  // Arcs before the first diagonal arc, then the diagonals, then the rest (the reference order).
  const int first_diag = diagonals.empty() ? static_cast<int>(arcs.size()) : diagonals.front().first_arc;
  for (int a = 0; a < first_diag; ++a)
    if (!in_diag[a]) order.push_back(a);
  for (auto& g : diagonals) order.push_back(g.first_arc);
  for (int a = first_diag; a < static_cast<int>(arcs.size()); ++a)
    if (!in_diag[a]) order.push_back(a);
  return order;
}

bool is_builtin_domain_name(const std::string& n) {
  static const char* names[] = {"cube", "tet", "pyr", "octa", "star", "CUBE", "TETRAHEDRON", "PYRAMID",
                                "OCTAHEDRON", "STAR", "tetrahedron", "pyramid", "octahedron"};
  for (auto* s : names)
    if (n == s) return true;
  return false;
}

Domain builtin_domain(const std::string& name) {
  Domain d;
  if (name == "cube" || name == "CUBE") {
    d = make_cube_like(DomainKind::Cube, "cube");
  } else if (name == "pyr" || name == "PYRAMID" || name == "pyramid") {
    d = make_base(DomainKind::Pyramid, "pyr", {{0, 0, 0}, {0, 0, 100}, {100, 0, 100}, {100, 0, 0}, {50, 100, 50}},
                  {{0, 1}, {1, 2}, {2, 3}, {0, 3}, {4, 0}, {4, 1}, {4, 2}, {4, 3}});
    for (int i = 0; i < 4; ++i) d.probe_corners[i] = {i};
    d.probe_fraction[4] = {0.5, 1.0, 0.5};
  } else if (name == "tet" || name == "TETRAHEDRON" || name == "tetrahedron") {
    d = make_base(DomainKind::Tet, "tet", {{0, 0, 0}, {0, 0, 100}, {100, 0, 50}, {33.3, 50.0, 33.3}},
                  {{0, 1}, {1, 2}, {0, 2}, {3, 0}, {3, 1}, {3, 2}});
    d.probe_corners[0] = {0};
    d.probe_corners[1] = {1};
    d.probe_fraction[2] = {1.0, 0.0, 0.5};
    d.probe_fraction[3] = {1.0 / 3.0, 1.0, 0.5};
  } else if (name == "octa" || name == "OCTAHEDRON" || name == "octahedron") {
    d = make_base(DomainKind::Octahedron, "octa",
                  {{0, 0, 0}, {0, 0, 100}, {100, 0, 100}, {100, 0, 0}, {50, 50, 50}, {50, -50, 50}},
                  {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 0}, {4, 1}, {4, 2}, {4, 3}, {5, 0}, {5, 1}, {5, 2}, {5, 3}});
    d.probe_fraction[0] = {0, 0.5, 0};
    d.probe_fraction[1] = {0, 0.5, 1};
    d.probe_fraction[2] = {1, 0.5, 1};
    d.probe_fraction[3] = {1, 0.5, 0};
    d.probe_fraction[4] = {0.5, 1, 0.5};
    d.probe_fraction[5] = {0.5, 0, 0.5};
  } else if (name == "star" || name == "STAR") {
    d = make_star();
  } else {
    throw Error(ErrorKind::BadInput, "", 0,
                "unknown domain '" + name + "' (expected cube, tet, pyr, octa, star or a domain file)");
  }
  Point3 c{0, 0, 0};
  for (auto& t : d.targets)
    for (int k = 0; k < 3; ++k) c[k] += t[k];
  for (int k = 0; k < 3; ++k) c[k] /= static_cast<double>(d.targets.size());
  d.kernel = c;
  finalize_domain(d, "domain " + d.name);
  return d;
}

void finalize_domain(Domain& d, const std::string& source) {
  const int n = static_cast<int>(d.num_nodes());
  const int na = static_cast<int>(d.arcs.size());
  if (n < 4) invalid(source, 0, "a polyhedral domain needs at least 4 nodes, got " + std::to_string(n));
  Point3 lo = d.targets[0], hi = d.targets[0];
  for (auto& t : d.targets)
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(t[k])) invalid(source, 0, "non-finite target coordinate");
      lo[k] = std::min(lo[k], t[k]);
      hi[k] = std::max(hi[k], t[k]);
    }
  d.size = norm(sub(hi, lo));
  // Rotation system: arcs around each node, CCW around the outward direction (target - kernel).
  d.rotation.assign(n, {});
  for (int a = 0; a < na; ++a) {
    d.rotation[d.arcs[a].from].push_back(a);
    d.rotation[d.arcs[a].to].push_back(a);
  }
  for (int v = 0; v < n; ++v) {
    if (d.rotation[v].size() < 3)
      invalid(source, 0, "node " + std::to_string(v) + " has " + std::to_string(d.rotation[v].size()) +
                             " arcs (a polyhedral graph needs at least 3)");
    if (points_equal(d.targets[v].data(), d.kernel.data()))
      invalid(source, 0, "node " + std::to_string(v) + " coincides with the kernel point");
    // The rest of this loop only orders the arcs by angle (double precision is enough for an order).
    Point3 r = sub(d.targets[v], d.kernel);
    const double rn = norm(r);
    if (!(rn > 0))
      invalid(source, 0, "node " + std::to_string(v) + " is too close to the kernel point to order its arcs");
    r = {r[0] / rn, r[1] / rn, r[2] / rn};
    Point3 axis = std::fabs(r[0]) < 0.6 ? Point3{1, 0, 0} : Point3{0, 1, 0};
    Point3 e1 = cross(axis, r);
    const double e1n = norm(e1);
    e1 = {e1[0] / e1n, e1[1] / e1n, e1[2] / e1n};
    const Point3 e2 = cross(r, e1);  // e1 x e2 = r: increasing angle = CCW around r
    std::vector<std::pair<double, int>> by_angle;
    for (int a : d.rotation[v]) {
      const int w = d.arcs[a].from == v ? d.arcs[a].to : d.arcs[a].from;
      const Point3 dir = sub(d.targets[w], d.targets[v]);
      by_angle.push_back({std::atan2(dot(dir, e2), dot(dir, e1)), a});
    }
    std::sort(by_angle.begin(), by_angle.end());
    for (std::size_t i = 0; i < by_angle.size(); ++i) {
      d.rotation[v][i] = by_angle[i].second;
      if (i > 0 && by_angle[i].first == by_angle[i - 1].first)
        invalid(source, 0, "two arcs leave node " + std::to_string(v) + " in the same direction");
    }
  }
  // Faces by dart tracing: dart 2a = from->to, 2a+1 = to->from.
  auto dart_tail = [&](int dart) { return dart % 2 == 0 ? d.arcs[dart / 2].from : d.arcs[dart / 2].to; };
  auto dart_head = [&](int dart) { return dart % 2 == 0 ? d.arcs[dart / 2].to : d.arcs[dart / 2].from; };
  std::vector<char> used(2 * na, 0);
  d.faces.clear();
  for (int start = 0; start < 2 * na; ++start) {
    if (used[start]) continue;
    DomainFace f;
    int dart = start;
    while (!used[dart]) {
      used[dart] = 1;
      f.nodes.push_back(dart_tail(dart));
      f.arcs.push_back(dart / 2);
      const int v = dart_head(dart);
      const auto& rot = d.rotation[v];
      const int k = static_cast<int>(std::find(rot.begin(), rot.end(), dart / 2) - rot.begin());
      const int next_arc = rot[(k + rot.size() - 1) % rot.size()];  // just clockwise of u at v
      dart = 2 * next_arc + (d.arcs[next_arc].from == v ? 0 : 1);
      if (static_cast<int>(f.nodes.size()) > 2 * na) invalid(source, 0, "face tracing did not close");
    }
    if (dart != start) invalid(source, 0, "face tracing did not close");
    d.faces.push_back(std::move(f));
  }
  const int nf = static_cast<int>(d.faces.size());
  if (n - na + nf != 2)
    invalid(source, 0, "the arcs around the kernel do not form a sphere-like polyhedron (V - E + F = " +
                           std::to_string(n) + " - " + std::to_string(na) + " + " + std::to_string(nf) + " = " +
                           std::to_string(n - na + nf) + ", expected 2)");
  if (!three_connected(d)) invalid(source, 0, "the arc graph is not 3-connected");
  const double* kp = d.kernel.data();
  for (int fi = 0; fi < nf; ++fi) {
    const auto& f = d.faces[fi];
    const int k = static_cast<int>(f.nodes.size());
    std::vector<int> sorted_nodes = f.nodes;
    std::sort(sorted_nodes.begin(), sorted_nodes.end());
    if (k < 3 || std::adjacent_find(sorted_nodes.begin(), sorted_nodes.end()) != sorted_nodes.end())
      invalid(source, 0, "face " + std::to_string(fi) + " is not a simple cycle");
    // Newell normal, planarity within 1e-9 * size.
    Point3 normal{0, 0, 0}, centre{0, 0, 0};
    for (int i = 0; i < k; ++i) {
      const Point3& p = d.targets[f.nodes[i]];
      const Point3& q = d.targets[f.nodes[(i + 1) % k]];
      normal[0] += (p[1] - q[1]) * (p[2] + q[2]);
      normal[1] += (p[2] - q[2]) * (p[0] + q[0]);
      normal[2] += (p[0] - q[0]) * (p[1] + q[1]);
      for (int c = 0; c < 3; ++c) centre[c] += p[c] / k;
    }
    const double nn = norm(normal);
    if (!(nn > 0)) invalid(source, 0, "face " + std::to_string(fi) + " is degenerate");
    for (int i = 0; i < k; ++i) {
      const double off = dot(sub(d.targets[f.nodes[i]], centre), normal) / nn;
      if (std::fabs(off) > 1e-9 * d.size)
        invalid(source, 0, "face " + std::to_string(fi) + " (nodes " + [&] {
          std::string s;
          for (int v : f.nodes) s += (s.empty() ? "" : " ") + std::to_string(v);
          return s;
        }() + ") is not planar");
    }
    // Strict convexity: every corner turns the same way as the normal.
    for (int i = 0; i < k; ++i) {
      const Point3& a = d.targets[f.nodes[i]];
      const Point3& b = d.targets[f.nodes[(i + 1) % k]];
      const Point3& c = d.targets[f.nodes[(i + 2) % k]];
      if (!(dot(cross(sub(b, a), sub(c, b)), normal) > 1e-12 * d.size * d.size * nn))
        invalid(source, 0, "face " + std::to_string(fi) + " is not strictly convex at node " +
                               std::to_string(f.nodes[(i + 1) % k]));
    }
    // Exact: every fan triangle sees the kernel on its inner side (strictly star-shaped, outward CCW).
    for (int i = 1; i + 1 < k; ++i) {
      const int s = orient3d(d.targets[f.nodes[0]].data(), d.targets[f.nodes[i]].data(),
                             d.targets[f.nodes[i + 1]].data(), kp);
      if (s <= 0)
        invalid(source, 0, "the domain is not strictly star-shaped w.r.t. the kernel point (face " +
                               std::to_string(fi) + ")");
    }
  }
}

Domain parse_custom_domain(const std::string& text, const std::string& source) {
  Domain d;
  d.kind = DomainKind::Custom;
  d.name = "custom";
  std::vector<std::size_t> node_lines, target_lines;
  std::vector<std::size_t> arc_lines;
  bool have_kernel = false;
  std::istringstream in(text);
  std::string line;
  std::size_t lineno = 0;
  auto parse_double = [&](const std::string& tok) {
    char* end = nullptr;
    const double v = std::strtod(tok.c_str(), &end);
    if (tok.empty() || *end != '\0' || !std::isfinite(v)) invalid(source, lineno, "bad number '" + tok + "'");
    return v;
  };
  auto parse_int = [&](const std::string& tok) {
    char* end = nullptr;
    const long v = std::strtol(tok.c_str(), &end, 10);
    if (tok.empty() || *end != '\0' || v < 0 || v > 1000000) invalid(source, lineno, "bad index '" + tok + "'");
    return static_cast<int>(v);
  };
  while (std::getline(in, line)) {
    ++lineno;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string t; ls >> t;) tok.push_back(t);
    if (tok.empty()) continue;
    const std::string& key = tok[0];
    if (key == "n") {
      if (tok.size() < 2) invalid(source, lineno, "'n' needs at least one bbox corner index");
      std::vector<int> corners;
      for (std::size_t i = 1; i < tok.size(); ++i) {
        const int c = parse_int(tok[i]);
        if (c > 7) invalid(source, lineno, "bbox corner index " + tok[i] + " out of range 0..7");
        corners.push_back(c);
      }
      d.probe_corners.push_back(corners);
      d.probe_fraction.push_back({kNaN, kNaN, kNaN});
      node_lines.push_back(lineno);
    } else if (key == "nm" || key == "k") {
      if (tok.size() != 4) invalid(source, lineno, "'" + key + "' needs exactly 3 coordinates");
      const Point3 p{parse_double(tok[1]), parse_double(tok[2]), parse_double(tok[3])};
      if (key == "nm") {
        d.targets.push_back(p);
        target_lines.push_back(lineno);
      } else {
        if (have_kernel) invalid(source, lineno, "second kernel line");
        d.kernel = p;
        have_kernel = true;
      }
    } else if (key == "a") {
      if (tok.size() != 3) invalid(source, lineno, "'a' needs exactly 2 node indices");
      d.arcs.push_back({parse_int(tok[1]), parse_int(tok[2])});
      arc_lines.push_back(lineno);
    } else {
      invalid(source, lineno, "unknown directive '" + key + "' (expected n, nm, a or k)");
    }
  }
  if (d.probe_corners.empty()) invalid(source, 0, "no 'n' lines");
  if (d.targets.size() != d.probe_corners.size())
    invalid(source, target_lines.empty() ? 0 : target_lines.back(),
            std::to_string(d.probe_corners.size()) + " 'n' lines but " + std::to_string(d.targets.size()) +
                " 'nm' lines (they must match)");
  const int n = static_cast<int>(d.targets.size());
  for (std::size_t i = 0; i < d.arcs.size(); ++i) {
    const auto& a = d.arcs[i];
    if (a.from >= n || a.to >= n)
      invalid(source, arc_lines[i], "arc node index out of range (there are " + std::to_string(n) + " nodes)");
    if (a.from == a.to) invalid(source, arc_lines[i], "arc joins a node to itself");
    for (std::size_t j = 0; j < i; ++j)
      if ((d.arcs[j].from == a.from && d.arcs[j].to == a.to) || (d.arcs[j].from == a.to && d.arcs[j].to == a.from))
        invalid(source, arc_lines[i], "duplicate arc (also on line " + std::to_string(arc_lines[j]) + ")");
  }
  if (!have_kernel) {
    Point3 c{0, 0, 0};
    for (auto& t : d.targets)
      for (int k = 0; k < 3; ++k) c[k] += t[k];
    for (int k = 0; k < 3; ++k) c[k] /= n;
    d.kernel = c;
  }
  finalize_domain(d, source);
  return d;
}

Domain read_custom_domain(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw_io(path, "cannot open domain file");
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_custom_domain(ss.str(), path);
}

Domain domain_from_name_or_file(const std::string& name_or_path) {
  if (is_builtin_domain_name(name_or_path)) return builtin_domain(name_or_path);
  if (name_or_path.rfind(kPolycubePrefix, 0) == 0) return polycube_domain(name_or_path.substr(kPolycubePrefix.size()));
  return read_custom_domain(name_or_path);
}

namespace {
// Squared distance from p to triangle abc (Ericson, Real-Time Collision Detection §5.1.5).
double point_triangle_distance2(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
  const Point3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto dist2 = [&](const Point3& q) { const Point3 r = sub(p, q); return dot(r, r); };
  if (d1 <= 0 && d2 <= 0) return dist2(a);
  const Point3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dist2(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return dist2({a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]});
  }
  const Point3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dist2(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return dist2({a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return dist2({b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])});
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return dist2({a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w});
}
}  // namespace

double distance_to_domain_boundary(const Domain& d, const Point3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& f : d.faces)
    for (std::size_t i = 1; i + 1 < f.nodes.size(); ++i)
      best = std::min(best, point_triangle_distance2(p, d.targets[f.nodes[0]], d.targets[f.nodes[i]],
                                                     d.targets[f.nodes[i + 1]]));
  return std::sqrt(best);
}

}  // namespace volmap
