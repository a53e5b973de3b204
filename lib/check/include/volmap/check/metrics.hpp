// volmap/check/metrics.hpp — VOLMAP's distortion metrics of a volume map (volmap-reference.md §7),
// compatible with VOLMAP's `metrics` tool to its printed digits, plus fixed/extra fields.
// Conventions: a tet (v0,v1,v2,v3) is VOLMAP-positive iff exact orient3d > 0; an output tet is
// "inverted" iff orient3d(output positions, INPUT tet's vertex order) <= 0 (exact, absolute sign).
// Per tet: F_in = [a1−a0 | a2−a0 | a3−a0] (columns) on the input, F_out the same on the output with
// the same vertex ids, J = F_out·F_in⁻¹ (input → output), s1 ≥ s2 ≥ s3 its singular values.
// Energies (cinolib distortion_energies.cpp), clamped to [lower, upper] with inf/NaN → upper:
//   Conformal  (s1²+s2²+s3²)/(3(s1s2s3)^{2/3})           lower 1
//   Dirichlet  s1²+s2²+s3²                               lower 3
//   SymDir     Σsᵢ² + Σsᵢ⁻²                               lower 6
//   ARAP       Σ(sᵢ−1)²                                   lower 0
//   MIPS3D     ⅛(s1/s2+s2/s1)(s3/s1+s1/s3)(s2/s3+s3/s2)  lower 1
// VOLMAP-compatible fields follow the reference's floating-point path (Eigen inverse of F_in, J by a
// plain triple loop, Eigen JacobiSVD, cinolib's formulas; see metrics.cpp) so that they match its
// printed digits even on tets flat at double precision; energy_scaled uses rotation invariants
// (‖J‖², ‖cof J‖², det J = det F_out/det F_in). E = Σ d·|V_out| / Σ|V_out| over valid
// (non-inverted) tets (VOLMAP weights by OUTPUT volume). "Tet radius ratio" (compat) = −R/(3r) over all output tets (Verdict §6.11);
// quality = 3r/R ∈ (0,1]. Scaled Jacobian (Verdict), negated so VOLMAP-positive tets are > 0.
#pragma once

#include <volmap/core/mesh_data.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

enum class Energy { Conformal = 0, Dirichlet, SymmetricDirichlet, Arap, Mips3d };
inline constexpr int kNumEnergies = 5;
const char* energy_name(Energy e);            // "conformal", "dirichlet", "symmetric_dirichlet", "arap", "mips3d"
double energy_lower_bound(Energy e);          // the optimum: 1, 3, 6, 0, 1

struct MetricsOptions {
  double upper = 100.0;        // VOLMAP's clamp (its 3rd argument)
  bool keep_per_tet = false;   // fill MetricsReport::per_tet (for --vtu)
  bool parallel = true;
  // Opt-in compatibility switch, never the default. A source tet whose edge matrix F_in is exactly
  // singular in doubles has no finite J; VOLMAP's `metrics` (cinolib + Eigen 3.4 JacobiSVD, which
  // returns early on non-finite input) then reads UNINITIALISED singular values. By default such tets
  // get `upper` for every energy (the value the NaN gave with Eigen 3.3). With this switch they get
  // the values that reproduce VOLMAP's printed duck-star row to every digit:
  //   (s1, s2, s3) := (F_out(1,2), F_out(2,0), F_out(2,1)) = ((b3−b0).y, (b1−b0).z, (b2−b0).z),
  // i.e. doubles 5..7 of the row-major output edge matrix of the same tet (a fingerprint of the
  // reference binary's stack layout, found by testing hypotheses against the oracle; not a
  // meaningful energy). Only the five compatible energies change; per-tet singular values stay NaN.
  bool emulate_volmap_singular_tets = false;
};

// min / max / weighted mean over a set of tets; `defined` is false when the set is empty.
struct RangeStats {
  double min = 0, max = 0, mean = 0;
  bool defined = false;
};

struct PerTetMetrics {
  std::vector<std::int8_t> orientation;                  // exact sign of the output tet (input order)
  std::array<std::vector<double>, kNumEnergies> energy;  // clamped energies; upper for inverted tets
  std::vector<double> quality_in, quality_out;           // 3r/R (signed by orientation for the output)
  std::vector<double> scaled_jacobian_out;               // VOLMAP-positive sign
  std::vector<double> singular_values;  // 3 per tet: s1 >= s2 >= s3 >= 0 of J (JacobiSVD; every tet, inverted too)
};

struct MetricsReport {
  std::size_t num_tets = 0;
  std::size_t num_inverted = 0;   // orient3d(out) <= 0, exact
  std::size_t num_degenerate = 0; // orient3d(out) == 0 (subset of num_inverted)
  double inverted_percent = 0;
  double upper = 100.0;
  // VOLMAP-compatible energies over valid tets (min starts at upper, max at lower as in VOLMAP;
  // `defined` false when every tet is inverted, where VOLMAP prints E = NaN).
  std::array<RangeStats, kNumEnergies> energy;
  // Same, with the output scaled by k = (V_in/V_out)^(1/3) about the origin (scale-free distortion).
  std::array<RangeStats, kNumEnergies> energy_scaled;
  // Source tets whose F_in is exactly singular in doubles (J not finite): how many, the first ids, and
  // whether their energies were emulated (MetricsOptions::emulate_volmap_singular_tets) or clamped
  // to `upper` (default).
  std::size_t num_singular_source = 0;
  std::vector<std::uint64_t> first_singular_source;  // up to 20 ids, increasing
  bool singular_source_emulated = false;
  double volume_in = 0, volume_out = 0;  // total |volume| (output: all tets)
  double scale_factor = 1;               // k
  // Compat "Tet Radius Ratio" −R/(3r) over all output tets (min = worst, avg unweighted).
  RangeStats tet_radius_ratio;
  // 3r/R over all tets: input (unsigned) and output (signed by exact orientation).
  RangeStats quality_in, quality_out;
  // Scaled Jacobian of the output over all tets, VOLMAP-positive sign, unweighted mean (log.csv cols 8–10).
  RangeStats scaled_jacobian_out;
  PerTetMetrics per_tet;  // filled when keep_per_tet
  double seconds = 0;     // compute time (no parsing)
};

// Computes the metrics of the map in → out. Pairs tets by connectivity: output positions are looked
// up by the input tet's vertex ids (the output's own tet list must hold the same vertex sets; see
// match_connectivity). Throws Error(BadInput) on mismatched meshes, non-finite coordinates, an input
// tet that is not strictly positive, or upper < lower bounds.
MetricsReport compute_metrics(const TetMeshData& in, const TetMeshData& out, const MetricsOptions& options = {});

// The same for a map given as positions only: out_xyz[3v..3v+2] is the image of input vertex v (a
// caller that has matched the output's tets against the input's, e.g. with match_connectivity, can
// free them first). Throws Error(BadInput) when the sizes differ or a tet refers to a missing vertex.
MetricsReport compute_metrics(const TetMeshData& in, const std::vector<double>& out_xyz,
                              const MetricsOptions& options = {});

// Single-tet helpers (points are 3 doubles), exposed for tests and other modules.
// Returns the clamped energies of J = F_out·F_in⁻¹ (valid tets only; not for inverted ones).
std::array<double, kNumEnergies> tet_energies(const double* const in[4], const double* const out[4], double upper);
// Singular values s1 >= s2 >= s3 of J = F_out·F_in⁻¹ (VOLMAP's path: Eigen inverse, JacobiSVD).
std::array<double, 3> tet_singular_values(const double* const in[4], const double* const out[4]);
double tet_radius_ratio_compat(const double* p0, const double* p1, const double* p2, const double* p3);  // −R/(3r)
double tet_scaled_jacobian_volmap(const double* p0, const double* p1, const double* p2, const double* p3);

// VOLMAP's text block (6 significant digits) and one CSV line ("; " separated, %f; no newline).
std::string format_metrics_volmap(const MetricsReport& report);
std::string format_metrics_csv_line(const std::string& map_name, const MetricsReport& report);

}  // namespace volmap
