// volmap/volume/map_state.hpp — the state every stage of the volume mapper works on, and the one
// rule that judges them (docs/mapping.md §8).
// MapState: the source TetMesh (refined in place, interior only, by B0/B1), the target position of
// every vertex and the locked mask as vertex properties (they follow every edit: new vertices start
// unlocked at (0,0,0) until the stage that made them places them), and the input's sizes. Locked
// vertices (the boundary) carry the boundary map's doubles and are never moved.
// Flat arrays for the untanglers (FFM, TLC, Tutte, link kernel) come from the compacted mesh:
// stages that edit the mesh compact() it before they return. Input vertex ids 0..input_vertices-1
// never change (edits delete no vertex; new ones are appended).
// StageJudge: after a stage, the exact number of non-positive target tets; a stage that makes it
// worse than the best state so far is undone (mesh, target and locked restored), otherwise the
// current state becomes the best one. A stage that throws is undone the same way (restore_best).
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/core/properties.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace volmap {

struct MapState {
  // Validates the pair and builds the state: the map must prescribe exactly the boundary vertices
  // (each once); every source tet must be strictly positive; `initial` (3 doubles per input vertex,
  // or empty) is a starting map whose boundary entries equal the map's doubles bit-exactly. Interior
  // targets start at `initial`, or at (0,0,0). Throws Error(BadInput) naming the first problem.
  MapState(const TetMeshData& input, const BoundaryMap& map, const std::vector<double>& initial = {});
  MapState(const MapState&) = delete;
  MapState& operator=(const MapState&) = delete;

  TetMesh source;
  PositionProperty target;
  VertexProperty<std::uint8_t> locked;
  std::size_t input_vertices = 0, input_tets = 0;

  // Targets as a flat array (3 doubles per vertex) and back; the mesh must have no tombstones.
  std::vector<double> target_xyz() const;
  void set_target_xyz(const std::vector<double>& xyz);
  // Throws Error(Failed) when the mesh holds tombstones (a stage forgot to compact()).
  void require_compact() const;
  // Exact number of tets with orient3d(target) <= 0.
  std::size_t count_nonpositive() const;
};

// A stage's verdict: the exact count the stage left, the count of the state kept, and whether the
// stage was undone.
struct StageVerdict {
  std::size_t measured = 0;
  std::size_t kept = 0;
  bool undone = false;
};

class StageJudge {
 public:
  explicit StageJudge(MapState& state);
  ~StageJudge();
  // Judges the state as the last stage left it (see the file comment).
  StageVerdict judge();
  // Restores the best state unconditionally (a stage that threw may have left a partial edit).
  // Before the first judge() there is nothing to restore: throws Error(Failed).
  void restore_best();
  // The count of the best state so far (SIZE_MAX before the first judge()).
  std::size_t best() const { return best_bad_; }

 private:
  MapState& state_;
  std::size_t best_bad_ = std::size_t(-1);
  std::uint64_t best_version_ = 0;                // topology version the saved state belongs to
  std::vector<std::array<double, 3>> best_target_;
  std::vector<std::uint8_t> best_locked_;
  std::unique_ptr<TetMesh> best_mesh_;            // saved when a stage changed the topology
};

}  // namespace volmap
