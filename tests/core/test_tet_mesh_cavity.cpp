// TetMesh::replace_cavity: random ball cavities of Kuhn grids (grown from a vertex star while every
// cavity boundary face stays strictly visible from the star's centre, so the cavity is star-shaped
// and a ball) replaced by the cones from an interior point — with a new apex (the cavity's interior
// vertices deleted) or with the centre vertex kept as apex. Oracles: check_invariants with exact
// positivity, the adjacency equal to a from-scratch rebuild, the oriented mesh boundary unchanged
// (brute-force face map), counts, slot reuse, labels and properties from the named parents; fills
// that do not close onto the cavity are refused with the mesh bit-identical.
#include <doctest/doctest.h>

#include <volmap/core/error.hpp>
#include <volmap/core/properties.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/predicates.hpp>
#include <volmap/testing/generate.hpp>

#include "mesh_test_util.hpp"

#include <algorithm>
#include <map>
#include <random>
#include <set>

using namespace volmap;

namespace {

using Triple = std::array<std::uint32_t, 3>;

void require_ok(const TetMesh& m) {
  const InvariantReport r = m.check_invariants(true);
  INFO(r.problem);
  REQUIRE(r.ok);
}

// The adjacency after edits equals the one TetMesh builds from scratch from the live tets
// (to_data() renumbers survivors in slot order): every opp entry and every vertex's boundary flag.
void require_adjacency_as_rebuilt(const TetMesh& m) {
  const TetMesh rebuilt(m.to_data());
  std::vector<std::uint32_t> tet_id(m.num_tet_slots(), kInvalidIndex), vertex_id(m.num_vertex_slots(), kInvalidIndex);
  std::uint32_t nt = 0, nv = 0;
  for (std::uint32_t t = 0; t < m.num_tet_slots(); ++t)
    if (m.tet_is_live(TetId(t))) tet_id[t] = nt++;
  for (std::uint32_t v = 0; v < m.num_vertex_slots(); ++v)
    if (m.vertex_is_live(VertexId(v))) vertex_id[v] = nv++;
  REQUIRE(rebuilt.num_tets() == nt);
  REQUIRE(rebuilt.num_vertices() == nv);
  std::size_t wrong_opp = 0, wrong_boundary = 0;
  for (std::uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (tet_id[t] == kInvalidIndex) continue;
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t o = m.opposite_array()[4 * std::size_t(t) + i];
      const std::uint32_t expected = o == TetMesh::kBoundary ? TetMesh::kBoundary : 4 * tet_id[o >> 2] + (o & 3);
      if (rebuilt.opposite_array()[4 * std::size_t(tet_id[t]) + i] != expected) ++wrong_opp;
    }
  }
  for (std::uint32_t v = 0; v < m.num_vertex_slots(); ++v)
    if (vertex_id[v] != kInvalidIndex && m.vertex_is_boundary(VertexId(v)) != rebuilt.vertex_is_boundary(VertexId(vertex_id[v])))
      ++wrong_boundary;
  CHECK(wrong_opp == 0);
  CHECK(wrong_boundary == 0);
}

// The outward face (local i) of tet t, as vertex ids.
std::array<VertexId, 3> face_of(const TetMesh& m, TetId t, int i) { return m.half_face_vertices(HalfFaceId(t, i)); }

bool sees_strictly(const TetMesh& m, TetId t, int i, const double* p) {
  const auto f = face_of(m, t, i);
  return orient3d(m.vertex_position(f[0]), m.vertex_position(f[1]), m.vertex_position(f[2]), p) > 0;
}

// A cavity grown from the star of interior vertex c: tets behind boundary faces are added in random
// order as long as every boundary face of the grown set is strictly visible from c's position.
std::vector<TetId> grow_star_shaped_cavity(const TetMesh& m, VertexId c, std::size_t extra, std::mt19937& rng) {
  std::vector<TetId> cavity;
  m.vertex_star(c, cavity);
  std::set<std::uint32_t> in;
  for (TetId t : cavity) in.insert(t.idx());
  const double* p = m.vertex_position(c);
  auto all_visible = [&](const std::set<std::uint32_t>& s) {
    for (std::uint32_t t : s)
      for (int i = 0; i < 4; ++i) {
        const HalfFaceId o = m.half_face_opposite(HalfFaceId(TetId(t), i));
        if ((!o.is_valid() || !s.count(o.tet().idx())) && !sees_strictly(m, TetId(t), i, p)) return false;
      }
    return true;
  };
  const std::size_t target = in.size() + extra;
  for (std::size_t tries = 0; tries < 8 * extra && in.size() < target; ++tries) {
    std::vector<TetId> behind;
    for (std::uint32_t t : in)
      for (int i = 0; i < 4; ++i) {
        const HalfFaceId o = m.half_face_opposite(HalfFaceId(TetId(t), i));
        if (o.is_valid() && !in.count(o.tet().idx())) behind.push_back(o.tet());
      }
    if (behind.empty()) break;
    const TetId t = behind[std::uniform_int_distribution<std::size_t>(0, behind.size() - 1)(rng)];
    auto grown = in;
    grown.insert(t.idx());
    if (all_visible(grown)) in = std::move(grown);
  }
  cavity.assign(in.size(), TetId::kInvalid);
  std::transform(in.begin(), in.end(), cavity.begin(), [](std::uint32_t t) { return TetId(t); });
  std::shuffle(cavity.begin(), cavity.end(), rng);  // the caller's order decides slot reuse
  return cavity;
}

// Cones from `apex` over the cavity's boundary faces; each cone's parent is the tet whose face it covers.
std::vector<CavityTet> cones(const TetMesh& m, const std::vector<TetId>& cavity, VertexId apex) {
  std::set<std::uint32_t> in;
  for (TetId t : cavity) in.insert(t.idx());
  std::vector<CavityTet> fill;
  for (TetId t : cavity)
    for (int i = 0; i < 4; ++i) {
      const HalfFaceId o = m.half_face_opposite(HalfFaceId(t, i));
      if (o.is_valid() && in.count(o.tet().idx())) continue;
      const auto f = face_of(m, t, i);
      fill.push_back({{f[0], f[1], f[2], apex}, t});
    }
  return fill;
}

// Everything a refused edit must leave as it was.
struct Snapshot {
  explicit Snapshot(const TetMesh& m, const TetProperty<int>& tag, const VertexProperty<double>& weight)
      : tv(m.tet_vertex_array()), opp(m.opposite_array()), v2h(m.vertex_half_face_array()), xyz(m.positions()),
        tet_labels(m.tet_labels()), vertex_labels(m.vertex_labels()), tags(tag.data()), weights(weight.data()),
        version(m.topology_version()), live_tets(m.num_tets()), live_vertices(m.num_vertices()), free_slots(m.num_free_tet_slots()) {}
  bool operator==(const Snapshot& o) const {
    return tv == o.tv && opp == o.opp && v2h == o.v2h && xyz == o.xyz && tet_labels == o.tet_labels &&
           vertex_labels == o.vertex_labels && tags == o.tags && weights == o.weights && version == o.version &&
           live_tets == o.live_tets && live_vertices == o.live_vertices && free_slots == o.free_slots;
  }
  std::vector<std::uint32_t> tv, opp, v2h;
  std::vector<double> xyz;
  std::vector<std::int32_t> tet_labels, vertex_labels;
  std::vector<int> tags;
  std::vector<double> weights;
  std::uint64_t version;
  std::size_t live_tets, live_vertices, free_slots;
};

}  // namespace

TEST_CASE("replace_cavity: random star-shaped ball cavities of a Kuhn grid replaced by cones from an interior point") {
  // A 5^3 Kuhn grid with jittered interior vertices (general position: no coplanar faces that would
  // stop the visibility-driven growth early), every tet still positive.
  TetMeshData data = generate_kuhn_grid(5, 5, 5);
  for (std::size_t t = 0; t < data.num_tets(); ++t) data.tet_labels[t] = std::int32_t(1000 + t);
  {
    std::mt19937 jitter_rng(5);
    std::uniform_real_distribution<double> jitter(-0.2, 0.2);
    for (std::size_t v = 0; v < data.num_vertices(); ++v) {
      bool inside = true;
      for (int i = 0; i < 3; ++i) inside = inside && data.xyz[3 * v + i] > 0 && data.xyz[3 * v + i] < 5;
      if (!inside) continue;
      const std::vector<double> keep = data.xyz;
      for (int i = 0; i < 3; ++i) data.xyz[3 * v + i] += jitter(jitter_rng);
      for (std::size_t t = 0; t < data.num_tets(); ++t)
        if (mesh_test::orient_tet(data.xyz, &data.tets[4 * t]) <= 0) {
          data.xyz = keep;
          break;
        }
    }
  }
  TetMesh m(data);
  require_ok(m);
  TetProperty<int> tag(m, -1);
  VertexProperty<double> weight(m, 0.5);
  for (std::uint32_t t = 0; t < m.num_tet_slots(); ++t) tag[TetId(t)] = int(t);
  for (std::uint32_t v = 0; v < m.num_vertex_slots(); ++v) weight[VertexId(v)] = double(v);
  const std::set<Triple> boundary = mesh_test::oriented_boundary(m);
  std::mt19937 rng(20261124);
  int new_apex = 0, kept_apex = 0, deleted_total = 0;
  for (int round = 0; round < 60; ++round) {
    // A random interior vertex (the grid's interior vertices stay interior through the edits).
    std::vector<VertexId> interior;
    for (std::uint32_t v = 0; v < m.num_vertex_slots(); ++v)
      if (m.vertex_is_live(VertexId(v)) && !m.vertex_is_boundary(VertexId(v))) interior.push_back(VertexId(v));
    REQUIRE(!interior.empty());
    const VertexId c = interior[std::uniform_int_distribution<std::size_t>(0, interior.size() - 1)(rng)];
    const std::vector<TetId> cavity = grow_star_shaped_cavity(m, c, round % 7 * 8, rng);
    const bool keep_c = round % 2 == 1;
    const double p[3] = {m.vertex_position(c)[0], m.vertex_position(c)[1], m.vertex_position(c)[2]};
    const std::vector<CavityTet> fill = cones(m, cavity, keep_c ? c : CavityTet::new_vertex(0));
    // The cavity's vertices not on its boundary are deleted (all of them when the apex is new).
    std::set<std::uint32_t> cavity_vertices, kept;
    for (TetId t : cavity)
      for (VertexId v : m.tet_vertices(t)) cavity_vertices.insert(v.idx());
    for (const CavityTet& f : fill)
      for (VertexId v : f.v)
        if (v.idx() < CavityTet::kFirstNewVertex) kept.insert(v.idx());
    std::vector<std::uint32_t> dropped;
    for (std::uint32_t v : cavity_vertices)
      if (!kept.count(v)) dropped.push_back(v);
    CHECK(std::count(dropped.begin(), dropped.end(), c.idx()) == (keep_c ? 0 : 1));
    // The untouched tets and vertices, and who the fill's parents are.
    std::map<std::uint32_t, std::array<VertexId, 4>> others;
    std::set<std::uint32_t> in;
    for (TetId t : cavity) in.insert(t.idx());
    for (std::uint32_t t = 0; t < m.num_tet_slots(); ++t)
      if (m.tet_is_live(TetId(t)) && !in.count(t)) others[t] = m.tet_vertices(TetId(t));
    std::vector<int> parent_tag;
    std::vector<std::int32_t> parent_label;
    for (const CavityTet& f : fill) {
      parent_tag.push_back(tag[f.parent]);
      parent_label.push_back(m.tet_labels()[f.parent.idx()]);
    }
    const std::size_t nt = m.num_tets(), nv = m.num_vertices();
    const std::uint64_t version = m.topology_version();
    const std::vector<double> positions = keep_c ? std::vector<double>() : std::vector<double>(p, p + 3);
    const CavityReplacement r = m.replace_cavity(cavity, fill, positions);
    require_ok(m);
    require_adjacency_as_rebuilt(m);
    CHECK(m.topology_version() != version);
    CHECK(mesh_test::oriented_boundary(m) == boundary);
    CHECK(m.num_tets() == nt - cavity.size() + fill.size());
    CHECK(m.num_vertices() == nv - dropped.size() + (keep_c ? 0 : 1));
    REQUIRE(r.tets.size() == fill.size());
    REQUIRE(r.vertices.size() == (keep_c ? 0u : 1u));
    for (std::uint32_t v : dropped) CHECK_FALSE(m.vertex_is_live(VertexId(v)));
    for (std::size_t k = 0; k < fill.size(); ++k) {
      if (k < cavity.size()) CHECK(r.tets[k] == cavity[k]);  // fill k reuses cavity slot k
      const VertexId apex = keep_c ? c : r.vertices[0];
      const auto tv = m.tet_vertices(r.tets[k]);
      for (int i = 0; i < 3; ++i) CHECK(tv[i] == fill[k].v[i]);
      CHECK(tv[3] == apex);
      CHECK(tag[r.tets[k]] == parent_tag[k]);
      CHECK(m.tet_labels()[r.tets[k].idx()] == parent_label[k]);
    }
    for (std::size_t k = fill.size(); k < cavity.size(); ++k) CHECK_FALSE(m.tet_is_live(cavity[k]));
    for (const auto& [t, tv] : others) {
      CHECK(m.tet_is_live(TetId(t)));
      CHECK(m.tet_vertices(TetId(t)) == tv);
      CHECK(tag[TetId(t)] == int(t));
    }
    if (!keep_c) {
      CHECK(weight[r.vertices[0]] == 0.5);  // the default
      for (int i = 0; i < 3; ++i) CHECK(m.vertex_position(r.vertices[0])[i] == p[i]);
      weight[r.vertices[0]] = double(r.vertices[0].idx());
    }
    for (std::uint32_t v = 0; v < m.num_vertex_slots(); ++v)
      if (m.vertex_is_live(VertexId(v))) CHECK(weight[VertexId(v)] == double(v));
    // New tets get fresh tags so the next rounds can follow them too.
    for (TetId t : r.tets) tag[t] = int(t.idx());
    (keep_c ? kept_apex : new_apex) += 1;
    deleted_total += int(dropped.size());
  }
  CHECK(new_apex > 0);
  CHECK(kept_apex > 0);
  CHECK(deleted_total > new_apex);  // some grown cavities had interior vertices besides the centre
  MESSAGE("cavity rounds: " << new_apex << " with a new apex, " << kept_apex << " with the centre kept, " << deleted_total
                            << " interior vertices deleted");
  // compact() afterwards: tombstones (tets and deleted vertices) go, properties follow.
  const TetMeshData live = m.to_data();
  const CompactRemap remap = m.compact();
  require_ok(m);
  CHECK(m.num_free_tet_slots() == 0);
  CHECK(m.tet_vertex_array() == live.tets);
  CHECK(m.positions() == live.xyz);
  for (std::uint32_t v = 0; v < m.num_vertex_slots(); ++v) CHECK(weight[VertexId(v)] != 0.5);
  CHECK(mesh_test::oriented_boundary(m).size() == boundary.size());
  (void)remap;
}

TEST_CASE("replace_cavity: fills that do not close onto the cavity are refused and the mesh stays bit-identical") {
  TetMesh m(generate_kuhn_grid(3, 3, 3));
  TetProperty<int> tag(m, -1);
  VertexProperty<double> weight(m, 0.5);
  for (std::uint32_t t = 0; t < m.num_tet_slots(); ++t) tag[TetId(t)] = int(t);
  // Tombstones and free slots from an earlier edit, so refusal must keep those too.
  {
    const auto tv = m.tet_vertices(TetId(0));
    double p[3] = {0, 0, 0};
    for (VertexId v : tv)
      for (int i = 0; i < 3; ++i) p[i] += 0.25 * m.vertex_position(v)[i];
    const VertexId w = m.split_tet(TetId(0), p);
    std::vector<TetId> star;
    m.vertex_star(w, star);
    m.replace_cavity(star, cones(m, star, w));  // a 4-tet ball back to 4 tets: no change in count
    m.replace_cavity(star, {{{tv[0], tv[1], tv[2], tv[3]}, star[0]}});  // and merged back: 3 tombstones, w deleted
    require_ok(m);
    REQUIRE(m.num_free_tet_slots() == 3);
  }
  const VertexId c(1 + 4 * (1 + 4 * 1));  // grid vertex (1,1,1): interior
  REQUIRE_FALSE(m.vertex_is_boundary(c));
  std::vector<TetId> cavity;
  m.vertex_star(c, cavity);
  const std::vector<CavityTet> good = cones(m, cavity, CavityTet::new_vertex(0));
  const double p[3] = {1.0, 1.0, 1.0};
  const std::vector<double> at_p(p, p + 3);
  const Snapshot before(m, tag, weight);
  auto refused = [&](const std::vector<TetId>& cav, const std::vector<CavityTet>& fill, const std::vector<double>& pos) {
    CHECK_THROWS_AS(m.replace_cavity(cav, fill, pos), Error);
    CHECK(Snapshot(m, tag, weight) == before);
  };
  SUBCASE("a cone left out: a cavity face uncovered and two fill faces open") {
    auto fill = good;
    fill.pop_back();
    refused(cavity, fill, at_p);
  }
  SUBCASE("one cone with the opposite winding") {
    auto fill = good;
    std::swap(fill[3].v[0], fill[3].v[1]);
    refused(cavity, fill, at_p);
  }
  SUBCASE("one cone given twice") {
    auto fill = good;
    fill.push_back(fill[0]);
    refused(cavity, fill, at_p);
  }
  SUBCASE("a fill over a vertex outside the cavity") {
    auto fill = good;
    fill[0].v[3] = VertexId(0);  // the grid corner (0,0,0) is no vertex of c's star
    refused(cavity, fill, at_p);
  }
  SUBCASE("a new vertex that no fill tet uses, or a missing position") {
    refused(cavity, good, {1.0, 1.0, 1.0, 0.5, 0.5, 0.5});
    refused(cavity, good, {});
  }
  SUBCASE("a cavity with a dead tet, a repeated tet, or a parent outside it") {
    auto cav = cavity;
    cav.push_back(cav[0]);
    refused(cav, good, at_p);
    std::uint32_t dead = 0;
    while (m.tet_is_live(TetId(dead))) ++dead;
    cav = cavity;
    cav.push_back(TetId(dead));
    refused(cav, good, at_p);
    auto fill = good;
    std::uint32_t outside = 0;
    while (!m.tet_is_live(TetId(outside)) || std::count(cavity.begin(), cavity.end(), TetId(outside))) ++outside;
    fill[0].parent = TetId(outside);
    refused(cavity, fill, at_p);
  }
  SUBCASE("a fill face repeated") {
    std::uint32_t h = 0;
    while (!m.tet_is_live(HalfFaceId(h).tet()) || m.half_face_is_boundary(HalfFaceId(h))) ++h;
    const HalfFaceId o = m.half_face_opposite(HalfFaceId(h));
    const std::vector<TetId> pair = {HalfFaceId(h).tet(), o.tet()};
    std::vector<CavityTet> same = {{m.tet_vertices(pair[0]), pair[0]}, {m.tet_vertices(pair[1]), pair[1]}};
    m.replace_cavity(pair, same);  // the identity fill is accepted...
    const Snapshot identity(m, tag, weight);
    CHECK(identity.tv == before.tv);
    same.push_back(same[0]);       // ...a third copy of a tet is not
    CHECK_THROWS_AS(m.replace_cavity(pair, same), Error);
    CHECK(Snapshot(m, tag, weight) == identity);
  }
  // The good fill is accepted afterwards (the refusals really left a usable mesh).
  const CavityReplacement r = m.replace_cavity(cavity, good, at_p);
  require_ok(m);
  require_adjacency_as_rebuilt(m);
  CHECK(r.vertices.size() == 1);
  CHECK_FALSE(m.vertex_is_live(c));
}

TEST_CASE("replace_cavity: a glued fill face that is already a face outside the cavity is refused") {
  // Three tets around the edge de (through the triangle abc), and a fourth tet (a,b,c,f) outside
  // them. The 3-2 exchange of the ring would glue (a,b,c,d) and (a,b,c,e) along abc, already the
  // face of (a,b,c,f): refused. Without the fourth tet the same fill is accepted.
  auto oriented = [](const std::vector<double>& xyz, std::array<std::uint32_t, 4> t) {
    if (mesh_test::orient_tet(xyz, t.data()) < 0) std::swap(t[0], t[1]);
    return t;
  };
  const std::vector<double> xyz = {0, 0, 0, 2, 0, 0, 0, 2, 0, 0.5, 0.5, 1, 0.5, 0.5, -1, 0.5, 0.5, 2};  // a b c d e f
  const std::uint32_t a = 0, b = 1, c = 2, d = 3, e = 4, f = 5;
  const std::array<std::array<std::uint32_t, 4>, 3> ring = {{{d, e, a, b}, {d, e, b, c}, {d, e, c, a}}};
  for (bool with_outside_tet : {true, false}) {
    TetMeshData data;
    data.xyz = xyz;
    if (!with_outside_tet) data.xyz.resize(15);
    for (const auto& t : ring) {
      const auto o = oriented(data.xyz, t);
      data.tets.insert(data.tets.end(), o.begin(), o.end());
    }
    if (with_outside_tet) {
      const auto o = oriented(data.xyz, {a, b, c, f});
      data.tets.insert(data.tets.end(), o.begin(), o.end());
    }
    TetMesh m(data);
    require_ok(m);
    const std::vector<TetId> cavity = {TetId(0), TetId(1), TetId(2)};
    std::vector<CavityTet> fill;
    for (std::uint32_t apex : {d, e}) {
      const auto o = oriented(data.xyz, {a, b, c, apex});
      fill.push_back({{VertexId(o[0]), VertexId(o[1]), VertexId(o[2]), VertexId(o[3])}, TetId(0)});
    }
    if (with_outside_tet) {
      const std::vector<std::uint32_t> tv = m.tet_vertex_array(), opp = m.opposite_array();
      CHECK_THROWS_AS(m.replace_cavity(cavity, fill), Error);
      CHECK(m.tet_vertex_array() == tv);
      CHECK(m.opposite_array() == opp);
    } else {
      m.replace_cavity(cavity, fill);
      require_ok(m);
      require_adjacency_as_rebuilt(m);
      CHECK(m.num_tets() == 2);
      CHECK(m.num_free_tet_slots() == 1);
    }
  }
}
