// tools/support/view_export.hpp — packs a tet mesh / volume map / boundary map and its per-tet figures into
// ONE self-contained HTML page (volmap-view): the data as one base64 blob of little-endian typed
// arrays plus a small JSON header, and the viewer bundle (viewer/dist/viewer.js, three.js inside)
// inlined. The page needs no server and no network (works from file://).
//
// Conventions: vertex ids 0-based; tets 4 ids each in file order (VOLMAP-positive means
// orient3d(v0,v1,v2,v3) > 0, volmap-reference.md §1). Per-tet flags are decided by the caller with
// exact predicates; the browser only displays them. Volumes are signed with the VOLMAP convention
// (positive for VOLMAP-positive tets). Page format: "volmap-view-1" (see viewer/src/data.js).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

enum class ViewMode {
  Mesh,         // one tet mesh
  VolumeMap,    // source mesh + target (same tets, moved vertices)
  BoundaryMap   // source mesh + mapped positions of its boundary vertices only
};

// Per-tet flag bits (exact, from volmap predicates).
// VolumeMap: relative to the source tet, as VOLMAP's volume_mapping_check (for the usual
// VOLMAP-positive sources: orient3d(mapped tet) < 0 / == 0). Mesh and BoundaryMap: the tet itself.
constexpr std::uint8_t kViewInverted = 1;           // orientation flipped (Mesh: orient3d < 0)
constexpr std::uint8_t kViewDegenerate = 2;         // zero orientation (mapped or source tet)
constexpr std::uint8_t kViewSourceNonPositive = 4;  // orient3d(source tet) <= 0

// One per-tet scalar shown in the viewer (an energy, a quality measure).
struct ViewField {
  std::string key;    // e.g. "mips3d"
  std::string label;  // e.g. "MIPS3D"
  double lower = 0;   // display clamp: non-finite -> upper, then clamp to [lower, upper]
  double upper = 1;
  bool worse_high = true;  // energies: high is bad; quality 3r/R: low is bad
  bool valid_only = true;  // figures/histogram only over tets not flagged inverted/degenerate
  bool volume_weighted = true;  // weighted mean by |target volume| (Mesh/BoundaryMap: |source volume|)
  std::vector<double> values;   // one per tet, raw (may be inf/NaN)
};

struct ViewData {
  ViewMode mode = ViewMode::Mesh;
  std::string title;
  std::string source_name;
  std::string target_name;                 // output mesh or boundary map file name
  std::vector<double> source_xyz;          // 3 * num_vertices
  std::vector<std::uint32_t> tets;         // 4 * num_tets
  std::vector<double> target_xyz;          // VolumeMap/BoundaryMap: 3 * num_vertices (BoundaryMap:
                                           // NaN for vertices without a mapped position); else empty
  std::vector<std::uint8_t> flags;         // num_tets, kView* bits
  std::vector<double> volume_in;           // num_tets, signed (VOLMAP sign)
  std::vector<double> volume_out;          // num_tets (VolumeMap only), signed
  std::vector<double> sigma;               // 3 * num_tets singular values of J (VolumeMap only), s1>=s2>=s3
  std::vector<ViewField> fields;
  std::string initial_field;               // key of the field coloured at load
  std::size_t num_boundary_faces = 0;      // from volmap::boundary_half_faces (0: not given); the
                                           // viewer's own face matching is checked against it

  std::size_t num_vertices() const { return source_xyz.size() / 3; }
  std::size_t num_tets() const { return tets.size() / 4; }
};

// Global figures the side panel shows (computed from ViewData with VOLMAP's metrics rules:
// clamp, valid tets only, mean weighted by |volume|).
struct ViewFieldSummary {
  std::string key;
  std::size_t count = 0;  // tets that entered the figures
  double min = 0, max = 0, weighted_mean = 0;  // NaN when count == 0
};
struct ViewSummary {
  std::size_t num_tets = 0, num_vertices = 0;
  std::size_t num_inverted = 0, num_degenerate = 0, num_source_nonpositive = 0;
  std::vector<ViewFieldSummary> fields;
};

// Throws Error(BadInput) when array sizes disagree or a tet references a missing vertex.
void validate_view_data(const ViewData& data);
ViewSummary summarize_view(const ViewData& data);

// Standard base64 (RFC 4648, with padding, no line breaks).
std::string base64_encode(const std::uint8_t* bytes, std::size_t size);

// The whole page. `viewer_bundle` is the JS of viewer/dist/viewer.js; throws Error(BadInput) when it
// is empty or contains "</script" (it could not be inlined).
std::string build_view_html(const ViewData& data, const std::string& viewer_bundle);
// build_view_html written atomically to `path`.
void write_view_html(const std::string& path, const ViewData& data, const std::string& viewer_bundle);

}  // namespace volmap
