// steiner_free_fill.cpp — the advancing-front search of steiner_free_fill.hpp (docs/mapping.md §4.1).
// The front holds the oriented faces that still need a tet on their positive side; a tet (f, v) on
// front face f is admissible when it is positive in both spaces, holds no other vertex (closed tet,
// both spaces), and each of its three other faces is either on the front facing it (then both
// close) or new (then it joins the front reversed). A face closed once may not be used again.
#include <volmap/volume/steiner_free_fill.hpp>

#include <volmap/core/error.hpp>
#include <volmap/core/local_tables.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/chord_rules.hpp>

#include <algorithm>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace volmap {

namespace {

using Face = std::array<std::uint32_t, 3>;
using Tet = std::array<std::uint32_t, 4>;

constexpr std::uint32_t kIdBits = 21;  // face keys pack three ids

std::uint64_t face_key(Face f) {
  std::sort(f.begin(), f.end());
  return (std::uint64_t(f[0]) << (2 * kIdBits)) | (std::uint64_t(f[1]) << kIdBits) | f[2];
}

// The key with the orientation: even when f is a rotation of its sorted order.
std::uint64_t oriented_key(const Face& f) {
  const bool even = (f[0] < f[1]) + (f[1] < f[2]) + (f[2] < f[0]) == 2;
  return 2 * face_key(f) + (even ? 1 : 0);
}

bool same_orientation(const Face& f, const Face& g) { return oriented_key(f) == oriented_key(g); }

Face reversed(const Face& f) { return {f[0], f[2], f[1]}; }

// A 64-bit mixer (splitmix64's finaliser).
std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Face i of tet t in the outward order: t lies on its positive side.
Face tet_face(const Tet& t, int i) { return {t[kTetFace[i][0]], t[kTetFace[i][1]], t[kTetFace[i][2]]}; }

class FillSearch {
 public:
  FillSearch(const std::vector<Face>& faces, const double* source, const double* target, std::size_t num_vertices,
             const SteinerFreeFillLimits& limits, const std::vector<std::uint32_t>& required,
             const std::vector<std::uint32_t>& optional)
      : source_(source), target_(target), limits_(limits), clock_(limits.time_limit_seconds),
        bound_(limits.max_tets ? limits.max_tets : std::numeric_limits<std::size_t>::max()) {
    auto check = [&](std::uint32_t v) {
      if (v >= num_vertices || v >= (1u << kIdBits)) throw Error(ErrorKind::BadInput, "", 0, "vertex id out of range");
      return v;
    };
    for (const Face& f : faces)
      for (std::uint32_t v : f) blocking_.push_back(check(v));
    for (std::uint32_t v : required) blocking_.push_back(check(v));
    std::sort(blocking_.begin(), blocking_.end());
    blocking_.erase(std::unique(blocking_.begin(), blocking_.end()), blocking_.end());
    vertices_ = blocking_;
    for (std::uint32_t v : optional) vertices_.push_back(check(v));
    std::sort(vertices_.begin(), vertices_.end());
    vertices_.erase(std::unique(vertices_.begin(), vertices_.end()), vertices_.end());
    for (const Face& f : faces)
      if (!front_.emplace(face_key(f), f).second) throw Error(ErrorKind::BadInput, "", 0, "a face is listed twice");
  }

  SteinerFreeFillResult run() {
    if (!front_.empty()) search();
    SteinerFreeFillResult r;
    r.found = !best_.empty();
    r.exhausted = !stopped_ && (best_.empty() || limits_.minimise);
    r.optimal = r.found && r.exhausted;
    r.nodes = nodes_;
    for (const Tet& t : best_) r.tets.insert(r.tets.end(), t.begin(), t.end());
    return r;
  }

 private:
  const double* source_;
  const double* target_;
  SteinerFreeFillLimits limits_;
  TimeBudget clock_;
  std::vector<std::uint32_t> vertices_;  // every vertex a tet may use
  std::vector<std::uint32_t> blocking_;  // the surface's and the required ones: no tet may hold one
  std::unordered_map<std::uint64_t, Face> front_;  // face key -> the orientation that needs a tet
  std::unordered_set<std::uint64_t> closed_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> apexes_;  // oriented key -> geometric candidates
  std::vector<Tet> placed_, best_;
  std::size_t bound_;  // a fill needs fewer tets than this
  std::size_t nodes_ = 0;
  bool stopped_ = false;
  const FpEnvironmentScope fp_;

  const double* src(std::uint32_t v) const { return source_ + 3 * std::size_t(v); }
  const double* tgt(std::uint32_t v) const { return target_ + 3 * std::size_t(v); }

  bool out_of_budget() {
    if (!stopped_ && (nodes_ >= limits_.max_nodes || ((nodes_ & 63) == 0 && clock_.expired()))) stopped_ = true;
    return stopped_;
  }

  // No blocking vertex other than t's lies in the closed tet t (positive) with positions `xyz`. A
  // closed fill cannot have one (by the degree argument every point of the solid is in exactly one
  // tet or on a face), so for surface vertices this only prunes, and for required ones it makes a
  // closed fill use them. Optional points are not tested: an unused one may lie anywhere.
  bool holds_no_vertex(const Tet& t, const double* xyz) const {
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = hi[k] = xyz[3 * std::size_t(t[0]) + k];
      for (int i = 1; i < 4; ++i) {
        lo[k] = std::min(lo[k], xyz[3 * std::size_t(t[i]) + k]);
        hi[k] = std::max(hi[k], xyz[3 * std::size_t(t[i]) + k]);
      }
    }
    for (std::uint32_t w : blocking_) {
      if (w == t[0] || w == t[1] || w == t[2] || w == t[3]) continue;
      const double* p = xyz + 3 * std::size_t(w);
      if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] || p[2] > hi[2]) continue;
      bool inside = true;
      for (int i = 0; i < 4 && inside; ++i) {
        const Face f = tet_face(t, i);
        inside = fp_.orient3d(xyz + 3 * std::size_t(f[0]), xyz + 3 * std::size_t(f[1]), xyz + 3 * std::size_t(f[2]), p) >= 0;
      }
      if (inside) return false;
    }
    return true;
  }

  // The vertices v for which (f, v) is positive in both spaces and holds no other vertex (cached).
  const std::vector<std::uint32_t>& geometric_apexes(const Face& f) {
    auto [it, fresh] = apexes_.try_emplace(oriented_key(f));
    if (!fresh) return it->second;
    for (std::uint32_t v : vertices_) {
      if (v == f[0] || v == f[1] || v == f[2]) continue;
      if (fp_.orient3d(src(f[0]), src(f[1]), src(f[2]), src(v)) <= 0) continue;
      if (fp_.orient3d(tgt(f[0]), tgt(f[1]), tgt(f[2]), tgt(v)) <= 0) continue;
      const Tet t{f[0], f[1], f[2], v};
      if (holds_no_vertex(t, source_) && holds_no_vertex(t, target_)) it->second.push_back(v);
    }
    return it->second;
  }

  // -1 when (f, v) cannot be placed now; otherwise how many of its three other faces close.
  int closes(const Face& f, std::uint32_t v) const {
    const Tet t{f[0], f[1], f[2], v};
    int matched = 0;
    for (int i = 0; i < 3; ++i) {  // faces opposite f[i]: the three that hold v
      const Face g = tet_face(t, i);
      const std::uint64_t k = face_key(g);
      if (closed_.count(k)) return -1;
      const auto it = front_.find(k);
      if (it == front_.end()) continue;
      if (!same_orientation(it->second, g)) return -1;  // t would lie where a tet (or the outside) already is
      ++matched;
    }
    return matched;
  }

  struct Choice {
    Face face;
    std::vector<std::pair<int, std::uint32_t>> apexes;  // (faces closed, v)
  };

  // The front face with the fewest placeable tets; its tets, most faces closed first, then the
  // best shape in the worse of the two spaces.
  bool most_constrained(Choice& best) {
    std::size_t fewest = std::numeric_limits<std::size_t>::max();
    std::uint64_t best_rank = 0;
    std::vector<std::pair<int, std::uint32_t>> options;
    std::size_t scanned = 0;
    for (const auto& [key, f] : front_) {
      // A large front's first scan computes every face's candidates: the clock is read within it.
      if ((++scanned & 63) == 0 && limits_.time_limit_seconds > 0 && clock_.expired()) {
        stopped_ = true;
        return false;
      }
      options.clear();
      for (std::uint32_t v : geometric_apexes(f)) {
        const int m = closes(f, v);
        if (m >= 0) options.push_back({m, v});
        if (options.size() > fewest) break;
      }
      // Ties go to the lowest rank, a hash of the face and the seed: the same choice whatever the
      // order of the front's table, and another one for another seed.
      const std::uint64_t rank = mix(key ^ limits_.seed);
      if (options.size() < fewest || (options.size() == fewest && rank < best_rank)) {
        fewest = options.size();
        best_rank = rank;
        best.face = f;
        best.apexes = options;
        if (fewest == 0) break;
      }
    }
    if (fewest == 0) return false;
    auto shape = [&](std::uint32_t v) {
      const Face& f = best.face;
      return std::min(tet_shape(src(f[0]), src(f[1]), src(f[2]), src(v)), tet_shape(tgt(f[0]), tgt(f[1]), tgt(f[2]), tgt(v)));
    };
    std::vector<std::tuple<int, double, std::uint32_t>> ranked;
    for (auto [m, v] : best.apexes) ranked.emplace_back(m, shape(v), v);
    std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
      return std::get<0>(a) != std::get<0>(b) ? std::get<0>(a) > std::get<0>(b) : std::get<1>(a) > std::get<1>(b);
    });
    best.apexes.clear();
    for (const auto& [m, s, v] : ranked) best.apexes.push_back({m, v});
    return true;
  }

  // Places (f, v); returns the faces that joined the front (to undo).
  std::vector<std::uint64_t> place(const Face& f, std::uint32_t v) {
    const Tet t{f[0], f[1], f[2], v};
    std::vector<std::uint64_t> added;
    front_.erase(face_key(f));
    closed_.insert(face_key(f));
    for (int i = 0; i < 3; ++i) {
      const Face g = tet_face(t, i);
      const std::uint64_t k = face_key(g);
      if (front_.erase(k)) {
        closed_.insert(k);
      } else {
        front_.emplace(k, reversed(g));
        added.push_back(k);
      }
    }
    placed_.push_back(t);
    return added;
  }

  void undo(const Face& f, std::uint32_t v, const std::vector<std::uint64_t>& added) {
    const Tet t{f[0], f[1], f[2], v};
    placed_.pop_back();
    for (int i = 2; i >= 0; --i) {
      const Face g = tet_face(t, i);
      const std::uint64_t k = face_key(g);
      if (std::find(added.begin(), added.end(), k) != added.end()) {
        front_.erase(k);
      } else {
        closed_.erase(k);
        front_.emplace(k, g);
      }
    }
    closed_.erase(face_key(f));
    front_.emplace(face_key(f), f);
  }

  void search() {
    if (front_.empty()) {
      best_ = placed_;  // fewer tets than the bound, which it becomes
      bound_ = best_.size();
      return;
    }
    // A tet closes at most four front faces: at least ceil(|front| / 4) more are needed.
    if (placed_.size() + (front_.size() + 3) / 4 >= bound_) return;
    if (out_of_budget()) return;
    Choice choice;
    if (!most_constrained(choice)) return;
    for (const auto& [m, v] : choice.apexes) {
      ++nodes_;
      const auto added = place(choice.face, v);
      search();
      undo(choice.face, v, added);
      if ((!best_.empty() && !limits_.minimise) || out_of_budget()) return;
    }
  }
};

}  // namespace

SteinerFreeFillResult fill_without_steiner_points(const std::vector<std::array<std::uint32_t, 3>>& faces,
                                                  const double* source_xyz, const double* target_xyz,
                                                  std::size_t num_vertices, const SteinerFreeFillLimits& limits,
                                                  const std::vector<std::uint32_t>& required,
                                                  const std::vector<std::uint32_t>& optional) {
  FillSearch search(faces, source_xyz, target_xyz, num_vertices, limits, required, optional);
  return search.run();
}

}  // namespace volmap
