// volmap/volmap.hpp — the whole library in one include (link volmap::volmap).
// Wings, each usable alone (link volmap::<wing>, include <volmap/<wing>/...>):
//   core     TetMeshData, TetMesh (half-face mesh, edits, properties), ids, local tables, Error
//   io       read_tet_mesh / write_medit / read_boundary_map, VTK/VTU, Gmsh .msh, OpenVolumeMesh .ovm,
//            surfaces, atomic outputs
//   check    check_tet_mesh, self-intersection, check_map, metrics
//   surface  domains, surface maps onto them (OpenMesh TriMesh boundary), their check
//   volume   Tutte 3D, FFM/TLC untangling, blocking-chord removal, cone repair, compute_volume_map
// Conventions (docs/conventions.md): a VOLMAP-positive tet (v0,v1,v2,v3) has orient3d > 0; ids are
// 0-based in memory (Medit files are 1-based); tet vertex order is the user's, never changed.
#pragma once

#include <volmap/predicates.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/core/ids.hpp>
#include <volmap/core/local_tables.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/core/properties.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/core/topology.hpp>

#include <volmap/io/atomic_file.hpp>
#include <volmap/io/io.hpp>
#include <volmap/io/io_surface.hpp>
#include <volmap/io/output_paths.hpp>
#include <volmap/io/read_notes.hpp>
#include <volmap/io/temp_cleanup.hpp>

#include <volmap/check/input_mesh.hpp>
#include <volmap/check/map_check.hpp>
#include <volmap/check/metrics.hpp>
#include <volmap/check/orientation.hpp>
#include <volmap/check/self_intersection.hpp>
#include <volmap/check/tetmesh_checks.hpp>

#include <volmap/surface/boundary_surface.hpp>
#include <volmap/surface/domain.hpp>
#include <volmap/surface/map_extension.hpp>
#include <volmap/surface/polycube.hpp>
#include <volmap/surface/surface_map.hpp>
#include <volmap/surface/surface_map_check.hpp>

#include <volmap/volume/chord_cone.hpp>
#include <volmap/volume/chord_flip.hpp>
#include <volmap/volume/chord_rules.hpp>
#include <volmap/volume/chord_split.hpp>
#include <volmap/volume/cone_repair.hpp>
#include <volmap/volume/feasibility.hpp>
#include <volmap/volume/ffm.hpp>
#include <volmap/volume/kernel_lp.hpp>
#include <volmap/volume/link_kernel.hpp>
#include <volmap/volume/map_stages.hpp>
#include <volmap/volume/map_state.hpp>
#include <volmap/volume/tlc.hpp>
#include <volmap/volume/tutte3d.hpp>
#include <volmap/volume/volume_map.hpp>
