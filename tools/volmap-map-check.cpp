// volmap-map-check — exact certification of a volume map (volmap-reference.md §6, mapping.md §1):
//   volmap-map-check <in.mesh> <out.mesh> [--boundary map.txt] [--rationals-in f] [--rationals-out f]
//                    [--absolute] [--json]
// in.mesh must be a valid VOLMAP input (input_mesh.hpp: what volmap-tetmesh-check accepts), else
// exit 2 naming it and the problem; the one exception, without --absolute, is an input whose only
// problem is its orientation (negative tets, e.g. the opposite convention): it gets VOLMAP's relative
// check, never a certificate (exit 1 at best). --absolute asks for a certificate, so it refuses every
// invalid input. Every tet is evaluated in the INPUT tet's vertex order with exact orient3d (VOLMAP-positive = > 0).
// Relative test (VOLMAP's): the output sign must equal the input sign, nonzero. --absolute also
// requires the output tet (in the output file's own vertex order) to be > 0. Certified only when
// additionally every input tet is positive and (with --boundary) every boundary vertex sits exactly
// on the map's position. With rationals files the check runs on exact rational coordinates; a missing
// side is converted exactly from the mesh's doubles. Exit 0 certified, 1 not, 2 bad input.
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/io/io.hpp>
#include <volmap/check/map_check.hpp>
#include <volmap/check/orientation.hpp>

#include <chrono>
#include <cstdio>

namespace {
const char* match_name(volmap::ConnectivityMatch m) {
  switch (m) {
    case volmap::ConnectivityMatch::Identical: return "identical";
    case volmap::ConnectivityMatch::Reordered: return "same tets, some with another vertex order";
    case volmap::ConnectivityMatch::Permuted: return "same tets in another order";
  }
  return "?";
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Exact volume-map check (relative to the input, or --absolute), on doubles or rationals"};
  app.name("volmap-map-check");
  std::string in_path, out_path, boundary_path, rat_in_path, rat_out_path;
  bool absolute = false, json = false;
  std::size_t max_bad = 20;
  app.add_option("in.mesh", in_path, "source tet mesh (.mesh, .vtk, .vtu, .msh or .ovm by extension)")->required();
  app.add_option("out.mesh", out_path, "mapped tet mesh (same vertices and tets; .mesh, .vtk, .vtu or .msh)")->required();
  app.add_option("--boundary", boundary_path, "boundary map: boundary vertices must sit exactly on it");
  app.add_option("--rationals-in", rat_in_path, "exact input coordinates (VOLMAP num/den file)");
  app.add_option("--rationals-out", rat_out_path, "exact output coordinates (VOLMAP num/den file)");
  app.add_flag("--absolute", absolute, "also require every output tet to be VOLMAP-positive by itself");
  app.add_option("--max-bad", max_bad, "how many bad tet ids to list (default 20)")->check(CLI::Range(0, 1000000));
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    using Clock = std::chrono::steady_clock;
    auto t0 = Clock::now();
    volmap_tools::InputMeshes inputs("volmap-map-check", &json);
    const volmap::TetMeshData in = inputs.read(in_path);
    // A relative check of an input in the opposite orientation convention is VOLMAP's use case: such
    // an input passes with a note (and is never certified); any other problem refuses it, and so
    // does any problem at all when --absolute asks for a certificate.
    const volmap::InputMeshVerdict verdict =
        volmap_tools::naming_file(in_path, [&] { return volmap::judge_input_mesh(in); });
    if (!verdict.valid_up_to_orientation || (absolute && !verdict.valid))
      throw volmap::Error(volmap::ErrorKind::BadInput, in_path, 0,
                          "not a valid input tet mesh: " + verdict.reason() +
                              (verdict.valid_up_to_orientation ? " (--absolute certifies valid inputs only; without it the relative check runs)" : ""));
    const volmap::TetMeshData out = inputs.read(out_path);
    // The pair is checked first, so a mismatch is blamed on the mapped mesh, not on a later file.
    volmap_tools::naming_file(out_path + " (against " + in_path + ")", [&] { return volmap::match_connectivity(in, out); });
    volmap::BoundaryMap map;
    if (!boundary_path.empty()) {
      map = volmap::read_boundary_map(boundary_path);
      volmap::validate_boundary_map(map, in, boundary_path);
    }
    const bool rational = !rat_in_path.empty() || !rat_out_path.empty();
    std::vector<volmap::Rational> rin, rout;
    if (rational) {
      rin = rat_in_path.empty() ? volmap::rationals_from_doubles(in.xyz) : volmap::read_rationals(rat_in_path, in.num_vertices());
      rout = rat_out_path.empty() ? volmap::rationals_from_doubles(out.xyz)
                                  : volmap::read_rationals(rat_out_path, out.num_vertices());
    }
    const double read_seconds = std::chrono::duration<double>(Clock::now() - t0).count();

    volmap::MapCheckOptions options;
    options.absolute = absolute;
    options.max_reported_bad = max_bad;
    t0 = Clock::now();
    const volmap::BoundaryMap* boundary = boundary_path.empty() ? nullptr : &map;
    const volmap::MapCheckReport r = volmap_tools::naming_file(out_path + " (against " + in_path + ")", [&] {
      return rational ? volmap::check_map_rational(in, rin, out, rout, boundary, options)
                      : volmap::check_map(in, out, boundary, options);
    });
    const double check_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const bool certified = r.certified();

    if (json) {
      nlohmann::json j;
      j["certified"] = certified;
      j["valid"] = r.map_valid();
      j["mode"] = absolute ? "absolute" : "relative";
      j["arithmetic"] = rational ? "rational" : "double";
      j["num_tets"] = r.num_tets;
      j["connectivity"] = match_name(r.connectivity);
      j["input"] = {{"positive", r.input.positive}, {"zero", r.input.zero}, {"negative", r.input.negative}};
      j["output"] = {{"positive", r.output.positive}, {"zero", r.output.zero}, {"negative", r.output.negative}};
      j["relative"] = {{"positive", r.relative_positive}, {"zero", r.relative_zero}, {"negative", r.relative_negative}};
      if (absolute) {
        j["output_own_order"] = {{"positive", r.output_own_order.positive},
                                 {"zero", r.output_own_order.zero},
                                 {"negative", r.output_own_order.negative}};
      }
      j["num_bad"] = r.num_bad;
      j["first_bad_tets"] = r.first_bad;
      j["input_all_positive"] = r.input_all_positive();
      if (!verdict.valid) j["input_problem"] = verdict.reason();
      j["input_orientation"] = volmap::describe_orientation(r.input);
      if (!inputs.empty()) j["input_notes"] = inputs.json();
      if (r.boundary_checked) {
        j["boundary_mismatches"] = r.boundary_mismatches;
        j["first_boundary_mismatches"] = r.first_boundary_mismatches;
      }
      j["seconds"] = {{"read", read_seconds}, {"check", check_seconds}};
      return volmap_tools::print_json(std::move(j), certified ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed);
    } else {
      std::printf("%zu tets, connectivity: %s, %s arithmetic, %s check\n", r.num_tets, match_name(r.connectivity),
                  rational ? "exact rational" : "exact double", absolute ? "absolute" : "relative");
      std::printf("input:  %zu positive, %zu zero, %zu negative\n", r.input.positive, r.input.zero, r.input.negative);
      std::printf("output: %zu positive, %zu zero, %zu negative (input vertex order)\n", r.output.positive,
                  r.output.zero, r.output.negative);
      std::printf("relative to input: %zu same sign, %zu degenerate, %zu flipped\n", r.relative_positive,
                  r.relative_zero, r.relative_negative);
      if (absolute) {
        std::printf("output in its own order: %zu positive, %zu zero, %zu negative\n", r.output_own_order.positive,
                    r.output_own_order.zero, r.output_own_order.negative);
      }
      if (r.num_bad) {
        std::printf("%zu bad tets; first:", r.num_bad);
        for (auto t : r.first_bad) std::printf(" %llu", static_cast<unsigned long long>(t));
        std::printf("\n");
      }
      if (r.boundary_checked) {
        std::printf("boundary: %zu vertices off their prescribed position\n", r.boundary_mismatches);
      }
      if (!verdict.valid) std::printf("note: %s: %s; no map from it can be certified\n", in_path.c_str(), verdict.reason().c_str());
      if (certified) {
        std::printf("The map is valid (certified, %s check)\n", rational ? "rationals" : "floating point");
      } else if (r.map_valid()) {
        std::printf("The map is valid relative to the input [%s check] but NOT certified\n",
                    rational ? "rationals" : "floating point");
      } else {
        std::printf("The map is not valid [%zu elements not valid -- %s check]\n", r.num_bad,
                    rational ? "rationals" : "floating point");
      }
      std::printf("time: read %.3f s, check %.4f s\n", read_seconds, check_seconds);
    }
    return certified ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed;
  }, &json);
}
