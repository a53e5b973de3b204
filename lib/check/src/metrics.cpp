// metrics.cpp — VOLMAP-compatible distortion metrics (volmap-reference.md §7; VOLMAP metrics/functions.cpp,
// cinolib distortion_energies.cpp, Verdict report SAND2007-1751 §6.11 radius ratio and scaled Jacobian).
// Orientation: VOLMAP-positive = exact orient3d > 0; per-tet work uses the INPUT tet's vertex ids on
// both meshes. The per-tet kernels and the two arithmetic paths of the energies (VOLMAP's JacobiSVD
// path and the closed forms that print the same digits) are in metrics_tet.hpp.
// Passes: exact signs of both meshes with the volume totals (the scale factor), then ONE more pass
// over the tets as a TBB pipeline: chunks of tets are evaluated in parallel into a few reusable
// buffers and reduced by a serial in-order stage, so every sum runs in tet order exactly as VOLMAP's
// serial loops (same rounding) while no per-tet array is kept (unless keep_per_tet).
#include <volmap/core/error.hpp>
#include <volmap/check/map_check.hpp>
#include <volmap/check/metrics.hpp>
#include <volmap/predicates.hpp>

#include "metrics_tet.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace volmap {
namespace {

using namespace metrics_detail;

// The "singular values" VOLMAP's metrics binary read for a tet without finite J (see
// MetricsOptions::emulate_volmap_singular_tets): doubles 5, 6, 7 of the row-major output edge matrix
// F_out = [b1−b0 | b2−b0 | b3−b0], i.e. (b3−b0).y, (b1−b0).z, (b2−b0).z. Hypotheses tested against
// the duck-star oracle row (the only pair with such tets): previous/next/last tet's singular values,
// zeros, rows/columns of F_in, F_in⁻¹, J of this and neighbouring tets, and every 3 consecutive
// doubles of F_in, F_out, F_in⁻¹, J (row- and column-major) of tets t−2..t+2; only this one gives all
// 15 printed numbers of the row (in particular Dirichlet/SymDir/ARAP minima 5.14619 / 8.44081 /
// 12.9782, all three from tet 15272, and Conformal / MIPS3D E 3.12373 / 9.54883).
void volmap_singular_tet_values(const double* const out[4], double sigma[3]) {
  sigma[0] = out[3][1] - out[0][1];
  sigma[1] = out[1][2] - out[0][2];
  sigma[2] = out[2][2] - out[0][2];
}

// What the in-order reduction needs of one tet.
struct TetResult {
  double energy[kEnergies];  // VOLMAP-compatible, clamped; valid tets only
  double scaled[kEnergies];  // of the scale-normalised output; valid tets only
  double weight;             // cinolib unsigned volume of the output tet; valid tets only
  double weight_scaled;      // |V_out|·k³; valid tets only
  double trr_out;            // VOLMAP's "Tet Radius Ratio" −R/(3r) of the output
  double quality_out;        // 3r/R of the output, signed by its exact orientation
  double quality_in;         // 3r/R of the input
  double scaled_jacobian_out;
  bool singular_source;      // J not finite (F_in singular in doubles)
};

struct TetContext {
  const TetMeshData& in;
  const std::vector<double>& out_xyz;
  const std::int8_t* sign_out;
  double scale, upper;
  ClosedFormBounds bounds;
  bool emulate_singular;
  PerTetMetrics* per_tet;  // null unless keep_per_tet
};

// Energies of a valid tet (exact orient3d of the output > 0) into r; sigma (when not null) receives
// the JacobiSVD singular values for the per-tet report.
void valid_tet_energies(const TetContext& c, const double* const pin[4], const double* const pout[4], TetResult& r,
                        double* sigma) {
  const RowMat3 f_in = edge_matrix(pin), f_out = edge_matrix(pout);
  const RowMat3 j = compat_jacobian(f_in, f_out);
  double svd[3];
  bool have_svd = false;
  auto take_svd = [&] {
    if (!have_svd) jacobi_singular_values(j, svd);
    have_svd = true;
  };
  if (sigma) take_svd();
  r.singular_source = !j.allFinite();
  if (r.singular_source) {
    take_svd();  // NaN
    double emulated[3];
    if (c.emulate_singular) volmap_singular_tet_values(pout, emulated);
    compat_energies(c.emulate_singular ? emulated : svd, c.upper, r.energy);
    std::fill(r.scaled, r.scaled + kEnergies, c.upper);
  } else {
    const Invariants v = invariants_of(j, det3(j));
    ClosedFormParts parts;
    if (!closed_form_energies(v, c.bounds, r.energy, parts)) {
      take_svd();
      compat_energies(svd, c.upper, r.energy);
      parts = ClosedFormParts{};
    }
    const double det_in = det3(f_in);
    if (det_in != 0.0) {
      scaled_energies(Invariants{v.i1, v.i2, det3(f_out) / det_in}, c.scale, c.bounds, parts, r.scaled);
    } else {
      std::fill(r.scaled, r.scaled + kEnergies, c.upper);
    }
  }
  if (sigma) std::copy(svd, svd + 3, sigma);
}

void evaluate_tet(const TetContext& c, std::size_t t, TetResult& r) {
  const std::uint32_t* tet = &c.in.tets[4 * t];
  const double* pin[4] = {&c.in.xyz[3 * tet[0]], &c.in.xyz[3 * tet[1]], &c.in.xyz[3 * tet[2]], &c.in.xyz[3 * tet[3]]};
  const double* pout[4] = {&c.out_xyz[3 * tet[0]], &c.out_xyz[3 * tet[1]], &c.out_xyz[3 * tet[2]],
                           &c.out_xyz[3 * tet[3]]};
  double* sigma = c.per_tet ? &c.per_tet->singular_values[3 * t] : nullptr;
  if (c.sign_out[t] > 0) {
    valid_tet_energies(c, pin, pout, r, sigma);
  } else {
    std::fill(r.energy, r.energy + kEnergies, c.upper);
    std::fill(r.scaled, r.scaled + kEnergies, c.upper);
    r.weight = r.weight_scaled = 0;
    const RowMat3 j = compat_jacobian(edge_matrix(pin), edge_matrix(pout));
    r.singular_source = !j.allFinite();
    if (sigma) jacobi_singular_values(j, sigma);
  }
  const TetFramePair frames(pin, pout);  // lane 0 the input tet, lane 1 the output tet
  const Lanes ratios = frames.radius_ratio_formula();
  const double jacobi_out = frames.jacobi[1];
  if (c.sign_out[t] > 0) {
    r.weight = unsigned_volume_of(jacobi_out);
    r.weight_scaled = std::fabs(volume_volmap(pout[0], pout[1], pout[2], pout[3])) * (c.scale * c.scale * c.scale);
  }
  const double radius_ratio_out = radius_ratio_of(ratios[1], jacobi_out);
  r.trr_out = -radius_ratio_out;
  r.quality_out = c.sign_out[t] * (1.0 / radius_ratio_out);
  r.quality_in = 1.0 / radius_ratio_of(ratios[0], frames.jacobi[0]);
  r.scaled_jacobian_out = scaled_jacobian_of(frames.n0[1], frames.n2[1], frames.n3[1], TetFramePair::lane(frames.l1, 1),
                                             TetFramePair::lane(frames.l4, 1), sub(pout[3], pout[2]), jacobi_out);
  if (c.per_tet) {
    PerTetMetrics& p = *c.per_tet;
    for (int e = 0; e < kEnergies; ++e) p.energy[e][t] = r.energy[e];
    p.quality_out[t] = r.quality_out;
    p.quality_in[t] = r.quality_in;
    p.scaled_jacobian_out[t] = r.scaled_jacobian_out;
  }
}

// min / max / plain sum, in the order values arrive (the mean is unweighted).
struct Accumulator {
  double min = std::numeric_limits<double>::infinity(), max = -std::numeric_limits<double>::infinity(), sum = 0;
  void add(double value) {
    min = std::min(min, value);
    max = std::max(max, value);
    sum += value;
  }
  RangeStats stats(std::size_t count) const {
    RangeStats s;
    s.defined = count > 0;
    s.min = count > 0 ? min : 0.0;
    s.max = count > 0 ? max : 0.0;
    s.mean = count > 0 ? sum / double(count) : std::numeric_limits<double>::quiet_NaN();
    return s;
  }
};

// The in-order reduction: VOLMAP's loops (min starts at upper, max at lower, E over valid tets) for
// the compatible energies, the same for the scaled ones, and plain accumulators for the rest.
struct Reduction {
  double sum[2][kEnergies] = {}, min[2][kEnergies], max[2][kEnergies];
  double weight[2] = {0, 0};
  bool any_valid = false;
  Accumulator trr, quality_in, quality_out, scaled_jacobian;
  std::size_t count = 0;
  std::size_t num_singular = 0;
  std::vector<std::uint64_t> first_singular;

  explicit Reduction(double upper) {
    for (int s = 0; s < 2; ++s)
      for (int e = 0; e < kEnergies; ++e) min[s][e] = upper, max[s][e] = kLowerBound[e];
  }
  void add(std::size_t t, std::int8_t sign_out, const TetResult& r) {
    if (sign_out > 0) {
      any_valid = true;
      const double* values[2] = {r.energy, r.scaled};
      const double w[2] = {r.weight, r.weight_scaled};
      for (int s = 0; s < 2; ++s) {
        for (int e = 0; e < kEnergies; ++e) {
          const double d = values[s][e];
          min[s][e] = std::min(min[s][e], d);
          max[s][e] = std::max(max[s][e], d);
          sum[s][e] += d * w[s];
        }
        weight[s] += w[s];
      }
    }
    trr.add(r.trr_out);
    quality_out.add(r.quality_out);
    quality_in.add(r.quality_in);
    scaled_jacobian.add(r.scaled_jacobian_out);
    ++count;
    if (r.singular_source) {
      ++num_singular;
      if (first_singular.size() < 20) first_singular.push_back(t);
    }
  }
  void finish(MetricsReport& report) const {
    for (int s = 0; s < 2; ++s)
      for (int e = 0; e < kEnergies; ++e) {
        RangeStats& stats = s == 0 ? report.energy[e] : report.energy_scaled[e];
        stats.defined = any_valid;
        stats.min = min[s][e];
        stats.max = max[s][e];
        stats.mean = any_valid ? sum[s][e] / weight[s] : std::numeric_limits<double>::quiet_NaN();
      }
    report.tet_radius_ratio = trr.stats(count);
    report.quality_in = quality_in.stats(count);
    report.quality_out = quality_out.stats(count);
    report.scaled_jacobian_out = scaled_jacobian.stats(count);
    report.num_singular_source = num_singular;
    report.first_singular_source = first_singular;
  }
};

// The first pass: exact orientation of every tet on both meshes (input must be all positive; the
// output's signs are kept), in parallel (chunked deterministic reduction of the counts), then the
// volume totals that give the scale factor, serially in tet order as VOLMAP sums (a chunked sum
// rounds differently and changes the last digits of scale_factor; the loop costs ~1 ms per 100k tets).
struct FirstPass {
  std::size_t in_not_positive = 0;
  std::size_t first_in_not_positive = std::numeric_limits<std::size_t>::max();
  std::size_t out_zero = 0, out_negative = 0;
  double in_abs = 0, out_signed = 0, out_abs = 0;  // Σ|V_in|, ΣV_out, Σ|V_out| in doubles, tet order

  static FirstPass join(FirstPass a, const FirstPass& b) {
    a.in_not_positive += b.in_not_positive;
    a.first_in_not_positive = std::min(a.first_in_not_positive, b.first_in_not_positive);
    a.out_zero += b.out_zero, a.out_negative += b.out_negative;
    return a;
  }
};

FirstPass orientation_and_volumes(const TetMeshData& in, const std::vector<double>& out_xyz, std::int8_t* sign_out,
                                  bool parallel) {
  auto corners = [](const std::vector<double>& xyz, const std::uint32_t* tet, const double* p[4]) {
    for (int k = 0; k < 4; ++k) p[k] = &xyz[3 * tet[k]];
  };
  auto body = [&](const tbb::blocked_range<std::size_t>& r, FirstPass acc) {
    const FpEnvironmentScope fp;  // MXCSR is per thread: one scope per task body
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const double *a[4], *b[4];
      corners(in.xyz, &in.tets[4 * t], a);
      corners(out_xyz, &in.tets[4 * t], b);
      if (fp.orient3d(a[0], a[1], a[2], a[3]) <= 0) {
        ++acc.in_not_positive;
        acc.first_in_not_positive = std::min(acc.first_in_not_positive, t);
      }
      const int s = fp.orient3d(b[0], b[1], b[2], b[3]);
      sign_out[t] = static_cast<std::int8_t>(s);
      acc.out_zero += s == 0;
      acc.out_negative += s < 0;
    }
    return acc;
  };
  const std::size_t nt = in.num_tets();
  FirstPass first = parallel ? tbb::parallel_deterministic_reduce(tbb::blocked_range<std::size_t>(0, nt, 8192),
                                                                  FirstPass{}, body, FirstPass::join)
                             : body(tbb::blocked_range<std::size_t>(0, nt), FirstPass{});
  for (std::size_t t = 0; t < nt; ++t) {
    const double *a[4], *b[4];
    corners(in.xyz, &in.tets[4 * t], a);
    corners(out_xyz, &in.tets[4 * t], b);
    const double vi = volume_volmap(a[0], a[1], a[2], a[3]), vo = volume_volmap(b[0], b[1], b[2], b[3]);
    first.in_abs += std::fabs(vi);
    first.out_signed += vo;
    first.out_abs += std::fabs(vo);
  }
  return first;
}

void require_finite(const std::vector<double>& xyz, const char* what) {
  if (!std::all_of(xyz.begin(), xyz.end(), [](double x) { return std::isfinite(x); }))
    throw Error(ErrorKind::BadInput, std::string(what) + ": non-finite vertex coordinate");
}

// Tets [begin, end) into results[0, end − begin). The vertices of tet t + kPrefetchDistance are
// prefetched (both meshes): the gathers of coordinates are the cache misses of this pass.
constexpr std::size_t kPrefetchDistance = 8;
void evaluate_range(const TetContext& c, std::size_t begin, std::size_t end, TetResult* results) {
  const std::size_t nt = c.in.num_tets();
  for (std::size_t t = begin; t < end; ++t) {
    if (t + kPrefetchDistance < nt) {
      const std::uint32_t* ahead = &c.in.tets[4 * (t + kPrefetchDistance)];
      for (int k = 0; k < 4; ++k) {
        __builtin_prefetch(&c.in.xyz[3 * std::size_t(ahead[k])]);
        __builtin_prefetch(&c.out_xyz[3 * std::size_t(ahead[k])]);
      }
    }
    evaluate_tet(c, t, results[t - begin]);
  }
}

// The one pass over the tets: chunks are evaluated in parallel and reduced in tet order.
void evaluate_and_reduce(const TetContext& c, std::size_t nt, bool parallel, Reduction& reduction) {
  constexpr std::size_t kChunk = 256;  // small buffers: few pages to map, all in cache
  const std::size_t num_chunks = (nt + kChunk - 1) / kChunk;
  auto reduce = [&](std::size_t begin, std::size_t end, const TetResult* results) {
    for (std::size_t t = begin; t < end; ++t) reduction.add(t, c.sign_out[t], results[t - begin]);
  };
  if (!parallel || num_chunks <= 1) {
    std::vector<TetResult> results(std::min(nt, kChunk));
    for (std::size_t begin = 0; begin < nt; begin += kChunk) {
      const std::size_t end = std::min(nt, begin + kChunk);
      evaluate_range(c, begin, end, results.data());
      reduce(begin, end, results.data());
    }
    return;
  }
  // At most `tokens` chunks are in flight and they retire in order, so chunk i can use buffer i % tokens.
  const std::size_t tokens = 2 * std::size_t(tbb::this_task_arena::max_concurrency());
  std::vector<std::vector<TetResult>> buffers(tokens, std::vector<TetResult>(kChunk));
  std::size_t next = 0;
  auto source = [&](tbb::flow_control& fc) -> std::size_t {
    if (next == num_chunks) fc.stop();
    return next++;
  };
  auto evaluate = [&](std::size_t chunk) {
    const std::size_t begin = chunk * kChunk;
    evaluate_range(c, begin, std::min(nt, begin + kChunk), buffers[chunk % tokens].data());
    return chunk;
  };
  auto retire = [&](std::size_t chunk) {
    const std::size_t begin = chunk * kChunk;
    reduce(begin, std::min(nt, begin + kChunk), buffers[chunk % tokens].data());
  };
  tbb::parallel_pipeline(tokens, tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order, source) &
                                     tbb::make_filter<std::size_t, std::size_t>(tbb::filter_mode::parallel, evaluate) &
                                     tbb::make_filter<std::size_t, void>(tbb::filter_mode::serial_in_order, retire));
}

}  // namespace

const char* energy_name(Energy e) {
  switch (e) {
    case Energy::Conformal: return "conformal";
    case Energy::Dirichlet: return "dirichlet";
    case Energy::SymmetricDirichlet: return "symmetric_dirichlet";
    case Energy::Arap: return "arap";
    case Energy::Mips3d: return "mips3d";
  }
  return "?";
}

double energy_lower_bound(Energy e) {
  return kLowerBound[static_cast<int>(e)];
}

std::array<double, kNumEnergies> tet_energies(const double* const in[4], const double* const out[4], double upper) {
  std::array<double, kNumEnergies> e{};
  compat_energies(tet_singular_values(in, out).data(), upper, e.data());
  return e;
}

std::array<double, 3> tet_singular_values(const double* const in[4], const double* const out[4]) {
  std::array<double, 3> s{};
  jacobi_singular_values(compat_jacobian(edge_matrix(in), edge_matrix(out)), s.data());
  return s;
}

double tet_radius_ratio_compat(const double* p0, const double* p1, const double* p2, const double* p3) {
  return -TetFrame(p0, p1, p2, p3).radius_ratio();
}

double tet_scaled_jacobian_volmap(const double* p0, const double* p1, const double* p2, const double* p3) {
  return TetFrame(p0, p1, p2, p3).scaled_jacobian(p2, p3);
}

MetricsReport compute_metrics(const TetMeshData& in, const TetMeshData& out, const MetricsOptions& options) {
  if (in.xyz.size() % 3 != 0 || in.tets.size() % 4 != 0 || out.xyz.size() % 3 != 0 || out.tets.size() % 4 != 0) {
    throw Error(ErrorKind::BadInput, "malformed mesh arrays");
  }
  match_connectivity(in, out);  // throws on any mismatch
  return compute_metrics(in, out.xyz, options);
}

MetricsReport compute_metrics(const TetMeshData& in, const std::vector<double>& out_xyz, const MetricsOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!(options.upper >= 6.0) || !std::isfinite(options.upper)) {
    throw Error(ErrorKind::BadInput, "upper bound must be a finite number >= 6 (the largest lower clamp)");
  }
  if (in.xyz.size() % 3 != 0 || in.tets.size() % 4 != 0) throw Error(ErrorKind::BadInput, "malformed mesh arrays");
  if (out_xyz.size() != in.xyz.size())
    throw Error(ErrorKind::BadInput, "the output has " + std::to_string(out_xyz.size() / 3) + " vertex positions, the input " +
                                         std::to_string(in.num_vertices()) + " vertices");
  for (std::uint32_t v : in.tets)
    if (v >= in.num_vertices())
      throw Error(ErrorKind::BadInput, "input mesh: a tet refers to vertex " + std::to_string(v) + " of " +
                                           std::to_string(in.num_vertices()));
  const std::size_t nt = in.num_tets();
  MetricsReport report;
  report.num_tets = nt;
  report.upper = options.upper;

  require_finite(in.xyz, "input mesh");
  require_finite(out_xyz, "output mesh");
  std::vector<std::int8_t> sign_out(nt);
  const FirstPass first = orientation_and_volumes(in, out_xyz, sign_out.data(), options.parallel);
  if (first.in_not_positive != 0) {
    throw Error(ErrorKind::BadInput, "input mesh has " + std::to_string(first.in_not_positive) +
                               " tets that are not VOLMAP-positive (exact orient3d <= 0; first: tet " +
                               std::to_string(first.first_in_not_positive) + "): metrics need a positive source mesh");
  }
  report.num_inverted = first.out_zero + first.out_negative;
  report.num_degenerate = first.out_zero;
  {
    // VOLMAP computes the percentage in float.
    const float percent = static_cast<float>(report.num_inverted) / static_cast<float>(nt == 0 ? 1 : nt) * 100.0f;
    report.inverted_percent = nt == 0 ? 0.0 : static_cast<double>(percent);
  }
  report.volume_in = first.in_abs;
  report.volume_out = first.out_abs;
  const double reference_out = first.out_signed > 0 ? first.out_signed : first.out_abs;
  report.scale_factor = reference_out > 0 ? std::cbrt(first.in_abs / reference_out) : 1.0;

  if (options.keep_per_tet) {
    PerTetMetrics& p = report.per_tet;
    p.orientation = sign_out;
    for (int e = 0; e < kNumEnergies; ++e) p.energy[e].resize(nt);
    p.quality_in.resize(nt);
    p.quality_out.resize(nt);
    p.scaled_jacobian_out.resize(nt);
    p.singular_values.resize(3 * nt);
  }
  const TetContext context{in,
                           out_xyz,
                           sign_out.data(),
                           report.scale_factor,
                           options.upper,
                           ClosedFormBounds(options.upper),
                           options.emulate_volmap_singular_tets,
                           options.keep_per_tet ? &report.per_tet : nullptr};
  Reduction reduction(options.upper);
  evaluate_and_reduce(context, nt, options.parallel, reduction);
  reduction.finish(report);
  report.singular_source_emulated = options.emulate_volmap_singular_tets;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

std::string format_metrics_volmap(const MetricsReport& r) {
  std::ostringstream s;  // default stream formatting = VOLMAP's std::cout (6 significant digits)
  auto triple = [&](const char* name, const RangeStats& st) {
    s << name << " (min/max/E): " << st.min << " / " << st.max << " / ";
    if (st.defined) s << st.mean; else s << "undefined";
    s << "\n";
  };
  s << "Num tets: " << r.num_tets << "\n";
  s << "Num inv. tets: " << r.num_inverted << " (" << static_cast<float>(r.inverted_percent) << "%)\n";
  triple("Conformal", r.energy[0]);
  triple("Dirichlet", r.energy[1]);
  triple("Sym. Dirichlet", r.energy[2]);
  triple("Arap", r.energy[3]);
  triple("Mips3d", r.energy[4]);
  s << "Tet Radius Ratio: (min/max/avg): " << r.tet_radius_ratio.min << " / " << r.tet_radius_ratio.max << " /: "
    << r.tet_radius_ratio.mean << "\n";
  return s.str();
}

std::string format_metrics_csv_line(const std::string& map_name, const MetricsReport& r) {
  auto f = [](double v) { return std::to_string(v); };  // %f, as VOLMAP (NaN prints "nan"/"-nan")
  const std::string sep = "; ";
  std::string line = map_name + sep + std::to_string(r.num_tets) + sep + std::to_string(r.num_inverted) + sep;
  for (int e = 0; e < kNumEnergies; ++e) {
    const RangeStats& st = r.energy[e];
    line += f(st.min) + sep + f(st.max) + sep + f(st.mean) + sep;
  }
  line += f(r.tet_radius_ratio.min) + sep + f(r.tet_radius_ratio.max) + sep + f(r.tet_radius_ratio.mean);
  return line;
}

}  // namespace volmap
