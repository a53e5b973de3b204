// volmap-predicates-selftest — the predicate validator on built-in data (no input files).
// Generates the hard cases of predicates.md §6 (Kettner ulp grids, near-coplanar / near-cocircular /
// near-cospherical rounded points, an exponent sweep from subnormals to 2^1000, mixed magnitudes,
// exactly degenerate integer grids and a flattened Kuhn grid through the batch path), checks every
// volmap sign against an independent GMP oracle, and prints, per family, how many signs a naive
// double determinant gets wrong versus volmap. Exit 0 iff volmap is exact on every case, 1 otherwise.
// Sign convention: Shewchuk's (orient3d > 0 for VOLMAP-positive tets).
#include <volmap/predicates.hpp>

#include "../predicates/testing/oracle.hpp"
#include "support/tool_common.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace or_ = volmap_oracle;

namespace {

struct Family {
  std::string name;
  long cases = 0, naive_wrong = 0, volmap_wrong = 0;
};

struct Runner {
  std::vector<Family> families;
  Family& add(const std::string& name) {
    families.push_back({name});
    return families.back();
  }
};

void o3(Family& f, const double* a, const double* b, const double* c, const double* d) {
  const int e = or_::orient3d(a, b, c, d);
  ++f.cases;
  f.naive_wrong += or_::naive_sign(or_::naive_orient3d(a, b, c, d)) != e;
  f.volmap_wrong += volmap::orient3d(a, b, c, d) != e;
}
void o2(Family& f, const double* a, const double* b, const double* c) {
  const int e = or_::orient2d(a, b, c);
  ++f.cases;
  f.naive_wrong += or_::naive_sign(or_::naive_orient2d(a, b, c)) != e;
  f.volmap_wrong += volmap::orient2d(a, b, c) != e;
}
void ic(Family& f, const double* a, const double* b, const double* c, const double* d) {
  const int e = or_::incircle(a, b, c, d);
  ++f.cases;
  f.naive_wrong += or_::naive_sign(or_::naive_incircle(a, b, c, d)) != e;
  f.volmap_wrong += volmap::incircle(a, b, c, d) != e;
}
void is(Family& f, const double* a, const double* b, const double* c, const double* d, const double* e) {
  const int x = or_::insphere(a, b, c, d, e);
  ++f.cases;
  f.naive_wrong += or_::naive_sign(or_::naive_insphere(a, b, c, d, e)) != x;
  f.volmap_wrong += volmap::insphere(a, b, c, d, e) != x;
}

void run_all(Runner& r) {
  std::mt19937_64 rng(20231123);
  {
    Family& f = r.add("orient2d Kettner ulp grid 256x256, q=(12,12) r=(24,24)");
    const double q[2] = {12, 12}, s[2] = {24, 24};
    for (const auto& p : or_::kettner_grid(0.5, 0.5)) o2(f, p.v, q, s);
  }
  {
    Family& f = r.add("orient3d Kettner analogue: d on a ulp grid near a far plane");
    const double a[3] = {12, 7, 19}, b[3] = {-31, 5, -26}, c[3] = {40, -64, -24};
    for (const auto& d : or_::kettner_grid_3d()) o3(f, a, b, c, d.v);
  }
  {
    Family& f = r.add("orient3d near-coplanar d = fl(a + s(b-a) + t(c-a))");
    for (int i = 0; i < 20000; ++i) {
      double a[3], b[3], c[3], d[3];
      or_::near_coplanar(rng, a, b, c, d);
      o3(f, a, b, c, d);
    }
  }
  {
    Family& f = r.add("incircle near-cocircular rounded points");
    for (int i = 0; i < 20000; ++i) {
      double a[2], b[2], c[2], d[2];
      or_::near_cocircular(rng, a, b, c, d);
      ic(f, a, b, c, d);
    }
  }
  {
    Family& f = r.add("insphere near-cospherical rounded points");
    for (int i = 0; i < 5000; ++i) {
      double a[3], b[3], c[3], d[3], e[3];
      or_::near_cospherical(rng, a, b, c, d, e);
      is(f, a, b, c, d, e);
    }
  }
  for (int scale : {-1074, -1000, -500, -360, -355, -340, -300, 300, 340, 342, 345, 1000}) {
    Family& f = r.add("orient3d exponent sweep, near-coplanar and random, x 2^" + std::to_string(scale));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 2000; ++i) {
      double a[3], b[3], c[3], d[3];
      if (i % 2) or_::near_coplanar(rng, a, b, c, d);
      else
        for (int k = 0; k < 3; ++k) a[k] = u(rng), b[k] = u(rng), c[k] = u(rng), d[k] = u(rng);
      for (double* p : {a, b, c, d})
        for (int k = 0; k < 3; ++k) p[k] = std::ldexp(p[k], scale);
      o3(f, a, b, c, d);
    }
  }
  {
    Family& f = r.add("all four predicates, mixed magnitudes 1e-300 / 5e299 / subnormal / 2^1000");
    const double sub = std::numeric_limits<double>::denorm_min();
    const double pts[][3] = {{1e-300, 5e299, 0}, {5e299, 1e-300, 1e-300}, {-5e299, 0, 5e299}, {0, 0, 1e-300},
                             {sub, 1, 0},        {1, sub, sub},            {0x1p1000, 0, 0},   {0, 0x1p1000, -sub}};
    const int n = 8;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k)
          for (int l = 0; l < n; ++l) {
            o3(f, pts[i], pts[j], pts[k], pts[l]);
            o2(f, pts[i], pts[j], pts[k]);
            ic(f, pts[i], pts[j], pts[k], pts[l]);
            is(f, pts[i], pts[j], pts[k], pts[l], pts[(i + j + k + l) % n]);
          }
  }
  {
    Family& f = r.add("orient3d exactly coplanar integer grid z = 3x - 2y + 7, scaled by 2^60 in z");
    std::uniform_int_distribution<int> u(-1000, 1000);
    for (int i = 0; i < 5000; ++i) {
      double p[4][3];
      for (auto& q : p) {
        q[0] = u(rng);
        q[1] = u(rng);
        q[2] = std::ldexp(3 * q[0] - 2 * q[1] + 7, i % 2 ? 60 : 0);
      }
      o3(f, p[0], p[1], p[2], p[3]);
    }
  }
  {
    // Batch path: a 24^3 Kuhn grid (82 944 tets) whose upper half is flattened onto a tilted plane.
    Family& f = r.add("orient3d_tets: Kuhn grid 24^3 x 6, upper half flattened onto a tilted plane");
    or_::IndexedTets grid = or_::kuhn_grid(24, 1.0 / 32);  // positive tets, before the flattening
    std::vector<double>& xyz = grid.xyz;
    const std::vector<std::uint32_t>& tets = grid.tets;
    for (std::size_t v = 0; v < xyz.size() / 3; ++v) {
      double* p = &xyz[3 * v];
      p[0] += 0.1;
      p[2] = std::min(p[2], 0.375 + (p[0] + p[1]) / 3);
    }
    const std::size_t nt = tets.size() / 4;
    std::vector<std::int8_t> signs(nt);
    const auto res = volmap::orient3d_tets(xyz.data(), xyz.size() / 3, tets.data(), nt, signs.data());
    for (std::size_t t = 0; t < nt; ++t) {
      const double* p[4];
      for (int i = 0; i < 4; ++i) p[i] = &xyz[3 * tets[4 * t + i]];
      const int e = or_::orient3d(p[0], p[1], p[2], p[3]);
      ++f.cases;
      f.naive_wrong += or_::naive_sign(or_::naive_orient3d(p[0], p[1], p[2], p[3])) != e;
      f.volmap_wrong += !res.ok || signs[t] != e;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"volmap-predicates-selftest: checks the exact predicates on built-in hard cases against a GMP "
               "oracle and compares with a naive double determinant. Exit 0 iff every volmap sign is exact.",
               "volmap-predicates-selftest"};
  bool json = false;
  app.add_flag("--json", json, "print one JSON object instead of the table");
  return volmap_tools::run_tool(
      app, argc, argv,
      [&]() {
        Runner r;
        const auto t0 = std::chrono::steady_clock::now();
        run_all(r);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        long cases = 0, naive = 0, wrong = 0;
        for (const auto& f : r.families) cases += f.cases, naive += f.naive_wrong, wrong += f.volmap_wrong;
        const int code = wrong == 0 ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed;
        if (json) {
          nlohmann::json j;
          j["cases"] = cases;
          j["naive_wrong"] = naive;
          j["volmap_wrong"] = wrong;
          j["seconds"] = seconds;
          for (const auto& f : r.families)
            j["families"].push_back(
                {{"name", f.name}, {"cases", f.cases}, {"naive_wrong", f.naive_wrong}, {"volmap_wrong", f.volmap_wrong}});
          return volmap_tools::print_json(std::move(j), code);
        } else {
          std::printf("%-84s %8s %12s %12s\n", "hard-case family (oracle: GMP rationals)", "cases", "naive wrong",
                      "volmap wrong");
          for (const auto& f : r.families)
            std::printf("%-84s %8ld %12ld %12ld\n", f.name.c_str(), f.cases, f.naive_wrong, f.volmap_wrong);
          std::printf("%-84s %8ld %12ld %12ld\n", "TOTAL", cases, naive, wrong);
          std::printf("%s: %ld cases in %.2f s; naive double determinant wrong on %ld, volmap wrong on %ld\n",
                      wrong == 0 ? "PASS" : "FAIL", cases, seconds, naive, wrong);
        }
        return code;
      },
      &json);
}
