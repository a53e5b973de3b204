// Google Benchmark of the exact predicates (ns per call / per tet), side by side with a naive double
// determinant (not robust) and, when CGAL is found, CGAL Epick (filtered exact predicates).
// Sign conventions: volmap = Shewchuk's. CGAL::orientation(p,q,r,s) = −orient3d(p,q,r,s); CGAL's
// side_of_oriented_circle agrees with incircle, side_of_oriented_sphere = −insphere (both checked at
// start on the near-degenerate sets).
// Inputs: 4096 precomputed tuples per data set, cycled (in cache). Batch: indexed Kuhn grid of
// 56³·6 = 1 053 696 tets (uint32 ids, xyz interleaved), clean, with half of it flattened onto z = c
// (zero-column shortcut) and with half of it flattened onto a tilted plane (exact L3 path).
#include <benchmark/benchmark.h>
#include <volmap/predicates_rational.hpp>

#include "../predicates/testing/oracle.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>
#include <random>
#include <utility>
#include <vector>

#ifdef VOLMAP_HAVE_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
#endif

namespace or_ = volmap_oracle;

namespace {

constexpr int kTuples = 4096;

struct Tuples {
  std::vector<double> pts;  // kTuples × 5 points × 3 coordinates (2D uses the first two)
  const double* p(int t, int i) const { return &pts[(std::size_t(t) * 5 + i) * 3]; }
};

enum class Set { Random, NearDegenerate };

Tuples make_tuples(Set set, int dim, int npts) {
  Tuples r;
  r.pts.resize(std::size_t(kTuples) * 15);
  std::mt19937_64 rng(set == Set::Random ? 11 : 12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int t = 0; t < kTuples; ++t) {
    double* q[5];
    for (int i = 0; i < 5; ++i) q[i] = &r.pts[(std::size_t(t) * 5 + i) * 3];
    if (set == Set::Random) {
      for (int i = 0; i < 5; ++i)
        for (int k = 0; k < 3; ++k) q[i][k] = u(rng);
    } else if (dim == 2 && npts == 3) {
      or_::near_collinear(rng, q[0], q[1], q[2]);
    } else if (dim == 3 && npts == 4) {
      or_::near_coplanar(rng, q[0], q[1], q[2], q[3]);
    } else if (dim == 2) {
      or_::near_cocircular(rng, q[0], q[1], q[2], q[3]);
    } else {
      or_::near_cospherical(rng, q[0], q[1], q[2], q[3], q[4]);
    }
  }
  return r;
}

const Tuples& tuples(Set set, int dim, int npts) {
  static Tuples cache[2][6];
  const int slot = (dim - 2) * 3 + (npts - 3);
  Tuples& t = cache[int(set)][slot];
  if (t.pts.empty()) t = make_tuples(set, dim, npts);
  return t;
}

// Naive determinants kept out of line so that every contender pays one call.
__attribute__((noinline)) double naive_o2(const double* a, const double* b, const double* c) {
  return or_::naive_orient2d(a, b, c);
}
__attribute__((noinline)) double naive_o3(const double* a, const double* b, const double* c, const double* d) {
  return or_::naive_orient3d(a, b, c, d);
}
__attribute__((noinline)) double naive_ic(const double* a, const double* b, const double* c, const double* d) {
  return or_::naive_incircle(a, b, c, d);
}
__attribute__((noinline)) double naive_is(const double* a, const double* b, const double* c, const double* d,
                                          const double* e) {
  return or_::naive_insphere(a, b, c, d, e);
}

// The floor of any semi-static filter: the naive determinant plus its error bound (the largest
// |difference| per column, their product, one comparison), with no range guard and no fallback (0 when
// undecided). Not a predicate (it is wrong under overflow, underflow or directed rounding); it shows
// what the bound alone costs beside the determinant.
__attribute__((noinline)) int filter_floor_o3(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double det = (adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy)) + cdz * (adx * bdy - bdx * ady);
  const double mx = std::max({std::fabs(adx), std::fabs(bdx), std::fabs(cdx)});
  const double my = std::max({std::fabs(ady), std::fabs(bdy), std::fabs(cdy)});
  const double mz = std::max({std::fabs(adz), std::fabs(bdz), std::fabs(cdz)});
  if (__builtin_expect(std::fabs(det) > 1.1e-14 * mx * my * mz, 1)) return det > 0 ? 1 : -1;
  return 0;
}

template <class F>
void run_scalar(benchmark::State& state, const Tuples& t, F f) {
  int i = 0;
  long acc = 0;
  for (auto _ : state) {
    acc += f(t, i);
    i = (i + 1) & (kTuples - 1);
  }
  benchmark::DoNotOptimize(acc);
  state.SetItemsProcessed(state.iterations());
}

#define VOLMAP_SCALAR_BENCH(name, set, dim, npts, expr)                              \
  void name(benchmark::State& state) {                                              \
    const Tuples& tup = tuples(set, dim, npts);                                     \
    run_scalar(state, tup, [](const Tuples& t, int i) { return long(expr); });      \
  }                                                                                 \
  BENCHMARK(name)

#define P(k) t.p(i, k)
VOLMAP_SCALAR_BENCH(orient2d_random_naive, Set::Random, 2, 3, or_::naive_sign(naive_o2(P(0), P(1), P(2))));
VOLMAP_SCALAR_BENCH(orient2d_random_volmap, Set::Random, 2, 3, volmap::orient2d(P(0), P(1), P(2)));
VOLMAP_SCALAR_BENCH(orient2d_neardeg_naive, Set::NearDegenerate, 2, 3, or_::naive_sign(naive_o2(P(0), P(1), P(2))));
VOLMAP_SCALAR_BENCH(orient2d_neardeg_volmap, Set::NearDegenerate, 2, 3, volmap::orient2d(P(0), P(1), P(2)));
VOLMAP_SCALAR_BENCH(orient3d_random_naive, Set::Random, 3, 4, or_::naive_sign(naive_o3(P(0), P(1), P(2), P(3))));
VOLMAP_SCALAR_BENCH(orient3d_random_volmap, Set::Random, 3, 4, volmap::orient3d(P(0), P(1), P(2), P(3)));
VOLMAP_SCALAR_BENCH(orient3d_neardeg_naive, Set::NearDegenerate, 3, 4,
                    or_::naive_sign(naive_o3(P(0), P(1), P(2), P(3))));
VOLMAP_SCALAR_BENCH(orient3d_neardeg_volmap, Set::NearDegenerate, 3, 4, volmap::orient3d(P(0), P(1), P(2), P(3)));
VOLMAP_SCALAR_BENCH(incircle_random_naive, Set::Random, 2, 4, or_::naive_sign(naive_ic(P(0), P(1), P(2), P(3))));
VOLMAP_SCALAR_BENCH(incircle_random_volmap, Set::Random, 2, 4, volmap::incircle(P(0), P(1), P(2), P(3)));
VOLMAP_SCALAR_BENCH(incircle_neardeg_naive, Set::NearDegenerate, 2, 4,
                    or_::naive_sign(naive_ic(P(0), P(1), P(2), P(3))));
VOLMAP_SCALAR_BENCH(incircle_neardeg_volmap, Set::NearDegenerate, 2, 4, volmap::incircle(P(0), P(1), P(2), P(3)));
VOLMAP_SCALAR_BENCH(insphere_random_naive, Set::Random, 3, 5, or_::naive_sign(naive_is(P(0), P(1), P(2), P(3), P(4))));
VOLMAP_SCALAR_BENCH(insphere_random_volmap, Set::Random, 3, 5, volmap::insphere(P(0), P(1), P(2), P(3), P(4)));
VOLMAP_SCALAR_BENCH(insphere_neardeg_naive, Set::NearDegenerate, 3, 5,
                    or_::naive_sign(naive_is(P(0), P(1), P(2), P(3), P(4))));
VOLMAP_SCALAR_BENCH(insphere_neardeg_volmap, Set::NearDegenerate, 3, 5,
                    volmap::insphere(P(0), P(1), P(2), P(3), P(4)));

#ifdef VOLMAP_HAVE_CGAL
// CGAL points prebuilt per data set (construction is not timed).
struct CgalTuples {
  std::vector<Epick::Point_2> p2;
  std::vector<Epick::Point_3> p3;
};
const CgalTuples& cgal_tuples(Set set, int dim, int npts) {
  static CgalTuples cache[2][6];
  CgalTuples& c = cache[int(set)][(dim - 2) * 3 + (npts - 3)];
  if (c.p2.empty() && c.p3.empty()) {
    const Tuples& t = tuples(set, dim, npts);
    for (int i = 0; i < kTuples; ++i)
      for (int k = 0; k < 5; ++k) {
        const double* q = t.p(i, k);
        if (dim == 2) c.p2.emplace_back(q[0], q[1]);
        else c.p3.emplace_back(q[0], q[1], q[2]);
      }
  }
  return c;
}
#define CGAL_BENCH(name, set, dim, npts, expr)                                              \
  void name(benchmark::State& state) {                                                     \
    const CgalTuples& c = cgal_tuples(set, dim, npts);                                     \
    int i = 0;                                                                             \
    long acc = 0;                                                                          \
    for (auto _ : state) {                                                                 \
      acc += long(expr);                                                                   \
      i = (i + 1) & (kTuples - 1);                                                         \
    }                                                                                      \
    benchmark::DoNotOptimize(acc);                                                         \
    state.SetItemsProcessed(state.iterations());                                           \
  }                                                                                        \
  BENCHMARK(name)
#define C2(k) c.p2[std::size_t(i) * 5 + k]
#define C3(k) c.p3[std::size_t(i) * 5 + k]
CGAL_BENCH(orient2d_random_cgal_epick, Set::Random, 2, 3, CGAL::orientation(C2(0), C2(1), C2(2)));
CGAL_BENCH(orient2d_neardeg_cgal_epick, Set::NearDegenerate, 2, 3, CGAL::orientation(C2(0), C2(1), C2(2)));
CGAL_BENCH(orient3d_random_cgal_epick, Set::Random, 3, 4, CGAL::orientation(C3(0), C3(1), C3(2), C3(3)));
CGAL_BENCH(orient3d_neardeg_cgal_epick, Set::NearDegenerate, 3, 4, CGAL::orientation(C3(0), C3(1), C3(2), C3(3)));
CGAL_BENCH(incircle_random_cgal_epick, Set::Random, 2, 4, CGAL::side_of_oriented_circle(C2(0), C2(1), C2(2), C2(3)));
CGAL_BENCH(incircle_neardeg_cgal_epick, Set::NearDegenerate, 2, 4,
           CGAL::side_of_oriented_circle(C2(0), C2(1), C2(2), C2(3)));
CGAL_BENCH(insphere_random_cgal_epick, Set::Random, 3, 5,
           CGAL::side_of_oriented_sphere(C3(0), C3(1), C3(2), C3(3), C3(4)));
CGAL_BENCH(insphere_neardeg_cgal_epick, Set::NearDegenerate, 3, 5,
           CGAL::side_of_oriented_sphere(C3(0), C3(1), C3(2), C3(3), C3(4)));
#endif

// ---- batch: indexed Kuhn grid -------------------------------------------------------------------

struct Mesh {
  std::vector<double> xyz;
  std::vector<std::uint32_t> tets;
  std::size_t degenerate = 0;  // exactly flat tets
};

constexpr int kGrid = 56;  // 56³·6 = 1 053 696 tets

const Mesh& mesh(int variant) {  // 0 clean, 1 half flattened onto z = c, 2 half onto a tilted plane
  static Mesh cache[3];
  Mesh& m = cache[variant];
  if (m.tets.empty()) {
    or_::IndexedTets grid = or_::kuhn_grid(kGrid, 1.0 / 64);  // cubes of edge 2^-6: exact coordinates
    m.xyz = std::move(grid.xyz);
    m.tets = std::move(grid.tets);
    const double zc = (kGrid / 2) / 64.0;
    for (std::size_t v = 0; v < m.xyz.size() / 3; ++v) {
      double* p = &m.xyz[3 * v];
      if (variant == 1 && p[2] > zc) p[2] = zc;
      // tilted plane z = zc + (x + y)/4: exact on the 2^-6 grid; every vertex above it is projected
      if (variant == 2 && p[2] > zc + (p[0] + p[1]) / 4) p[2] = zc + (p[0] + p[1]) / 4;
    }
    const auto r = volmap::orient3d_tets(m.xyz.data(), m.xyz.size() / 3, m.tets.data(), m.tets.size() / 4, nullptr);
    m.degenerate = r.zero;
  }
  return m;
}

void batch_volmap(benchmark::State& state) {
  const Mesh& m = mesh(int(state.range(0)));
  const std::size_t nt = m.tets.size() / 4;
  std::vector<std::int8_t> signs(nt);
  volmap::TetSignCounts r;
  for (auto _ : state) {
    r = volmap::orient3d_tets(m.xyz.data(), m.xyz.size() / 3, m.tets.data(), nt, signs.data());
    benchmark::DoNotOptimize(signs.data());
  }
  state.counters["tets"] = double(nt);
  state.counters["zero_tets"] = double(r.zero);
  state.counters["ns_per_tet"] =
      benchmark::Counter(double(nt), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetItemsProcessed(state.iterations() * std::int64_t(nt));
}
BENCHMARK(batch_volmap)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void batch_naive(benchmark::State& state) {  // same loop, plain double determinant (not robust)
  const Mesh& m = mesh(int(state.range(0)));
  const std::size_t nt = m.tets.size() / 4;
  std::vector<std::int8_t> signs(nt);
  for (auto _ : state) {
    const double* xyz = m.xyz.data();
    for (std::size_t t = 0; t < nt; ++t) {
      const std::uint32_t* v = &m.tets[4 * t];
      const double det = or_::naive_orient3d(xyz + 3 * std::size_t(v[0]), xyz + 3 * std::size_t(v[1]),
                                             xyz + 3 * std::size_t(v[2]), xyz + 3 * std::size_t(v[3]));
      signs[t] = std::int8_t((det > 0) - (det < 0));
    }
    benchmark::DoNotOptimize(signs.data());
  }
  state.counters["ns_per_tet"] =
      benchmark::Counter(double(nt), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetItemsProcessed(state.iterations() * std::int64_t(nt));
}
BENCHMARK(batch_naive)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// Rational coordinates (i/56 per axis, not dyadic): the double prefilter decides; range(0) = 1 makes
// the upper half exactly flat (z = 28/56), which goes to the homogeneous integer determinant.
void batch_volmap_rational(benchmark::State& state) {
  const Mesh& m = mesh(0);
  const std::size_t nt = m.tets.size() / 4, nv = m.xyz.size() / 3;
  std::vector<volmap::Rational> rxyz(3 * nv);
  for (std::size_t i = 0; i < 3 * nv; ++i) {
    long g = std::lround(m.xyz[i] * 64);
    if (state.range(0) == 1 && i % 3 == 2 && g > kGrid / 2) g = kGrid / 2;
    rxyz[i] = volmap::Rational(g) / kGrid;
  }
  std::vector<std::int8_t> signs(nt);
  volmap::TetSignCounts r;
  for (auto _ : state) {
    r = volmap::orient3d_tets(rxyz.data(), nv, m.tets.data(), nt, signs.data());
    benchmark::DoNotOptimize(signs.data());
  }
  state.counters["zero_tets"] = double(r.zero);
  state.counters["ns_per_tet"] =
      benchmark::Counter(double(nt), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetItemsProcessed(state.iterations() * std::int64_t(nt));
}
BENCHMARK(batch_volmap_rational)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);

#ifdef VOLMAP_HAVE_CGAL
void batch_cgal_epick(benchmark::State& state) {
  const Mesh& m = mesh(int(state.range(0)));
  const std::size_t nt = m.tets.size() / 4, nv = m.xyz.size() / 3;
  std::vector<Epick::Point_3> pts;
  pts.reserve(nv);
  for (std::size_t v = 0; v < nv; ++v) pts.emplace_back(m.xyz[3 * v], m.xyz[3 * v + 1], m.xyz[3 * v + 2]);
  std::vector<std::int8_t> signs(nt);
  for (auto _ : state) {
    for (std::size_t t = 0; t < nt; ++t) {
      const std::uint32_t* v = &m.tets[4 * t];
      signs[t] = std::int8_t(-int(CGAL::orientation(pts[v[0]], pts[v[1]], pts[v[2]], pts[v[3]])));
    }
    benchmark::DoNotOptimize(signs.data());
  }
  state.counters["ns_per_tet"] =
      benchmark::Counter(double(nt), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetItemsProcessed(state.iterations() * std::int64_t(nt));
}
BENCHMARK(batch_cgal_epick)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
#endif

// ---- Same-run anchors (issue 17) ------------------------------------------------------------------
// Ours and its anchors in ONE benchmark, timed in alternating blocks (the order rotates every
// iteration), so that a loaded machine slows them alike. Each block is timed with the calling thread's
// CPU clock (preemption is not counted); the counters are the median over blocks:
//   <contender>_ns     ns per call (scalar) or per tet of one mesh pass (map-check core),
//   ratio_naive        volmap / naive double determinant (not robust: the cost floor),
//   ratio_epick        volmap / CGAL Epick (filtered exact), when CGAL is found,
//   ratio_filter_floor volmap / the bare semi-static bound (filter_floor_o3; orient3d only).
//   anchor_orient3d_random         one orient3d call on random doubles in [-1,1]³ (stage A decides);
//                                  naive is out of line (one call, like ours); CGAL is inlined.
//   anchor_map_check_core/<threads> the exact positivity pass of a map check: input Kuhn grid
//                                  56³·6 = 1 053 696 tets and its smooth deformation (the output),
//                                  both signed and counted. ours = orient3d_tets over each mesh (with
//                                  its O(V) census), naive = the plain determinant loop, epick = a
//                                  CGAL::orientation loop on prebuilt points. 2 threads: the tets split
//                                  in halves on std::threads for every contender (wall clock).

double thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
double wall_seconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Contenders of one anchor benchmark: a name and a block body returning a checksum.
struct Contender {
  const char* name;
  std::function<long()> block;
  std::vector<double> seconds;
};

void run_anchored(benchmark::State& state, std::vector<Contender>& cs, double items_per_block, bool wall) {
  long acc = 0;
  std::size_t rot = 0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < cs.size(); ++k) {
      Contender& c = cs[(k + rot) % cs.size()];
      const double t0 = wall ? wall_seconds() : thread_cpu_seconds();
      acc += c.block();
      c.seconds.push_back((wall ? wall_seconds() : thread_cpu_seconds()) - t0);
    }
    ++rot;
  }
  benchmark::DoNotOptimize(acc);
  double ns[8] = {};
  for (std::size_t k = 0; k < cs.size(); ++k) {
    ns[k] = 1e9 * median(cs[k].seconds) / items_per_block;
    state.counters[std::string(cs[k].name) + "_ns"] = ns[k];
  }
  // cs[0] is ours, cs[1] naive; ratio_<name> = ours / that contender. A filter floor is also given
  // per naive call (filter_floor_per_naive): the least any semi-static filter can cost.
  for (std::size_t k = 1; k < cs.size(); ++k) state.counters[std::string("ratio_") + cs[k].name] = ns[0] / ns[k];
  for (std::size_t k = 2; k < cs.size(); ++k)
    if (std::string(cs[k].name) == "filter_floor") state.counters["filter_floor_per_naive"] = ns[k] / ns[1];
}

void anchor_orient3d_random(benchmark::State& state) {
  constexpr int kRounds = 4;  // calls per block: kRounds · kTuples
  const Tuples& t = tuples(Set::Random, 3, 4);
  std::vector<Contender> cs;
  cs.push_back({"volmap", [&t] {
                  long s = 0;
                  for (int r = 0; r < kRounds; ++r)
                    for (int i = 0; i < kTuples; ++i) s += volmap::orient3d(t.p(i, 0), t.p(i, 1), t.p(i, 2), t.p(i, 3));
                  return s;
                }, {}});
  cs.push_back({"naive", [&t] {
                  long s = 0;
                  for (int r = 0; r < kRounds; ++r)
                    for (int i = 0; i < kTuples; ++i)
                      s += or_::naive_sign(naive_o3(t.p(i, 0), t.p(i, 1), t.p(i, 2), t.p(i, 3)));
                  return s;
                }, {}});
#ifdef VOLMAP_HAVE_CGAL
  const CgalTuples& c = cgal_tuples(Set::Random, 3, 4);
  cs.push_back({"epick", [&c] {
                  long s = 0;
                  for (int r = 0; r < kRounds; ++r)
                    for (std::size_t i = 0; i < std::size_t(kTuples); ++i)
                      s -= long(CGAL::orientation(c.p3[i * 5], c.p3[i * 5 + 1], c.p3[i * 5 + 2], c.p3[i * 5 + 3]));
                  return s;
                }, {}});
#endif
  cs.push_back({"filter_floor", [&t] {
                  long s = 0;
                  for (int r = 0; r < kRounds; ++r)
                    for (int i = 0; i < kTuples; ++i) s += filter_floor_o3(t.p(i, 0), t.p(i, 1), t.p(i, 2), t.p(i, 3));
                  return s;
                }, {}});
  run_anchored(state, cs, double(kRounds) * kTuples, false);
}
BENCHMARK(anchor_orient3d_random)->MinTime(1.0);

struct MapPair {
  std::vector<double> in, out;
  std::vector<std::uint32_t> tets;
#ifdef VOLMAP_HAVE_CGAL
  std::vector<Epick::Point_3> in_pts, out_pts;
#endif
};
const MapPair& map_pair() {
  static MapPair p;
  if (p.tets.empty()) {
    or_::IndexedTets g = or_::kuhn_grid(kGrid, 1.0 / kGrid);
    p.in = std::move(g.xyz);
    p.tets = std::move(g.tets);
    p.out.resize(p.in.size());
    // 100·(x + 0.03·(sin 2y, sin 2z, sin 2x)): Jacobian I + (entries ≤ 0.06), every tet stays positive.
    for (std::size_t v = 0; v < p.in.size() / 3; ++v) {
      const double* q = &p.in[3 * v];
      p.out[3 * v] = 100 * (q[0] + 0.03 * std::sin(2 * q[1]));
      p.out[3 * v + 1] = 100 * (q[1] + 0.03 * std::sin(2 * q[2]));
      p.out[3 * v + 2] = 100 * (q[2] + 0.03 * std::sin(2 * q[0]));
    }
#ifdef VOLMAP_HAVE_CGAL
    for (std::size_t v = 0; v < p.in.size() / 3; ++v) {
      p.in_pts.emplace_back(p.in[3 * v], p.in[3 * v + 1], p.in[3 * v + 2]);
      p.out_pts.emplace_back(p.out[3 * v], p.out[3 * v + 1], p.out[3 * v + 2]);
    }
#endif
  }
  return p;
}

// Runs body(first, count) over the tets, on `threads` threads (1: the calling thread).
long split_tets(std::size_t nt, int threads, const std::function<long(std::size_t, std::size_t)>& body) {
  if (threads <= 1) return body(0, nt);
  long other = 0;
  const std::size_t half = nt / 2 / 2048 * 2048;
  std::thread worker([&] { other = body(half, nt - half); });
  const long mine = body(0, half);
  worker.join();
  return mine + other;
}

long plain_det_positive(const double* xyz, const std::uint32_t* tets, std::size_t nt) {
  long positive = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* v = tets + 4 * t;
    positive += or_::naive_orient3d(xyz + 3 * std::size_t(v[0]), xyz + 3 * std::size_t(v[1]),
                                    xyz + 3 * std::size_t(v[2]), xyz + 3 * std::size_t(v[3])) > 0;
  }
  return positive;
}

void anchor_map_check_core(benchmark::State& state) {
  const int threads = int(state.range(0));
  const MapPair& p = map_pair();
  const std::size_t nt = p.tets.size() / 4, nv = p.in.size() / 3;
  std::vector<Contender> cs;
  cs.push_back({"volmap", [&p, nt, nv, threads] {
                  if (threads == 1)
                    return long(volmap::orient3d_tets(p.in.data(), nv, p.tets.data(), nt, nullptr).positive +
                                volmap::orient3d_tets(p.out.data(), nv, p.tets.data(), nt, nullptr).positive);
                  const volmap::Orient3dBatchFilter fi = volmap::orient3d_batch_filter(p.in.data(), nv);
                  const volmap::Orient3dBatchFilter fo = volmap::orient3d_batch_filter(p.out.data(), nv);
                  return split_tets(nt, threads, [&](std::size_t first, std::size_t count) {
                    const std::uint32_t* t = p.tets.data() + 4 * first;
                    return long(volmap::orient3d_tets(fi, p.in.data(), nv, t, count, nullptr).positive +
                                volmap::orient3d_tets(fo, p.out.data(), nv, t, count, nullptr).positive);
                  });
                }, {}});
  cs.push_back({"naive", [&p, nt, threads] {
                  return split_tets(nt, threads, [&](std::size_t first, std::size_t count) {
                    const std::uint32_t* t = p.tets.data() + 4 * first;
                    return plain_det_positive(p.in.data(), t, count) + plain_det_positive(p.out.data(), t, count);
                  });
                }, {}});
#ifdef VOLMAP_HAVE_CGAL
  cs.push_back({"epick", [&p, nt, threads] {
                  return split_tets(nt, threads, [&](std::size_t first, std::size_t count) {
                    long positive = 0;
                    for (std::size_t k = first; k < first + count; ++k) {
                      const std::uint32_t* v = &p.tets[4 * k];
                      positive += CGAL::orientation(p.in_pts[v[0]], p.in_pts[v[1]], p.in_pts[v[2]], p.in_pts[v[3]]) < 0;
                      positive += CGAL::orientation(p.out_pts[v[0]], p.out_pts[v[1]], p.out_pts[v[2]], p.out_pts[v[3]]) < 0;
                    }
                    return positive;
                  });
                }, {}});
#endif
  run_anchored(state, cs, 2.0 * double(nt), threads > 1);
  state.counters["tets"] = double(nt);
}
BENCHMARK(anchor_map_check_core)->Arg(1)->Arg(2)->MinTime(2.0)->UseRealTime();

// Start-up sanity: the contenders agree with volmap on the data sets (wrong signs counted for naive).
void sanity() {
  long naive_wrong = 0;
  const Tuples& t = tuples(Set::NearDegenerate, 3, 4);
  for (int i = 0; i < kTuples; ++i) {
    const int s = volmap::orient3d(t.p(i, 0), t.p(i, 1), t.p(i, 2), t.p(i, 3));
    naive_wrong += or_::naive_sign(naive_o3(t.p(i, 0), t.p(i, 1), t.p(i, 2), t.p(i, 3))) != s;
#ifdef VOLMAP_HAVE_CGAL
    const auto& c = cgal_tuples(Set::NearDegenerate, 3, 4);
    if (-int(CGAL::orientation(c.p3[i * 5], c.p3[i * 5 + 1], c.p3[i * 5 + 2], c.p3[i * 5 + 3])) != s) {
      std::fprintf(stderr, "bench_predicates: CGAL and volmap disagree on orient3d tuple %d\n", i);
      std::exit(1);
    }
#endif
  }
#ifdef VOLMAP_HAVE_CGAL
  const Tuples& ic = tuples(Set::NearDegenerate, 2, 4);
  const auto& c2 = cgal_tuples(Set::NearDegenerate, 2, 4);
  for (int i = 0; i < kTuples; ++i)
    if (int(CGAL::side_of_oriented_circle(c2.p2[i * 5], c2.p2[i * 5 + 1], c2.p2[i * 5 + 2], c2.p2[i * 5 + 3])) !=
        volmap::incircle(ic.p(i, 0), ic.p(i, 1), ic.p(i, 2), ic.p(i, 3))) {
      std::fprintf(stderr, "bench_predicates: CGAL and volmap disagree on incircle tuple %d\n", i);
      std::exit(1);
    }
  const Tuples& is = tuples(Set::NearDegenerate, 3, 5);
  const auto& c3 = cgal_tuples(Set::NearDegenerate, 3, 5);
  for (int i = 0; i < kTuples; ++i)
    if (-int(CGAL::side_of_oriented_sphere(c3.p3[i * 5], c3.p3[i * 5 + 1], c3.p3[i * 5 + 2], c3.p3[i * 5 + 3],
                                          c3.p3[i * 5 + 4])) !=
        volmap::insphere(is.p(i, 0), is.p(i, 1), is.p(i, 2), is.p(i, 3), is.p(i, 4))) {
      std::fprintf(stderr, "bench_predicates: CGAL and volmap disagree on insphere tuple %d\n", i);
      std::exit(1);
    }
#endif
  std::printf("near-coplanar orient3d set: naive double wrong on %ld / %d; volmap%s agree\n", naive_wrong, kTuples,
#ifdef VOLMAP_HAVE_CGAL
              " and CGAL Epick"
#else
              ""
#endif
  );
  for (int v = 1; v <= 2; ++v)
    std::printf("Kuhn grid variant %d: %zu tets, %zu exactly flat\n", v, mesh(v).tets.size() / 4, mesh(v).degenerate);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  sanity();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// ---- Cost of the per-call MXCSR check (predicates/src/fp_env.hpp) -------------------------------
// Every public predicate reads MXCSR (stmxcsr, mask, predicted branch) before its filter and re-enters
// the default FP environment when FTZ/DAZ/non-nearest rounding is on. Differential anchor (written
// before FpEnvironmentScope gave a check-free entry point; the direct comparison follows below), in
// the same run, on the random set (stage A decides: the path where one check weighs most):
//   mxcsr_orient3d_1check   volmap::orient3d as shipped (its own check)
//   mxcsr_orient3d_2checks  the same call behind one more, identical, caller-side check
//   mxcsr_check_only        the check alone in the loop (plus the loop's own load/add)
// cost of one check ≈ 2checks − 1check; overhead of the check in orient3d ≈ cost / (1check − cost).
#if defined(__SSE2__)
#include <xmmintrin.h>
namespace {
inline bool mxcsr_is_default() { return (_mm_getcsr() & 0xE040u) == 0u; }  // fp_env.hpp's test
void mxcsr_orient3d_1check(benchmark::State& state) {
  run_scalar(state, tuples(Set::Random, 3, 4),
             [](const Tuples& t, int i) { return long(volmap::orient3d(P(0), P(1), P(2), P(3))); });
}
void mxcsr_orient3d_2checks(benchmark::State& state) {
  run_scalar(state, tuples(Set::Random, 3, 4), [](const Tuples& t, int i) {
    return __builtin_expect(mxcsr_is_default(), 1) ? long(volmap::orient3d(P(0), P(1), P(2), P(3))) : 7L;
  });
}
void mxcsr_check_only(benchmark::State& state) {
  run_scalar(state, tuples(Set::Random, 3, 4),
             [](const Tuples& t, int i) { return long(mxcsr_is_default()) + long(P(0)[0] > 0.0); });
}
BENCHMARK(mxcsr_orient3d_1check);
BENCHMARK(mxcsr_orient3d_2checks);
BENCHMARK(mxcsr_check_only);
}  // namespace
#endif

// ---- Checked free functions vs one FpEnvironmentScope + its unchecked members --------------------
//   mxcsr_<pred>_<set>_checked  volmap::<pred> (one MXCSR check per call)
//   mxcsr_<pred>_<set>_scope    volmap::FpEnvironmentScope fp (once, outside the timed loop); fp.<pred>
//   mxcsr_ratio_<pred>_<set>    both in the same run, interleaved in blocks of 4096 calls timed with
//                               steady_clock: counters checked_ns, scope_ns and ratio = checked/scope.
#include <chrono>
namespace {
#define VOLMAP_SCOPE_BENCH(name, set, dim, npts, checked_expr, scope_expr)                                 \
  void name##_checked(benchmark::State& state) {                                                          \
    run_scalar(state, tuples(set, dim, npts), [](const Tuples& t, int i) { return long(checked_expr); });  \
  }                                                                                                       \
  void name##_scope(benchmark::State& state) {                                                            \
    const volmap::FpEnvironmentScope fp;                                                                  \
    run_scalar(state, tuples(set, dim, npts), [&fp](const Tuples& t, int i) { return long(scope_expr); }); \
  }                                                                                                       \
  void name##_ratio(benchmark::State& state) {                                                            \
    const Tuples& t = tuples(set, dim, npts);                                                             \
    using clock = std::chrono::steady_clock;                                                              \
    double checked_s = 0, scope_s = 0;                                                                    \
    long acc = 0;                                                                                         \
    for (auto _ : state) {                                                                                \
      const auto t0 = clock::now();                                                                       \
      for (int i = 0; i < kTuples; ++i) acc += long(checked_expr);                                        \
      const auto t1 = clock::now();                                                                       \
      {                                                                                                   \
        const volmap::FpEnvironmentScope fp;                                                              \
        for (int i = 0; i < kTuples; ++i) acc += long(scope_expr);                                        \
      }                                                                                                   \
      const auto t2 = clock::now();                                                                       \
      checked_s += std::chrono::duration<double>(t1 - t0).count();                                        \
      scope_s += std::chrono::duration<double>(t2 - t1).count();                                          \
    }                                                                                                     \
    benchmark::DoNotOptimize(acc);                                                                        \
    const double calls = double(state.iterations()) * kTuples;                                            \
    state.counters["checked_ns"] = 1e9 * checked_s / calls;                                               \
    state.counters["scope_ns"] = 1e9 * scope_s / calls;                                                   \
    state.counters["ratio"] = scope_s > 0 ? checked_s / scope_s : 0.0;                                    \
  }                                                                                                       \
  BENCHMARK(name##_checked);                                                                              \
  BENCHMARK(name##_scope);                                                                                \
  BENCHMARK(name##_ratio)

VOLMAP_SCOPE_BENCH(mxcsr_orient3d_random, Set::Random, 3, 4, volmap::orient3d(P(0), P(1), P(2), P(3)),
                   fp.orient3d(P(0), P(1), P(2), P(3)));
VOLMAP_SCOPE_BENCH(mxcsr_orient3d_neardeg, Set::NearDegenerate, 3, 4, volmap::orient3d(P(0), P(1), P(2), P(3)),
                   fp.orient3d(P(0), P(1), P(2), P(3)));
VOLMAP_SCOPE_BENCH(mxcsr_orient2d_random, Set::Random, 2, 3, volmap::orient2d(P(0), P(1), P(2)),
                   fp.orient2d(P(0), P(1), P(2)));
VOLMAP_SCOPE_BENCH(mxcsr_insphere_random, Set::Random, 3, 5, volmap::insphere(P(0), P(1), P(2), P(3), P(4)),
                   fp.insphere(P(0), P(1), P(2), P(3), P(4)));

// Cost of entering and leaving a scope (default environment: one stmxcsr, no ldmxcsr).
void mxcsr_scope_enter_exit(benchmark::State& state) {
  for (auto _ : state) {
    volmap::FpEnvironmentScope fp;
    benchmark::DoNotOptimize(&fp);
  }
}
BENCHMARK(mxcsr_scope_enter_exit);
}  // namespace
