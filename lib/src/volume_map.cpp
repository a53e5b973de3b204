// volume_map.cpp — the volmap-map pipeline (see volmap/volume_map.hpp for conventions).
#include <volmap/volume_map.hpp>

#include <volmap/boundary_faces.hpp>
#include <volmap/chord_split.hpp>
#include <volmap/cone_repair.hpp>
#include <volmap/error.hpp>
#include <volmap/ffm.hpp>
#include <volmap/predicates.hpp>
#include <volmap/tlc.hpp>

#include <tbb/global_control.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>

namespace volmap {

namespace {
using Clock = std::chrono::steady_clock;

std::size_t exact_nonpositive(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tets) {
  const TetSignCounts c = orient3d_tets(xyz.data(), xyz.size() / 3, tets.data(), tets.size() / 4, nullptr);
  if (!c.ok) return tets.size() / 4;
  return c.zero + c.negative;
}
}  // namespace

void tutte_uniform(const std::vector<std::uint32_t>& tets, const std::vector<std::uint8_t>& on_boundary,
                   std::vector<double>& target_xyz) {
  const std::size_t nv = on_boundary.size();
  std::vector<std::int64_t> index(nv, -1);
  std::size_t n = 0;
  for (std::size_t v = 0; v < nv; ++v)
    if (!on_boundary[v]) index[v] = std::int64_t(n++);
  if (n == 0) return;
  std::vector<std::uint64_t> edges;
  edges.reserve(tets.size() / 4 * 6);
  static const int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
    for (const auto& e : kEdge) {
      std::uint64_t a = tets[4 * t + e[0]], b = tets[4 * t + e[1]];
      if (a > b) std::swap(a, b);
      edges.push_back((a << 32) | b);
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(2 * edges.size() + n);
  std::vector<double> diag(n, 0.0);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(Eigen::Index(n), 3);
  for (std::uint64_t e : edges) {
    const std::uint32_t a = std::uint32_t(e >> 32), b = std::uint32_t(e & 0xffffffffu);
    const std::int64_t ia = index[a], ib = index[b];
    if (ia >= 0) diag[std::size_t(ia)] += 1;
    if (ib >= 0) diag[std::size_t(ib)] += 1;
    if (ia >= 0 && ib >= 0) {
      trip.emplace_back(Eigen::Index(ia), Eigen::Index(ib), -1.0);
      trip.emplace_back(Eigen::Index(ib), Eigen::Index(ia), -1.0);
    } else if (ia >= 0) {
      for (int i = 0; i < 3; ++i) rhs(Eigen::Index(ia), i) += target_xyz[3 * std::size_t(b) + i];
    } else if (ib >= 0) {
      for (int i = 0; i < 3; ++i) rhs(Eigen::Index(ib), i) += target_xyz[3 * std::size_t(a) + i];
    }
  }
  for (std::size_t i = 0; i < n; ++i) trip.emplace_back(Eigen::Index(i), Eigen::Index(i), diag[i]);
  Eigen::SparseMatrix<double> L(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  L.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  if (solver.info() != Eigen::Success)
    throw Error(ErrorKind::Failed, "", 0, "tutte: the interior Laplacian is singular (an interior component does not touch the boundary)");
  const Eigen::MatrixXd X = solver.solve(rhs);
  for (std::size_t v = 0; v < nv; ++v)
    if (index[v] >= 0)
      for (int i = 0; i < 3; ++i) target_xyz[3 * v + i] = X(Eigen::Index(index[v]), i);
}

VolumeMapResult compute_volume_map(const TetMeshData& input, const BoundaryMap& map, const VolumeMapOptions& options) {
  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  auto remaining = [&]() -> double {
    if (options.time_limit_seconds <= 0) return 0;
    return std::max(1e-3, options.time_limit_seconds - elapsed());
  };
  auto out_of_time = [&] { return options.time_limit_seconds > 0 && elapsed() >= options.time_limit_seconds; };

  std::unique_ptr<tbb::global_control> thread_limit;
  if (options.max_threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(options.max_threads));
  VolumeMapResult r;
  const std::size_t nv = input.num_vertices(), nt = input.num_tets();
  r.input_tets = nt;
  r.input_vertices = nv;
  if (nt == 0) throw Error(ErrorKind::BadInput, "", 0, "the mesh has no tets");
  if (input.tets.size() != 4 * nt || input.xyz.size() != 3 * nv) throw Error(ErrorKind::BadInput, "", 0, "inconsistent mesh arrays");
  for (std::uint32_t v : input.tets)
    if (v >= nv) throw Error(ErrorKind::BadInput, "", 0, "tet vertex id out of range");

  // Boundary: the map must prescribe exactly the boundary vertices.
  const std::vector<std::uint32_t> bverts = boundary_vertex_ids(input);
  r.on_boundary.assign(nv, 0);
  for (auto v : bverts) r.on_boundary[v] = 1;
  r.target_xyz.assign(3 * nv, 0.0);
  std::vector<std::uint8_t> seen(nv, 0);
  for (std::size_t k = 0; k < map.size(); ++k) {
    const std::uint32_t v = map.vids[k];
    if (v >= nv) throw Error(ErrorKind::BadInput, "", 0, "map vertex id " + std::to_string(v) + " out of range");
    if (!r.on_boundary[v]) throw Error(ErrorKind::BadInput, "", 0, "map vertex " + std::to_string(v) + " is not a boundary vertex");
    if (seen[v]) throw Error(ErrorKind::BadInput, "", 0, "map vertex " + std::to_string(v) + " appears twice");
    seen[v] = 1;
    for (int i = 0; i < 3; ++i) r.target_xyz[3 * std::size_t(v) + i] = map.xyz[3 * k + i];
  }
  for (auto v : bverts)
    if (!seen[v]) throw Error(ErrorKind::BadInput, "", 0, "boundary vertex " + std::to_string(v) + " has no prescribed position");
  if (exact_nonpositive(input.xyz, input.tets) != 0)
    throw Error(ErrorKind::BadInput, "", 0, "the source mesh has tets with orient3d <= 0 (not VOLMAP-positive)");

  r.source = input;
  auto stage_done = [&](const std::string& name, double t0) {
    VolumeMapStage s;
    s.name = name;
    s.seconds = elapsed() - t0;
    s.nonpositive_after = exact_nonpositive(r.target_xyz, r.source.tets);
    r.stages.push_back(s);
    return s.nonpositive_after;
  };

  // §3 feasibility.
  double t0 = elapsed();
  r.feasibility = analyze_feasibility(input, r.on_boundary, r.target_xyz);
  r.stages.push_back({"feasibility", elapsed() - t0, 0});

  // §4 B0: split the blocking chords.
  const std::size_t growth_budget = std::size_t(options.max_growth * double(nt));
  if (options.allow_refinement && (!r.feasibility.blocking_chord_edges.empty() || !r.feasibility.blocking_chord_faces.empty())) {
    t0 = elapsed();
    const ChordSplitResult cs = split_chords(r.source, r.on_boundary, r.feasibility.blocking_chord_edges, r.feasibility.blocking_chord_faces);
    r.chord_edges_split = cs.edges_split;
    r.chord_faces_split = cs.faces_split;
    r.refined = cs.vertices_added > 0;
    r.target_xyz.resize(3 * r.source.num_vertices(), 0.0);
    r.stages.push_back({"chord-split", elapsed() - t0, 0});
  }

  // §2 Tutte 3D.
  t0 = elapsed();
  tutte_uniform(r.source.tets, r.on_boundary, r.target_xyz);
  std::size_t bad = stage_done("tutte3d", t0);
  if (bad == 0) r.certified_by = "tutte3d";

  // §5 FFM (regular reference, then rest shape) or §6 TLC.
  if (bad > 0 && options.method == MapMethod::Ffm) {
    for (ReferenceShape ref : {ReferenceShape::RegularTet, ReferenceShape::RestShape}) {
      if (bad == 0 || out_of_time()) break;
      t0 = elapsed();
      FfmOptions fo;
      fo.reference = ref;
      fo.time_limit_seconds = remaining();
      ffm_untangle(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, fo);
      const std::string name = ref == ReferenceShape::RegularTet ? "ffm-regular" : "ffm-rest";
      bad = stage_done(name, t0);
      if (bad == 0) r.certified_by = name;
    }
  }
  if (bad > 0 && options.method == MapMethod::Tlc && !out_of_time()) {
    t0 = elapsed();
    TlcOptions to;
    to.time_limit_seconds = remaining();
    tlc_untangle(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, to);
    bad = stage_done("tlc", t0);
    if (bad == 0) r.certified_by = "tlc";
  }

  // §7 B1 cone repair of what remains.
  if (bad > 0 && options.allow_refinement && options.method == MapMethod::Ffm && !out_of_time()) {
    t0 = elapsed();
    ConeRepairOptions co;
    co.max_added_tets = growth_budget > 0 ? growth_budget : 1;
    const ConeRepairResult cr = cone_repair(r.source, r.on_boundary, r.target_xyz, co);
    r.cone_patches = cr.patches;
    if (cr.patches > 0) r.refined = true;
    bad = stage_done("cone-repair", t0);
    if (bad == 0) r.certified_by = "cone-repair";
    if (bad > 0 && cr.patches > 0 && !out_of_time()) {
      // Re-run the untangler on the repaired mesh (its connectivity changed).
      t0 = elapsed();
      FfmOptions fo;
      fo.time_limit_seconds = remaining();
      ffm_untangle(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, fo);
      bad = stage_done("ffm-after-repair", t0);
      if (bad == 0) r.certified_by = "ffm-after-repair";
    }
  }

  // Quality pass (never breaks validity: kept only when the exact check passes).
  if (bad == 0 && options.quality_pass && !out_of_time()) {
    t0 = elapsed();
    ffm_quality_pass(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, ReferenceShape::RestShape,
                     options.quality_iterations, remaining());
    bad = stage_done("quality", t0);
  }

  r.nonpositive = exact_nonpositive(r.target_xyz, r.source.tets);
  r.certified = r.nonpositive == 0 && exact_nonpositive(r.source.xyz, r.source.tets) == 0;
  if (!r.certified) r.certified_by.clear();
  r.seconds = elapsed();
  return r;
}

}  // namespace volmap
