// volmap/volume_map.hpp — the certified robust volume mapper behind `volmap-map` (docs/mapping.md).
// Pipeline: exact feasibility analysis (§3) → B0 chord splitting of blocking chords (§4, when
// refinement is allowed) → Tutte 3D initialisation (§2) → FFM untangling with regular then rest
// reference shapes (§5), or TLC (§6) → B1 cone repair of the remaining clusters (§7, when refinement
// is allowed) → validity-preserving quality pass (§5). A stage's result counts only when the exact
// check (orient3d > 0 on every tet, on the doubles returned) passes.
// Conventions: flat TetMeshData, VOLMAP-positive source tets; boundary vertices of the result are
// bit-identical to the map's doubles; with refinement the source is refined only in the interior,
// original vertex ids 0..nv−1 are kept and new vertices/tets appended.
#pragma once

#include <volmap/feasibility.hpp>
#include <volmap/mesh_data.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace volmap {

enum class MapMethod { Ffm, Tlc };

struct VolumeMapOptions {
  MapMethod method = MapMethod::Ffm;
  bool allow_refinement = true;
  double max_growth = 0.05;        // tets added / input tets allowed for refinement
  double time_limit_seconds = 0;   // 0 = none (soft: checked between and inside stages)
  bool quality_pass = true;
  int quality_iterations = 300;
  int max_threads = 0;             // 0 = TBB default; 1 = one core (benchmarks)
};

struct VolumeMapStage {
  std::string name;
  double seconds = 0;
  std::size_t nonpositive_after = 0;  // exact count after the stage
};

struct VolumeMapResult {
  TetMeshData source;               // the (possibly refined) source mesh
  std::vector<double> target_xyz;   // 3 per vertex of `source`
  std::vector<std::uint8_t> on_boundary;
  bool certified = false;           // exact check passed on target_xyz (and the source is positive)
  bool refined = false;             // source != input
  std::size_t nonpositive = 0;      // exact count at the end
  std::size_t input_tets = 0, input_vertices = 0;
  std::size_t chord_edges_split = 0, chord_faces_split = 0, cone_patches = 0;
  std::string certified_by;         // stage that produced the certified map
  FeasibilityReport feasibility;    // on the input
  std::vector<VolumeMapStage> stages;
  double seconds = 0;
  double growth() const { return input_tets ? double(source.num_tets()) / double(input_tets) - 1.0 : 0.0; }
};

// Throws Error(BadInput) when the map does not match the mesh's boundary or a source tet is not
// strictly positive.
VolumeMapResult compute_volume_map(const TetMeshData& source, const BoundaryMap& map, const VolumeMapOptions& options = {});

// Uniform-weight Tutte 3D: interior vertices at the mean of their edge neighbours, boundary fixed
// (one sparse LDLᵀ factorisation, 3 right-hand sides). Overwrites the free entries of target_xyz.
void tutte_uniform(const std::vector<std::uint32_t>& tets, const std::vector<std::uint8_t>& on_boundary,
                   std::vector<double>& target_xyz);

}  // namespace volmap
