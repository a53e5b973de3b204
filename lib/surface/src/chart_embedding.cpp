// Chart flooding and the per-chart embedding (see chart_embedding.hpp). Validity of a chart is
// decided exactly on the written doubles: every image triangle positive in its face plane
// (orient2d) and about the check's kernel (orient3d): the domain's own kernel point for custom and
// polycube domains, else the centroid of all image points.
#include "chart_embedding.hpp"

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/surface/surface_map_check.hpp>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace volmap::surface_detail {
namespace {

[[noreturn]] void fail(const std::string& reason) { throw Error(ErrorKind::Failed, "", 0, reason); }

// Re-solves of a chart with stretch-reducing weights before giving up on it.
constexpr int kMaxReweightRounds = 200;
// Passes over the charts against the centroid of the image points (the check's kernel).
constexpr int kMaxCentroidPasses = 10;
// Per round, a vertex's relative stretch is clamped to [1/kStretchClamp, kStretchClamp].
constexpr double kStretchClamp = 1e4;
// A chart whose most shrunk triangle has less than kMinAreaRatio of its fair share of the face's
// area (its surface area × the chart's plane/surface area ratio) is reweighted until it has, at
// most kMaxQualityRounds times: Tutte's uniform weights shrink long thin parts exponentially
// (areas 1e-20 of their share on a creature's limbs), and a volume map inside such a sliver of the
// domain needs points that doubles cannot hold.
constexpr double kMinAreaRatio = 1e-4;
constexpr int kMaxQualityRounds = 30;

// Nodes on their targets, arc vertices on the straight segment between the targets of the arc's
// nodes, spaced by arc length.
void place_graph(const WorkingSurface& s, const Domain& d, const EmbeddedGraph& g, std::vector<double>& img) {
  for (std::size_t n = 0; n < d.num_nodes(); ++n)
    for (int k = 0; k < 3; ++k) img[3 * g.node_vertex[n].idx() + k] = d.targets[n][k];
  for (std::size_t a = 0; a < d.arcs.size(); ++a) {
    const auto& p = g.arc_path[a];
    const Point3& ta = d.targets[d.arcs[a].from];
    const Point3& tb = d.targets[d.arcs[a].to];
    double total = 0;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) total += s.length(p[i], p[i + 1]);
    double acc = 0;
    for (std::size_t i = 1; i + 1 < p.size(); ++i) {
      acc += s.length(p[i - 1], p[i]);
      const double t = acc / total;
      for (int k = 0; k < 3; ++k) img[3 * p[i].idx() + k] = ta[k] + t * (tb[k] - ta[k]);
    }
  }
}

// Floods the faces across non-arc edges into charts (face property `chart`); returns each chart's
// domain face: the face on the left of its arcs' darts.
std::vector<int> flood_charts(WorkingSurface& s, const Domain& d) {
  auto& m = s.mesh;
  std::vector<int> face_of_dart(2 * d.arcs.size(), -1);  // 2*arc (+1 when running to -> from)
  for (std::size_t f = 0; f < d.faces.size(); ++f) {
    const auto& face = d.faces[f];
    for (std::size_t i = 0; i < face.arcs.size(); ++i) {
      const int arc = face.arcs[i];
      face_of_dart[2 * arc + (d.arcs[arc].from == face.nodes[i] ? 0 : 1)] = static_cast<int>(f);
    }
  }
  for (auto f : m.faces()) m.property(s.chart, f) = -1;
  std::vector<int> chart_face;
  std::vector<FaceHandle> stack;
  for (auto seed : m.faces()) {
    if (m.property(s.chart, seed) >= 0) continue;
    const int c = static_cast<int>(chart_face.size());
    chart_face.push_back(-1);
    m.property(s.chart, seed) = c;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const FaceHandle f = stack.back();
      stack.pop_back();
      for (auto h : m.fh_range(f)) {
        const std::int32_t label = m.property(s.arc_label, m.edge_handle(h));
        if (label != 0) {
          const int arc = (label - 1) / 2;
          const bool forward = (h.idx() & 1) == (label - 1) % 2;  // h runs from -> to along the arc
          const int df = face_of_dart[2 * arc + (forward ? 0 : 1)];
          if (chart_face[c] >= 0 && chart_face[c] != df)
            fail("a chart touches two domain faces: the embedded arcs do not match the domain");
          chart_face[c] = df;
          continue;
        }
        const FaceHandle g = m.face_handle(m.opposite_halfedge_handle(h));
        if (m.property(s.chart, g) < 0) {
          m.property(s.chart, g) = c;
          stack.push_back(g);
        }
      }
    }
  }
  if (chart_face.size() != d.faces.size())
    fail("the arcs cut the surface into " + std::to_string(chart_face.size()) + " charts, the domain has " +
         std::to_string(d.faces.size()) + " faces");
  std::vector<int> seen(d.faces.size(), 0);
  for (int f : chart_face)
    if (f < 0 || seen[f]++) fail("charts do not correspond one-to-one to domain faces");
  return chart_face;
}

// Orthonormal frame of a domain face's plane: origin at its first node, e1 towards the second,
// e2 = n x e1 with n the Newell normal (outward).
struct FaceFrame {
  Point3 o, e1, e2;
  void to_plane(const double* x, double* uv) const {
    const double d0 = x[0] - o[0], d1 = x[1] - o[1], d2 = x[2] - o[2];
    uv[0] = d0 * e1[0] + d1 * e1[1] + d2 * e1[2];
    uv[1] = d0 * e2[0] + d1 * e2[1] + d2 * e2[2];
  }
  void to_space(const double* uv, double* x) const {
    for (int j = 0; j < 3; ++j) x[j] = o[j] + uv[0] * e1[j] + uv[1] * e2[j];
  }
};

FaceFrame face_frame(const Domain& d, const DomainFace& face) {
  FaceFrame fr;
  fr.o = d.targets[face.nodes[0]];
  Point3 nrm{0, 0, 0};
  const std::size_t k = face.nodes.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Point3& p = d.targets[face.nodes[i]];
    const Point3& q = d.targets[face.nodes[(i + 1) % k]];
    nrm[0] += (p[1] - q[1]) * (p[2] + q[2]);
    nrm[1] += (p[2] - q[2]) * (p[0] + q[0]);
    nrm[2] += (p[0] - q[0]) * (p[1] + q[1]);
  }
  const double nn = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
  for (auto& x : nrm) x /= nn;
  for (int j = 0; j < 3; ++j) fr.e1[j] = d.targets[face.nodes[1]][j] - fr.o[j];
  const double l1 = std::sqrt(fr.e1[0] * fr.e1[0] + fr.e1[1] * fr.e1[1] + fr.e1[2] * fr.e1[2]);
  for (auto& x : fr.e1) x /= l1;
  fr.e2 = {nrm[1] * fr.e1[2] - nrm[2] * fr.e1[1], nrm[2] * fr.e1[0] - nrm[0] * fr.e1[2],
           nrm[0] * fr.e1[1] - nrm[1] * fr.e1[0]};
  return fr;
}

// One chart: its faces, the frame of its domain face, its interior vertices (off the graph) with
// their neighbours in CSR and one symmetric positive weight per entry (uniform at first).
struct Chart {
  int face = -1;
  FaceFrame frame;
  std::vector<FaceHandle> faces;
  std::vector<VertexHandle> graph_vertices;  // the chart's vertices on the graph (its boundary)
  std::vector<VertexHandle> interior;
  std::vector<std::uint32_t> first;
  std::vector<VertexHandle> nbr;
  std::vector<double> weight;
  int rounds = 0;  // stretch-reducing rounds so far
};

// Builds, solves and reweights charts. Interior vertices belong to one chart each, so the
// vertex-indexed scratch (local index, plane coordinates) serves every chart; the plane coordinates
// of graph vertices are re-projected in the chart's frame before each use.
class ChartEmbedder {
 public:
  ChartEmbedder(const WorkingSurface& s, std::vector<double>& img)
      : s_(s),
        img_(img),
        local_(s.num_vertices(), -1),
        uv_(2 * s.num_vertices(), 0.0),
        sum_area_(s.num_vertices(), 0.0),
        sum_stretch_(s.num_vertices(), 0.0) {}

  Chart build(std::vector<FaceHandle> faces, const FaceFrame& frame, int face);
  // One sparse LDL^T solve of the weighted barycentric system; writes the interior vertices' images.
  void solve(const Chart& c);
  // Re-solves c with stretch-reducing weights until it is valid about k. Throws when the round
  // budget is spent.
  void reweight_until_valid(Chart& c, const double* k);
  bool valid(const Chart& c, const double* k) const;
  // Reweights c while its smallest area ratio is below kMinAreaRatio, keeping the weights of the
  // best round (kMaxQualityRounds at most).
  void reduce_shrinking(Chart& c);

 private:
  const WorkingSurface& s_;
  std::vector<double>& img_;
  std::vector<std::int32_t> local_;  // vertex index -> index among its chart's interior vertices
  std::vector<double> uv_;           // face-plane coordinates
  std::vector<double> sum_area_, sum_stretch_;  // per-vertex stretch accumulators (zero between uses)

  void project_graph_vertices(const Chart& c);
  void reduce_stretch_weights(Chart& c);
  double smallest_area_ratio(const Chart& c);
  // A triangle's corners: plane coordinates (2 doubles each) and surface points (3 each).
  struct Corners {
    const double *ua, *ub, *uc, *p, *q, *r;
  };
  Corners corners(const std::array<VertexHandle, 3>& t) const;
  std::array<double, 2> plane_and_surface_area(const std::array<VertexHandle, 3>& t) const;
};

Chart ChartEmbedder::build(std::vector<FaceHandle> faces, const FaceFrame& frame, int face) {
  Chart c;
  c.face = face;
  c.frame = frame;
  c.faces = std::move(faces);
  for (auto f : c.faces)
    for (auto v : face_vertices(s_.mesh, f)) {
      if (s_.is_on_graph(v)) {
        c.graph_vertices.push_back(v);
      } else if (local_[v.idx()] < 0) {
        local_[v.idx()] = static_cast<std::int32_t>(c.interior.size());
        c.interior.push_back(v);
      }
    }
  std::sort(c.graph_vertices.begin(), c.graph_vertices.end());
  c.graph_vertices.erase(std::unique(c.graph_vertices.begin(), c.graph_vertices.end()), c.graph_vertices.end());
  c.first.assign(1, 0);
  for (auto v : c.interior) {
    s_.for_each_outgoing(v, [&](HalfedgeHandle h) {
      const VertexHandle w = s_.mesh.to_vertex_handle(h);
      if (!s_.is_on_graph(w) && local_[w.idx()] < 0) fail("internal: interior vertex with a neighbour outside its chart");
      c.nbr.push_back(w);
    });
    c.first.push_back(static_cast<std::uint32_t>(c.nbr.size()));
  }
  c.weight.assign(c.nbr.size(), 1.0);
  return c;
}

void ChartEmbedder::project_graph_vertices(const Chart& c) {
  for (auto v : c.graph_vertices) c.frame.to_plane(&img_[3 * v.idx()], &uv_[2 * v.idx()]);
}

void ChartEmbedder::solve(const Chart& c) {
  if (c.interior.empty()) return;
  project_graph_vertices(c);
  const auto m = static_cast<Eigen::Index>(c.interior.size());
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(c.nbr.size() + c.interior.size());
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 2);
  for (Eigen::Index i = 0; i < m; ++i) {
    double diag = 0;
    for (std::uint32_t q = c.first[i]; q < c.first[i + 1]; ++q) {
      const VertexHandle w = c.nbr[q];
      const double wt = c.weight[q];
      diag += wt;
      if (s_.is_on_graph(w)) {
        rhs(i, 0) += wt * uv_[2 * w.idx()];
        rhs(i, 1) += wt * uv_[2 * w.idx() + 1];
      } else {
        trip.emplace_back(static_cast<int>(i), local_[w.idx()], -wt);
      }
    }
    trip.emplace_back(static_cast<int>(i), static_cast<int>(i), diag);
  }
  Eigen::SparseMatrix<double> L(m, m);
  L.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  if (solver.info() != Eigen::Success) fail("the Tutte system of a chart could not be factorised");
  const Eigen::MatrixXd uv = solver.solve(rhs);
  if (solver.info() != Eigen::Success) fail("the Tutte system of a chart could not be solved");
  for (Eigen::Index i = 0; i < m; ++i) {
    const VertexHandle v = c.interior[static_cast<std::size_t>(i)];
    uv_[2 * v.idx()] = uv(i, 0);
    uv_[2 * v.idx() + 1] = uv(i, 1);
    c.frame.to_space(&uv_[2 * v.idx()], &img_[3 * v.idx()]);
  }
}

// Every triangle of the chart strictly positive in the face plane (orient2d of the written points'
// plane coordinates) and about k (orient3d), exactly: a triangle the plane embedding collapsed can
// still look positive about one point through the rounding of its 3D coordinates.
bool ChartEmbedder::valid(const Chart& c, const double* k) const {
  for (auto f : c.faces) {
    const auto t = face_vertices(s_.mesh, f);
    double uv[3][2];
    for (int j = 0; j < 3; ++j) c.frame.to_plane(&img_[3 * t[j].idx()], uv[j]);
    if (orient2d(uv[0], uv[1], uv[2]) <= 0) return false;
    const double* a = &img_[3 * t[0].idx()];
    const double* b = &img_[3 * t[1].idx()];
    const double* d = &img_[3 * t[2].idx()];
    if (orient3d(a, b, d, k) <= 0) return false;
  }
  return true;
}

// The signed area of a chart triangle in its face plane (the current plane coordinates) and its
// area on the surface.
ChartEmbedder::Corners ChartEmbedder::corners(const std::array<VertexHandle, 3>& t) const {
  return {&uv_[2 * t[0].idx()], &uv_[2 * t[1].idx()], &uv_[2 * t[2].idx()], s_.point(t[0]), s_.point(t[1]), s_.point(t[2])};
}

std::array<double, 2> ChartEmbedder::plane_and_surface_area(const std::array<VertexHandle, 3>& t) const {
  const auto [ua, ub, uc, p, q, r] = corners(t);
  const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, w[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
  const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
  return {0.5 * ((ub[0] - ua[0]) * (uc[1] - ua[1]) - (uc[0] - ua[0]) * (ub[1] - ua[1])),
          0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])};
}

// One round of stretch reduction (after Yoshizawa, Belyaev and Seidel's stretch-minimising
// reweighting, symmetrised): each vertex's L2 stretch sigma (area-weighted over its chart triangles,
// relative to the chart's mean scale, clamped) divides the weights of its edges by sqrt(sigma), so
// vertices are pulled less towards over-shrunk regions. Triangles the rounding collapsed count as
// maximally stretched. Weights stay positive, so the next solve is again an embedding in exact
// arithmetic.
void ChartEmbedder::reduce_stretch_weights(Chart& c) {
  project_graph_vertices(c);
  // Per triangle: plane and surface areas, and the squared L2 stretch of the plane -> surface map.
  std::vector<std::array<double, 2>> tri(c.faces.size());
  double total2 = 0, total3 = 0;
  for (std::size_t i = 0; i < c.faces.size(); ++i) {
    const auto t = face_vertices(s_.mesh, c.faces[i]);
    const auto [ua, ub, uc, p, q, r] = corners(t);
    const auto [A2, A3] = plane_and_surface_area(t);
    double s2 = std::numeric_limits<double>::infinity();
    if (A2 > 0) {
      double ss = 0, st = 0;
      for (int j = 0; j < 3; ++j) {
        const double Ss = (p[j] * (ub[1] - uc[1]) + q[j] * (uc[1] - ua[1]) + r[j] * (ua[1] - ub[1])) / (2 * A2);
        const double St = (p[j] * (uc[0] - ub[0]) + q[j] * (ua[0] - uc[0]) + r[j] * (ub[0] - ua[0])) / (2 * A2);
        ss += Ss * Ss;
        st += St * St;
      }
      s2 = 0.5 * (ss + st);
    }
    tri[i] = {A3, s2};
    total2 += A2;
    total3 += A3;
  }
  const double scale = total2 / total3;  // squared stretch of a map shrinking every area alike
  const double cap = kStretchClamp * kStretchClamp;
  for (std::size_t i = 0; i < c.faces.size(); ++i) {
    double s2 = tri[i][1] * scale;
    if (!(s2 <= cap)) s2 = cap;  // collapsed or inverted in the plane: maximal
    for (auto v : face_vertices(s_.mesh, c.faces[i])) {
      sum_area_[v.idx()] += tri[i][0];
      sum_stretch_[v.idx()] += tri[i][0] * s2;
    }
  }
  const auto sigma = [&](VertexHandle v) {
    const double s2 = sum_area_[v.idx()] > 0 ? sum_stretch_[v.idx()] / sum_area_[v.idx()] : 1.0;
    return std::clamp(std::sqrt(s2), 1.0 / kStretchClamp, kStretchClamp);
  };
  for (std::size_t i = 0; i < c.interior.size(); ++i) {
    const double si = sigma(c.interior[i]);
    for (std::uint32_t q = c.first[i]; q < c.first[i + 1]; ++q) c.weight[q] /= std::sqrt(si * sigma(c.nbr[q]));
  }
  for (auto f : c.faces)
    for (auto v : face_vertices(s_.mesh, f)) sum_area_[v.idx()] = sum_stretch_[v.idx()] = 0;
}

// The smallest (plane area / surface area) of the chart's triangles over the chart's ratio (0 for
// a triangle the rounding collapsed or inverted).
double ChartEmbedder::smallest_area_ratio(const Chart& c) {
  project_graph_vertices(c);
  double total2 = 0, total3 = 0, worst = std::numeric_limits<double>::infinity();
  for (auto f : c.faces) {
    const auto [A2, A3] = plane_and_surface_area(face_vertices(s_.mesh, f));
    total2 += std::max(A2, 0.0);
    total3 += A3;
    if (A3 > 0) worst = std::min(worst, std::max(A2, 0.0) / A3);
  }
  return total2 > 0 && total3 > 0 ? worst / (total2 / total3) : 0.0;
}

void ChartEmbedder::reduce_shrinking(Chart& c) {
  if (c.interior.empty()) return;
  double best = smallest_area_ratio(c);
  std::vector<double> best_weight = c.weight;
  for (int round = 0; round < kMaxQualityRounds && best < kMinAreaRatio; ++round) {
    reduce_stretch_weights(c);
    solve(c);
    const double ratio = smallest_area_ratio(c);
    if (ratio > best) {
      best = ratio;
      best_weight = c.weight;
    }
  }
  if (best_weight != c.weight) {
    c.weight = std::move(best_weight);
    solve(c);
  }
}

void ChartEmbedder::reweight_until_valid(Chart& c, const double* k) {
  while (!valid(c, k)) {
    if (c.interior.empty())
      fail("a chart of domain face " + std::to_string(c.face) + " has an inverted triangle between arcs");
    if (c.rounds == kMaxReweightRounds)
      fail("the embedding of the chart of domain face " + std::to_string(c.face) + " stays inverted after " +
           std::to_string(kMaxReweightRounds) + " rounds of stretch-reducing weights");
    ++c.rounds;
    reduce_stretch_weights(c);
    solve(c);
  }
}

}  // namespace

std::vector<double> embed_charts(WorkingSurface& s, const Domain& d, const EmbeddedGraph& g) {
  std::vector<double> img(3 * s.num_vertices(), std::numeric_limits<double>::quiet_NaN());
  place_graph(s, d, g, img);
  const std::vector<int> chart_face = flood_charts(s, d);
  std::vector<std::vector<FaceHandle>> chart_faces(chart_face.size());
  for (auto f : s.mesh.faces()) chart_faces[s.mesh.property(s.chart, f)].push_back(f);
  ChartEmbedder embedder(s, img);
  std::vector<Chart> charts;
  for (std::size_t c = 0; c < chart_face.size(); ++c) {
    charts.push_back(embedder.build(std::move(chart_faces[c]), face_frame(d, d.faces[chart_face[c]]), chart_face[c]));
    embedder.solve(charts.back());
    embedder.reduce_shrinking(charts.back());
  }
  // Valid about the check's kernel: the domain's own (custom, polycube) or the centroid of all image
  // points (vertex index order = vid order). Reweighting a chart moves the centroid a little: repeat
  // until no chart changes.
  for (int pass = 0;; ++pass) {
    const Point3 k = d.has_fixed_kernel() ? d.kernel
                                          : compensated_centroid(s.num_vertices(), [&](std::size_t i) { return &img[3 * i]; });
    bool all_valid = true;
    for (auto& c : charts)
      if (!embedder.valid(c, k.data())) {
        all_valid = false;
        embedder.reweight_until_valid(c, k.data());
      }
    if (all_valid) return img;
    if (pass == kMaxCentroidPasses) fail("the charts stay inverted about the centroid of the image points");
  }
}

}  // namespace volmap::surface_detail
