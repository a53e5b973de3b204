// Outside consumer of the installed volmap::volmap: reads a tet mesh and its boundary map (a G1
// pair, given on the command line), builds the half-face TetMesh, checks the input, maps it with
// compute_volume_map (refinement allowed: the written source may be the refined mesh), writes the
// pair and certifies the files read back from disk.
// Usage: volmap_consumer_map <mesh> <map.txt> <out_dir>. Exit 0 only when the written pair is
// certified; 1 when it is not; 2 on an error.
#include <volmap/volmap.hpp>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: volmap_consumer_map <mesh> <map.txt> <out_dir>\n");
    return 2;
  }
  try {
    const volmap::TetMeshData input = volmap::read_tet_mesh(argv[1]);
    const volmap::BoundaryMap map = volmap::read_boundary_map(argv[2]);
    const volmap::TetMesh mesh(input);
    std::printf("consumer: %zu vertices, %zu tets, %zu boundary faces\n", mesh.num_vertices(), mesh.num_tets(),
                mesh.boundary_half_faces().size());
    const volmap::TetMeshCheckReport input_check = volmap::check_tet_mesh(input);
    if (!input_check.all_passed()) {
      std::fprintf(stderr, "consumer: %s fails the tet mesh checks\n", argv[1]);
      return 2;
    }
    volmap::VolumeMapOptions options;
    options.time_limit_seconds = 60;
    const volmap::VolumeMapResult result = volmap::compute_volume_map(input, map, options);

    const std::string dir = argv[3];
    volmap::TetMeshData image = result.source;
    image.xyz = result.target_xyz;
    volmap::write_medit(dir + "/in.mesh", result.source);
    volmap::write_medit(dir + "/out.mesh", image);
    const volmap::MapCheckReport check =
        volmap::check_map(volmap::read_tet_mesh(dir + "/in.mesh"), volmap::read_tet_mesh(dir + "/out.mesh"), &map);
    std::printf("consumer: mapper says %s; written pair %s (%zu bad tets)\n",
                result.certified ? "certified" : "not certified", check.certified() ? "certified" : "NOT certified",
                check.num_bad);
    return result.certified && check.certified() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 2;
  }
}
