// volmap-metrics — VOLMAP's map metrics (volmap-reference.md §7), same numbers as VOLMAP's `metrics`:
//   volmap-metrics <in.mesh> <out.mesh> [--upper 100] [--json] [--csv file] [--vtu per_tet.vtu]
//                  [--original original.mesh] [--emulate-volmap-singular-tets]
// Human output reproduces VOLMAP's text block; --csv appends VOLMAP's CSV line ("; " separated, %f);
// --json prints everything, including the fixed/extra fields (scale-normalised energies, 3r/R quality
// of input and output, scaled Jacobian, size ratio against --original, "undefined" instead of NaN).
// Source tets whose edge matrix is exactly singular in doubles (J not finite; duck star has 4) are
// where VOLMAP reads uninitialised singular values: by default they get `upper` for every energy;
// --emulate-volmap-singular-tets reproduces VOLMAP's values (see MetricsOptions in metrics.hpp).
// Tets are paired by connectivity: the output's positions are read with the input tet's vertex ids.
// in.mesh (and --original) must be valid VOLMAP inputs (input_mesh.hpp), else exit 2 naming the file
// (that reason first, before a mismatch with out.mesh); every mesh is read through the format
// dispatcher. The two meshes are read at once, and in.mesh is validated while the metrics are
// computed (two threads), with out.mesh's tet list freed once matched: wall time and peak memory. The CSV line and the .vtu are written together
// or not at all. Exit 0 when computed (also for maps with inverted tets: this tool measures, it does
// not certify), 2 on bad or mismatched input.
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/io/atomic_file.hpp>
#include <volmap/io/io.hpp>
#include <volmap/check/input_mesh.hpp>
#include <volmap/check/map_check.hpp>
#include <volmap/check/metrics.hpp>


#include <chrono>
#include <exception>
#include <future>
#include <thread>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {
// The output's own tet list, once matched against the input's, is not needed again: freeing it
// before the validation and the metrics keeps the peak memory below VOLMAP's.
void release_tets(volmap::TetMeshData& mesh) {
  std::vector<std::uint32_t>().swap(mesh.tets);
  std::vector<std::int32_t>().swap(mesh.tet_labels);
}

// The map in -> out read, checked and measured as two chains on two threads: the input is read, then
// validated; the output is read, then (once the input is there) matched against it, freed of its
// tet list and measured. The validation waits for that freeing, so that its scratch memory and the
// output's tets are never held at once (peak memory below VOLMAP's). Errors come in the order a
// user reads them: reading the input, its validity, reading the output, the match, the metrics.
// Reader notes are kept for the files read.
struct MeasuredMap {
  volmap::TetMeshData in, out;  // out keeps its positions only
  volmap::MetricsReport report;
};

// Runs `step` and keeps what it throws in `failure` (true when it succeeded).
template <class Step>
bool capture(std::exception_ptr& failure, Step&& step) {
  try {
    step();
    return true;
  } catch (...) {
    failure = std::current_exception();
    return false;
  }
}

MeasuredMap read_and_measure(volmap_tools::InputMeshes& inputs, const std::string& in_path, const std::string& out_path,
                             const volmap::MetricsOptions& options) {
  MeasuredMap m;
  volmap::TetMeshReadNotes notes[2];
  std::exception_ptr reading_in, invalid_in, reading_out, measuring;
  std::promise<void> in_read, out_matched;  // each set exactly once, on every path
  std::shared_future<void> in_ready = in_read.get_future().share(), out_ready = out_matched.get_future().share();
  const std::string pair_name = out_path + " (against " + in_path + ")";
  auto input_chain = [&] {
    const bool read = capture(reading_in, [&] { m.in = volmap::read_tet_mesh(in_path, notes[0]); });
    in_read.set_value();
    if (!read) return;
    out_ready.wait();
    capture(invalid_in, [&] { volmap::require_valid_input_mesh(m.in, in_path); });
  };
  auto output_chain = [&] {
    const bool read = capture(reading_out, [&] { m.out = volmap::read_tet_mesh(out_path, notes[1]); });
    in_ready.wait();
    const bool matched = read && !reading_in && capture(measuring, [&] {
      volmap_tools::naming_file(pair_name, [&] { volmap::match_connectivity(m.in, m.out); });
      release_tets(m.out);  // matched: from here on the map is out.xyz over in.tets
    });
    out_matched.set_value();
    if (!matched) return;
    capture(measuring, [&] {
      m.report = volmap_tools::naming_file(pair_name, [&] { return volmap::compute_metrics(m.in, m.out.xyz, options); });
    });
  };
  std::thread output_thread(output_chain);  // an OS thread: the chains must run at the same time
  input_chain();
  output_thread.join();
  if (!reading_in) inputs.keep(in_path, std::move(notes[0]));
  if (!reading_out) inputs.keep(out_path, std::move(notes[1]));
  for (const std::exception_ptr& e : {reading_in, invalid_in, reading_out, measuring})
    if (e) std::rethrow_exception(e);
  return m;
}

nlohmann::json stats_json(const volmap::RangeStats& s) {
  if (!s.defined) return {{"min", nullptr}, {"max", nullptr}, {"mean", nullptr}, {"defined", false}};
  return {{"min", s.min}, {"max", s.max}, {"mean", s.mean}, {"defined", true}};
}
// Every option of the tool.
struct Args {
  std::string in_path, out_path, csv_path, vtu_path, original_path;
  double upper = 100.0;
  bool json = false, emulate_singular = false;
};

void add_options(CLI::App& app, Args& a) {
  app.add_option("in.mesh", a.in_path, "source tet mesh (.mesh, .vtk, .vtu, .msh or .ovm; a valid VOLMAP input)")->required();
  app.add_option("out.mesh", a.out_path, "mapped tet mesh (same vertices and tets; .mesh, .vtk, .vtu, .msh or .ovm)")->required();
  app.add_option("--upper", a.upper, "energy clamp upper bound (default 100, at least 6)")
      ->check(volmap_tools::finite_range(6.0, 1e300));
  app.add_flag("--json", a.json, "print one JSON object");
  app.add_option("--csv", a.csv_path, "append VOLMAP's CSV line to this file");
  app.add_option("--original", a.original_path, "unrefined source mesh: report the size ratio against it");
  app.add_option("--vtu", a.vtu_path, "write the output mesh with per-tet cell data (energies, inverted, quality) to this .vtu");
  app.add_flag("--emulate-volmap-singular-tets", a.emulate_singular,
               "compatibility only: for source tets whose edge matrix is singular in doubles (no finite "
               "Jacobian), VOLMAP's metrics reads uninitialised singular values (Eigen 3.4 JacobiSVD returns "
               "early on non-finite input). Default: such tets get the upper bound for every energy. With "
               "this flag they get (F_out(1,2), F_out(2,0), F_out(2,1)) of the same tet, which reproduces "
               "VOLMAP's printed duck-star numbers; these values are not a meaningful distortion");
}

// The outputs, prepared (checked against the inputs and each other) before any work.
struct Outputs {
  volmap::AtomicOutput* csv = nullptr;  // appended to
  volmap::AtomicOutput* vtu = nullptr;
};

Outputs prepare_files(const Args& a, volmap_tools::RunFiles& files) {
  for (const std::string* p : {&a.in_path, &a.out_path}) volmap::require_tet_mesh_extension(*p);
  if (!a.original_path.empty()) volmap::require_tet_mesh_extension(a.original_path);
  if (!a.vtu_path.empty() && volmap::tet_mesh_format(a.vtu_path) != volmap::TetMeshFormat::Vtu)
    throw volmap::Error(volmap::ErrorKind::Unsupported, a.vtu_path, 0, "--vtu writes VTK XML: the path must end in .vtu");
  files.input(a.in_path, "input mesh");
  files.input(a.out_path, "mapped mesh");
  files.input(a.original_path, "--original mesh");
  Outputs out;
  if (!a.csv_path.empty()) out.csv = &files.output(a.csv_path, "--csv file");
  if (!a.vtu_path.empty()) out.vtu = &files.output(a.vtu_path, "--vtu output");
  return out;
}

// Appended like VOLMAP's log, but atomically: the old content plus the new line is written to a
// temporary file and renamed over the log (an interrupted run never leaves a torn line).
void append_csv_line(volmap::AtomicOutput& csv, const std::string& csv_path, const std::string& line) {
  std::string content;
  if (std::filesystem::exists(csv_path)) {
    std::ifstream old(csv_path, std::ios::binary);
    if (!old) throw volmap::Error(volmap::ErrorKind::Io, csv_path, 0, "cannot read the CSV file to append to");
    std::stringstream ss;
    ss << old.rdbuf();
    content = ss.str();
    if (!content.empty() && content.back() != '\n') content += '\n';
  }
  volmap::write_text(csv, content + line + "\n");
}

// The mapped mesh with per-tet cell data, cells in the INPUT's tet and vertex order (the order the
// metrics were evaluated in).
void write_per_tet_vtu(volmap::AtomicOutput& vtu, const volmap::TetMeshData& in, volmap::TetMeshData out, const volmap::MetricsReport& r) {
  volmap::TetMeshData cells = std::move(out);
  cells.tets = in.tets;
  cells.tet_labels = in.tet_labels;
  std::vector<volmap::CellDataArray> data;
  for (int e = 0; e < volmap::kNumEnergies; ++e) {
    data.push_back({volmap::energy_name(static_cast<volmap::Energy>(e)), r.per_tet.energy[e]});
  }
  std::vector<double> inverted(r.num_tets), orientation(r.num_tets);
  for (std::size_t t = 0; t < r.num_tets; ++t) {
    inverted[t] = r.per_tet.orientation[t] <= 0 ? 1.0 : 0.0;
    orientation[t] = r.per_tet.orientation[t];
  }
  data.push_back({"inverted", std::move(inverted)});
  data.push_back({"orientation", std::move(orientation)});
  data.push_back({"quality_out", r.per_tet.quality_out});
  data.push_back({"quality_in", r.per_tet.quality_in});
  data.push_back({"scaled_jacobian", r.per_tet.scaled_jacobian_out});
  volmap::write_vtu(vtu, cells, data);
}

// The --original mesh's size, when given (0, 0 without it).
struct OriginalSize {
  std::size_t tets = 0, vertices = 0;
};

struct Timings {
  double read_check_compute = 0, total = 0;
};

nlohmann::json metrics_json(const Args& a, const MeasuredMap& m, const OriginalSize& original, const Timings& t) {
  const volmap::MetricsReport& r = m.report;
  nlohmann::json j;
  j["input"] = a.in_path;
  j["output"] = a.out_path;
  j["num_tets"] = r.num_tets;
  j["num_inverted"] = r.num_inverted;
  j["num_degenerate"] = r.num_degenerate;
  j["inverted_percent"] = r.inverted_percent;
  j["upper"] = r.upper;
  nlohmann::json energies, scaled;
  for (int e = 0; e < volmap::kNumEnergies; ++e) {
    energies[volmap::energy_name(static_cast<volmap::Energy>(e))] = stats_json(r.energy[e]);
    scaled[volmap::energy_name(static_cast<volmap::Energy>(e))] = stats_json(r.energy_scaled[e]);
  }
  j["energies"] = energies;
  j["energies_scale_normalised"] = scaled;
  j["scale_factor"] = r.scale_factor;
  j["volume_in"] = r.volume_in;
  j["volume_out"] = r.volume_out;
  j["tet_radius_ratio_compat"] = stats_json(r.tet_radius_ratio);
  j["quality_in"] = stats_json(r.quality_in);
  j["quality_out"] = stats_json(r.quality_out);
  j["scaled_jacobian_out"] = stats_json(r.scaled_jacobian_out);
  j["singular_source_tets"] = {
      {"count", r.num_singular_source},
      {"first", r.first_singular_source},
      {"treatment", r.singular_source_emulated ? "emulated VOLMAP uninitialised singular values "
                                                 "(F_out(1,2), F_out(2,0), F_out(2,1))"
                                               : "energies set to upper (VOLMAP reads uninitialised memory here)"}};
  if (original.tets) {
    j["size_ratio_tets"] = double(r.num_tets) / double(original.tets);
    j["size_ratio_vertices"] = double(m.in.num_vertices()) / double(original.vertices);
  }
  // The pair is read, checked and measured on two threads at once: "compute" (the metrics alone)
  // overlaps "read_check_compute".
  j["seconds"] = {{"read_check_compute", t.read_check_compute}, {"compute", r.seconds}, {"total", t.total}};
  return j;
}

void print_text_report(const volmap::MetricsReport& r, const OriginalSize& original) {
  std::cout << volmap::format_metrics_volmap(r);
  std::cout << "Quality 3r/R input (min/max/avg): " << r.quality_in.min << " / " << r.quality_in.max << " / "
            << r.quality_in.mean << "\n";
  std::cout << "Quality 3r/R output, signed (min/max/avg): " << r.quality_out.min << " / " << r.quality_out.max
            << " / " << r.quality_out.mean << "\n";
  std::cout << "Scale-normalised (k = " << r.scale_factor << ") Dirichlet / Sym. Dirichlet / Arap E: ";
  for (int e : {1, 2, 3}) {
    if (r.energy_scaled[e].defined) std::cout << r.energy_scaled[e].mean; else std::cout << "undefined";
    std::cout << (e < 3 ? " / " : "\n");
  }
  if (r.num_singular_source) {
    std::cout << "Note: " << r.num_singular_source
              << " source tets have an edge matrix singular in doubles (no finite Jacobian; VOLMAP reads "
                 "uninitialised singular values there): "
              << (r.singular_source_emulated ? "VOLMAP's values emulated" : "energies set to the upper bound")
              << "\n";
  }
  if (original.tets) {
    std::cout << "Size ratio (tets): " << double(r.num_tets) / double(original.tets) << "\n";
  }
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"VOLMAP-compatible volume-map metrics (inverted tets, 5 distortion energies, quality)"};
  app.name("volmap-metrics");
  Args a;
  add_options(app, a);
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    volmap_tools::RunFiles files;
    volmap_tools::InputMeshes inputs("volmap-metrics", &a.json);
    const Outputs out = prepare_files(a, files);
    volmap::MetricsOptions options;
    options.upper = a.upper;
    options.keep_per_tet = out.vtu != nullptr;
    options.emulate_volmap_singular_tets = a.emulate_singular;
    MeasuredMap measured = read_and_measure(inputs, a.in_path, a.out_path, options);
    Timings timings;
    timings.read_check_compute = std::chrono::duration<double>(Clock::now() - t0).count();
    OriginalSize original;
    if (!a.original_path.empty()) {
      const volmap::TetMeshData mesh = volmap_tools::read_input_tet_mesh(inputs, a.original_path);
      original = {mesh.num_tets(), mesh.num_vertices()};
    }
    if (out.csv) append_csv_line(*out.csv, a.csv_path, volmap::format_metrics_csv_line(a.out_path, measured.report));
    if (out.vtu) write_per_tet_vtu(*out.vtu, measured.in, std::move(measured.out), measured.report);
    files.commit();
    timings.total = std::chrono::duration<double>(Clock::now() - t0).count();
    if (a.json) {
      nlohmann::json j;
      if (!inputs.empty()) j["input_notes"] = inputs.json();
      j.update(metrics_json(a, measured, original, timings));
      return volmap_tools::print_json(std::move(j), volmap_tools::kExitOk);
    }
    print_text_report(measured.report, original);
    return volmap_tools::kExitOk;
  }, &a.json);
}
