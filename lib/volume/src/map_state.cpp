// map_state.cpp — the mapper's state (validation of the input pair) and its keep-or-undo judge;
// conventions in volmap/volume/map_state.hpp.
#include <volmap/volume/map_state.hpp>

#include <volmap/core/error.hpp>

#include <volmap/predicates.hpp>

#include <cmath>
#include <string>

namespace volmap {

namespace {

[[noreturn]] void bad_input(const std::string& reason) { throw Error(ErrorKind::BadInput, "", 0, reason); }

// The checks that must pass before the half-face structure can be built.
const TetMeshData& checked_arrays(const TetMeshData& input) {
  const std::size_t nv = input.num_vertices(), nt = input.num_tets();
  if (nt == 0) bad_input("the mesh has no tets");
  if (input.tets.size() != 4 * nt || input.xyz.size() != 3 * nv) bad_input("inconsistent mesh arrays");
  for (std::uint32_t v : input.tets)
    if (v >= nv) bad_input("tet vertex id out of range");
  if (volmap::count_nonpositive(input.xyz, input.tets) != 0)
    bad_input("the source mesh has tets with orient3d <= 0 (not VOLMAP-positive)");
  return input;
}

}  // namespace

MapState::MapState(const TetMeshData& input, const BoundaryMap& map, const std::vector<double>& initial)
    : source(checked_arrays(input)), target(source), locked(source), input_vertices(input.num_vertices()), input_tets(input.num_tets()) {
  const std::size_t nv = input_vertices;
  // The map prescribes exactly the boundary vertices, each once.
  std::vector<std::uint8_t> seen(nv, 0);
  for (std::size_t k = 0; k < map.size(); ++k) {
    const std::uint32_t v = map.vids[k];
    if (v >= nv) bad_input("map vertex id " + std::to_string(v) + " out of range");
    if (!source.vertex_is_boundary(VertexId(v))) bad_input("map vertex " + std::to_string(v) + " is not a boundary vertex");
    if (seen[v]) bad_input("map vertex " + std::to_string(v) + " appears twice");
    seen[v] = 1;
    for (int i = 0; i < 3; ++i) target[VertexId(v)][i] = map.xyz[3 * k + i];
  }
  for (std::uint32_t v = 0; v < nv; ++v) {
    locked[VertexId(v)] = source.vertex_is_boundary(VertexId(v)) ? 1 : 0;
    if (locked[VertexId(v)] && !seen[v]) bad_input("boundary vertex " + std::to_string(v) + " has no prescribed position");
  }
  if (initial.empty()) return;
  if (initial.size() != 3 * nv)
    bad_input("the initial map has " + std::to_string(initial.size() / 3) + " vertices, the mesh " + std::to_string(nv));
  for (std::uint32_t v = 0; v < nv; ++v)
    if (locked[VertexId(v)])
      for (int i = 0; i < 3; ++i)
        if (initial[3 * std::size_t(v) + i] != target[VertexId(v)][i])
          bad_input("the initial map moves boundary vertex " + std::to_string(v) + " away from its prescribed position");
  for (std::size_t v = 0; v < nv; ++v)
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(initial[3 * v + i])) bad_input("the initial map has a non-finite coordinate at vertex " + std::to_string(v));
  set_target_xyz(initial);
}

std::vector<double> MapState::target_xyz() const {
  std::vector<double> xyz(3 * target.size());
  for (std::size_t v = 0; v < target.size(); ++v)
    for (int i = 0; i < 3; ++i) xyz[3 * v + i] = target.data()[v][i];
  return xyz;
}

void MapState::set_target_xyz(const std::vector<double>& xyz) {
  if (xyz.size() != 3 * target.size()) throw Error(ErrorKind::Failed, "", 0, "map state: target array of the wrong size");
  for (std::size_t v = 0; v < target.size(); ++v)
    for (int i = 0; i < 3; ++i) target.data()[v][i] = xyz[3 * v + i];
}

void MapState::require_compact() const {
  if (source.num_free_tet_slots() != 0 || source.num_vertices() != source.num_vertex_slots())
    throw Error(ErrorKind::Failed, "", 0, "map state: the source mesh holds tombstones (a stage did not compact it)");
}

std::size_t MapState::count_nonpositive() const {
  require_compact();
  return volmap::count_nonpositive(target_xyz(), source.tet_vertex_array());
}

StageJudge::StageJudge(MapState& state) : state_(state) {}
StageJudge::~StageJudge() = default;

void StageJudge::restore_best() {
  if (!best_mesh_) throw Error(ErrorKind::Failed, "", 0, "StageJudge: no state judged yet to restore");
  if (state_.source.topology_version() != best_version_) state_.source = *best_mesh_;  // resets the properties...
  state_.target.data() = best_target_;                                                // ...restored here
  state_.locked.data() = best_locked_;
  best_version_ = state_.source.topology_version();
}

StageVerdict StageJudge::judge() {
  StageVerdict v;
  v.measured = state_.count_nonpositive();
  if (best_bad_ != std::size_t(-1) && v.measured > best_bad_) {
    restore_best();
    v.kept = best_bad_;
    v.undone = true;
    return v;
  }
  best_bad_ = v.measured;
  if (!best_mesh_ || state_.source.topology_version() != best_version_) best_mesh_ = std::make_unique<TetMesh>(state_.source);
  best_version_ = state_.source.topology_version();
  best_target_ = state_.target.data();
  best_locked_ = state_.locked.data();
  v.kept = v.measured;
  return v;
}

}  // namespace volmap
