// volmap-dataset — extend the benchmark (VOLMAP paper, Sections 6-7) in one command:
//   volmap-dataset <surfaces_dir> <dataset_dir> --group G7 [--domains cube,tet,pyr,octa,star,sphere,polycube:<cells>]
//                  [--jobs N] [--quality 1.414 | --coarse] [--max-volume V] [--decimate F] [--keep-going]
//                  [--keep-unrefined] [--json]
// For each surface (.obj .off .stl .ply): tetrahedralize (which checks the surface first), run the
// tet-mesh checks, compute every domain's boundary map on ONE mesh (as VOLMAP does), verify every map
// exactly, then publish <dataset>/<group>/<name>.mesh and <group>_<dom>/<name>_<dom>.txt. Every step
// is one of the volmap-* tools run as a child process; a polycube domain (`polycube:<cells file|cross7|L3>`,
// at most one) is published under the benchmark's suffix `pc`, with its cells beside the map
// (<group>_pc/<name>_pc_cells.txt); a surface that fails any step is skipped and
// the reason goes to <dataset>/<group>_log.txt. Maps made before a later domain refines the mesh are
// carried onto the refined mesh (lib map_extension) and re-verified, so one mesh serves all domains.
// Tet meshes (.mesh .vtk .vtu, VOLMAP-positive) in the folder are used as they are, without TetGen.
// --decimate F first coarsens surfaces of more than F triangles to F (lib decimate; more when F would
// make a thin part self-intersect: the decimation keeps an embedded surface embedded). --keep-going
// drops only the domains whose map fails (recorded per domain, the mesh it failed on kept in
// <group>_failed/) and publishes the others. --keep-unrefined also publishes the mesh before any
// surface-map split as <group>_unrefined/<name>.mesh (no benchmark group; for growth figures).
// --mesh-per-domain (volmap's layout extension, for end-to-end figures per (mesh, domain)): every
// domain maps its own copy of the TetGen mesh, <group>/<name>.mesh is that unsplit mesh, and a
// domain whose map split boundary edges publishes its mesh as <group>_<dom>/<name>_<dom>.mesh beside
// the map (VOLMAP's own tools, which read only <group>/<name>.mesh, cannot read such a case).
#include "support/tool_common.hpp"

#include <volmap/io/atomic_file.hpp>
#include "support/dataset.hpp"
#include <volmap/tetgen/decimate.hpp>
#include <volmap/io/io.hpp>
#include <volmap/surface/map_extension.hpp>
#include <volmap/surface/polycube.hpp>
#include "support/process.hpp"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <functional>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

std::string tools_dir() {
  std::error_code ec;
  const auto self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : self.parent_path().string();
}

std::string first_line(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) return line.substr(0, 300);
  return "";
}

struct SurfaceOutcome {
  std::string name;
  bool ok = false;
  std::string reason;        // why it was skipped
  int refinement_passes = 0;
  std::size_t faces = 0, decimated_faces = 0;  // input triangles; after --decimate (0 = not decimated)
  std::size_t tetgen_tets = 0, tets = 0;       // after TetGen; published (after surface-map splits)
  std::vector<std::pair<std::string, std::size_t>> domain_tets;  // --mesh-per-domain: (domain, its mesh's tets)
  std::vector<std::pair<std::string, std::string>> failed_domains;  // (domain, reason) with --keep-going
};

struct DatasetOptions {
  std::vector<std::string> domains;
  std::string quality, max_volume;
  bool coarse = false, keep_going = false, keep_unrefined = false;
  bool mesh_per_domain = false;  // each domain maps its own copy of the TetGen mesh (layout extension)
  std::size_t decimate = 0;  // 0 = never
};

// Writes the surface decimated to `faces` triangles into `work` when it has more, and returns the
// path TetGen should read.
fs::path decimated_input(const fs::path& surface, const fs::path& work, std::size_t faces, SurfaceOutcome& outcome) {
  const volmap::SurfaceData s = volmap::read_surface(surface.string());
  outcome.faces = s.num_triangles();
  if (faces == 0 || s.num_triangles() <= faces) return surface;
  volmap::DecimateOptions options;
  options.target_faces = faces;
  const auto d = volmap::decimate_surface(s, options);
  outcome.decimated_faces = d.faces_after;
  const fs::path out = work / (surface.stem().string() + "_decimated.off");
  volmap::write_surface(out.string(), d.surface);
  return out;
}

// Runs one tool; on failure returns its one-line reason (stderr), on success "".
std::string run_step(const std::vector<std::string>& argv, const fs::path& work, const std::string& step) {
  const auto out = work / (step + ".out");
  const auto err = work / (step + ".err");
  const auto r = volmap::run_process(argv, 0, out.string(), err.string());
  if (!r.started) return step + ": " + r.spawn_error;
  if (r.term_signal) return step + ": crashed (signal " + std::to_string(r.term_signal) + ")";
  if (r.exit_code != 0) {
    std::string reason = first_line(err);
    if (reason.empty()) reason = first_line(out);
    return step + " failed (exit " + std::to_string(r.exit_code) + ")" + (reason.empty() ? "" : ": " + reason);
  }
  return "";
}

void copy_atomically(const fs::path& from, const fs::path& to) {
  std::ifstream in(from, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  volmap::write_text_atomically(to.string(), ss.str());
}

// The folder/file suffix of a domain: the benchmark's `pc` for polycube:<cells>, else its name.
std::string domain_suffix(const std::string& dom) {
  return dom.rfind(volmap::kPolycubePrefix, 0) == 0 ? "pc" : dom;
}

// The cells of a polycube domain as a cells file ("" for other domains).
std::string cells_text(const std::string& dom) {
  if (domain_suffix(dom) != "pc") return "";
  std::string text = "# polycube cells (i j k), cell size 100\n";
  for (const auto& c : volmap::polycube_cells(dom.substr(volmap::kPolycubePrefix.size())))
    text += std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
  return text;
}

bool is_tet_mesh(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".mesh" || ext == ".vtk" || ext == ".vtu";
}

// Decimates (--decimate) and tetrahedralizes the surface into `mesh`; returns the failure or "".
std::string tetrahedralize_step(const fs::path& surface, const fs::path& work, const fs::path& mesh,
                                const DatasetOptions& opt, SurfaceOutcome& outcome) {
  fs::path input;
  try {
    input = decimated_input(surface, work, opt.decimate, outcome);
  } catch (const volmap::Error& e) {
    return std::string("decimate failed: ") + e.what();
  }
  std::vector<std::string> tetgen = {(fs::path(tools_dir()) / "volmap-tetrahedralize").string(), input.string(),
                                     mesh.string()};
  if (opt.coarse) tetgen.push_back("--coarse");
  else tetgen.insert(tetgen.end(), {"--quality", opt.quality});
  if (!opt.max_volume.empty()) tetgen.insert(tetgen.end(), {"--max-volume", opt.max_volume});
  return run_step(tetgen, work, "tetrahedralize");
}

// --mesh-per-domain: each domain maps its own copy of `mesh`; a domain whose map splits boundary edges
// keeps its refined mesh as work/<name>_<suffix>.mesh (published beside the map, where
// discover_cases looks first). Returns the first failure ("" when every kept domain verified).
std::string map_each_domain_on_its_own_mesh(const fs::path& mesh, const fs::path& work, const std::string& name,
                                            std::vector<std::string>& domains, SurfaceOutcome& outcome,
                                            const std::function<void(const std::string&, const std::string&, const fs::path&)>& drop,
                                            bool keep_going) {
  const fs::path tools(tools_dir());
  outcome.refinement_passes = 1;
  for (const auto& dom : std::vector<std::string>(domains)) {
    const std::string suffix = domain_suffix(dom);
    const fs::path map = work / (name + "_" + suffix + ".txt"), own = work / (name + "_" + suffix + ".mesh");
    fs::remove(own);
    std::string e = run_step({(tools / "volmap-surface-map").string(), dom, mesh.string(), map.string(), "--refined", own.string()},
                             work, "surface-map-" + suffix);
    const fs::path mapped = fs::exists(own) ? own : mesh;
    if (e.empty())
      e = run_step({(tools / "volmap-surface-map-check").string(), mapped.string(), map.string(), "--domain", dom}, work,
                   "surface-map-check-" + suffix);
    if (e.empty() && mapped == own)
      e = run_step({(tools / "volmap-tetmesh-check").string(), own.string()}, work, "tetmesh-check-" + suffix);
    if (!e.empty()) {
      if (!keep_going) return e;
      drop(dom, e, mapped);  // keeps the mesh it failed on: its own when the map split edges
      fs::remove(own);
      continue;
    }
    outcome.domain_tets.emplace_back(dom, volmap::read_tet_mesh(mapped.string()).num_tets());
  }
  return "";
}

SurfaceOutcome process_surface(const fs::path& surface, const fs::path& dataset, const std::string& group,
                               const DatasetOptions& opt) {
  const fs::path tools(tools_dir());
  SurfaceOutcome outcome;
  outcome.name = surface.stem().string();
  const fs::path work = dataset / (".work_" + group) / outcome.name;
  fs::remove_all(work);
  fs::create_directories(work);
  const fs::path mesh = work / (outcome.name + ".mesh");

  if (is_tet_mesh(surface))
    volmap::write_medit(mesh.string(), volmap::read_tet_mesh(surface.string()));  // used as is: no TetGen
  else if (auto e = tetrahedralize_step(surface, work, mesh, opt, outcome); !e.empty())
    return outcome.reason = e, outcome;
  outcome.tetgen_tets = volmap::read_tet_mesh(mesh.string()).num_tets();
  if (auto e = run_step({(tools / "volmap-tetmesh-check").string(), mesh.string()}, work, "tetmesh-check"); !e.empty())
    return outcome.reason = e, outcome;
  if (opt.keep_unrefined) {
    fs::create_directories(dataset / (group + "_unrefined"));
    copy_atomically(mesh, dataset / (group + "_unrefined") / (outcome.name + ".mesh"));
  }

  // One mesh for every domain: map the domains in turn; when a domain refines the mesh (midpoint
  // splits of boundary edges), the maps computed so far are carried onto the refined mesh by midpoint
  // interpolation (map_extension.hpp). Then every map is verified exactly; a map that fails (e.g. a
  // carried sphere map, whose midpoints leave the sphere) is recomputed on the final mesh, which may
  // refine again: repeat, a bounded number of times.
  auto map_path = [&](const std::string& dom) { return work / (outcome.name + "_" + domain_suffix(dom) + ".txt"); };
  std::vector<std::string> domains = opt.domains;
  // --keep-going: the mesh the domain failed on (and its map, if one was written) are kept in
  // <dataset>/<group>_failed/ to reproduce the failure; that folder is no benchmark group.
  // `failed_on`: the mesh the domain was mapped on ("" = the shared mesh).
  const std::function<void(const std::string&, const std::string&, const fs::path&)> drop =
      [&](const std::string& dom, const std::string& reason, const fs::path& failed_on) {
    outcome.failed_domains.emplace_back(dom, reason);
    domains.erase(std::find(domains.begin(), domains.end(), dom));
    const fs::path kept = dataset / (group + "_failed");
    fs::create_directories(kept);
    copy_atomically(failed_on.empty() ? mesh : failed_on, kept / (outcome.name + "_" + domain_suffix(dom) + ".mesh"));
    if (fs::exists(map_path(dom)))
      copy_atomically(map_path(dom), kept / (outcome.name + "_" + domain_suffix(dom) + ".txt"));
    fs::remove(map_path(dom));
  };
  if (opt.mesh_per_domain) {
    if (auto e = map_each_domain_on_its_own_mesh(mesh, work, outcome.name, domains, outcome, drop, opt.keep_going); !e.empty())
      return outcome.reason = e, outcome;
  }
  std::vector<std::string> pending = opt.mesh_per_domain ? std::vector<std::string>() : domains;
  constexpr int kMaxPasses = 6;
  for (int pass = 0; pass < kMaxPasses && !pending.empty(); ++pass) {
    outcome.refinement_passes = pass + 1;
    for (const auto& dom : pending) {
      const fs::path refined = work / "refined.mesh";
      fs::remove(refined);
      const auto before = volmap::read_tet_mesh(mesh.string());
      if (auto e = run_step({(tools / "volmap-surface-map").string(), dom, mesh.string(), map_path(dom).string(),
                             "--refined", refined.string()},
                            work, "surface-map-" + domain_suffix(dom));
          !e.empty()) {
        if (!opt.keep_going) return outcome.reason = e, outcome;
        drop(dom, e, {});
        continue;
      }
      if (!fs::exists(refined)) continue;
      const auto refined_mesh = volmap::read_tet_mesh(refined.string());
      for (const auto& other : domains) {
        if (other == dom || !fs::exists(map_path(other))) continue;
        const auto carried = volmap::extend_boundary_map_over_splits(volmap::read_boundary_map(map_path(other).string()),
                                                                     before, refined_mesh);
        volmap::write_boundary_map(map_path(other).string(), carried);
      }
      fs::rename(refined, mesh);
    }
    pending.clear();
    for (const auto& dom : domains) {
      if (!run_step({(tools / "volmap-surface-map-check").string(), mesh.string(), map_path(dom).string(), "--domain", dom},
                    work, "surface-map-check-" + domain_suffix(dom))
               .empty())
        pending.push_back(dom);
    }
  }
  if (!pending.empty() && opt.keep_going)
    for (const auto& dom : std::vector<std::string>(pending))
      drop(dom, "map did not verify after " + std::to_string(kMaxPasses) + " passes: " +
                    run_step({(tools / "volmap-surface-map-check").string(), mesh.string(), map_path(dom).string(),
                              "--domain", dom},
                             work, "surface-map-check-" + domain_suffix(dom)),
           {});
  else if (!pending.empty())
    return outcome.reason = "maps did not verify after " + std::to_string(kMaxPasses) + " passes", outcome;
  if (domains.empty()) return outcome.reason = "no domain could be mapped", outcome;
  if (auto e = run_step({(tools / "volmap-tetmesh-check").string(), mesh.string()}, work, "tetmesh-check-final");
      !e.empty())
    return outcome.reason = e, outcome;

  fs::create_directories(dataset / group);
  for (const auto& dom : domains) {
    const std::string suffix = domain_suffix(dom);
    const fs::path folder = dataset / (group + "_" + suffix);
    fs::create_directories(folder);
    if (suffix == "pc")
      volmap::write_text_atomically((folder / (outcome.name + "_pc_cells.txt")).string(), cells_text(dom));
    copy_atomically(map_path(dom), folder / (outcome.name + "_" + suffix + ".txt"));
    const fs::path own = work / (outcome.name + "_" + suffix + ".mesh");
    if (opt.mesh_per_domain && fs::exists(own)) copy_atomically(own, folder / (outcome.name + "_" + suffix + ".mesh"));
  }
  outcome.tets = volmap::read_tet_mesh(mesh.string()).num_tets();
  copy_atomically(mesh, dataset / group / (outcome.name + ".mesh"));  // last: a mesh means a complete case
  fs::remove_all(work);
  outcome.ok = true;
  return outcome;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Turn closed genus-0 surfaces into a new VOLMAP group: tet meshes + verified boundary maps.",
               "volmap-dataset"};
  std::string surfaces_dir, dataset_dir, group, domains_text = "cube,tet,pyr,octa,star";
  DatasetOptions opt;
  opt.quality = "1.414";
  int jobs = 1;
  bool json = false;
  app.add_option("surfaces_dir", surfaces_dir,
                 "folder of .obj/.off/.stl/.ply surfaces (and .mesh/.vtk/.vtu tet meshes, used as they are)")
      ->required();
  app.add_option("dataset_dir", dataset_dir, "VOLMAP layout root to write into (created)")->required();
  app.add_option("--group", group, "group folder name, e.g. G7")->required();
  app.add_option("--domains", domains_text,
                 "comma-separated domains (cube,tet,pyr,octa,star,sphere,polycube:<cells file|cross7|L3>)");
  app.add_option("--jobs,-j", jobs, "surfaces processed in parallel")->check(CLI::Range(1, 64));
  auto* quality_option = app.add_option("--quality", opt.quality, "TetGen radius-edge bound (q switch), at least 1")
                              ->check(volmap_tools::finite_range(1.0, 1e300));
  app.add_flag("--coarse", opt.coarse, "no quality refinement (TetGen without q): most tets touch the boundary")
      ->excludes(quality_option);
  app.add_option("--max-volume", opt.max_volume, "TetGen maximum tet volume (a switch)")
      ->check(volmap_tools::finite_non_negative());
  app.add_option("--decimate", opt.decimate,
                 "first decimate surfaces of more than this many triangles to this many (quadric edge collapses; fewer collapses where that many would make the surface self-intersect)")
      ->check(CLI::Validator(
          [](std::string& v) {  // 0 = never; a closed surface has at least 4 triangles
            std::size_t n = 0;
            return CLI::detail::lexical_cast(v, n) && (n == 0 || n >= 4) ? std::string()
                                                                          : "must be 0 (never) or at least 4, got '" + v + "'";
          },
          "0 or >= 4"));
  app.add_flag("--keep-unrefined", opt.keep_unrefined,
               "also write the mesh before any surface-map split to <group>_unrefined/<name>.mesh");
  app.add_flag("--mesh-per-domain", opt.mesh_per_domain,
               "each domain maps its own copy of the mesh: a domain that splits boundary edges publishes its refined "
               "mesh as <group>_<dom>/<name>_<dom>.mesh (volmap-run uses it); <group>/<name>.mesh stays unsplit");
  app.add_flag("--keep-going", opt.keep_going,
               "a domain whose map fails is dropped (reason in the log and JSON); the other domains are published");
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    if (group.size() < 2 || group[0] != 'G' || group.find_first_not_of("0123456789", 1) != std::string::npos)
      throw volmap::Error(volmap::ErrorKind::BadInput, "--group must look like G<number>, got '" + group + "'");
    std::vector<std::string>& domains = opt.domains;
    {
      std::stringstream ss(domains_text);
      for (std::string d; std::getline(ss, d, ',');)
        if (d.rfind(volmap::kPolycubePrefix, 0) == 0) {  // checked now: a bad polycube is bad input
          std::string cells = d.substr(volmap::kPolycubePrefix.size());
          if (!volmap::is_builtin_polycube_name(cells)) cells = fs::absolute(cells).string();  // children's cwd
          volmap::polycube_domain(cells);
          if (std::any_of(domains.begin(), domains.end(), [](const std::string& o) { return domain_suffix(o) == "pc"; }))
            throw volmap::Error(volmap::ErrorKind::BadInput, "", 0, "at most one polycube domain per group (suffix pc)");
          domains.push_back(std::string(volmap::kPolycubePrefix) + cells);
        } else if (!d.empty()) {
          const auto& known = volmap::volmap_domain_suffixes();
          if (std::find(known.begin(), known.end(), d) == known.end() || d == "pc")
            throw volmap::Error(volmap::ErrorKind::BadInput, "unsupported domain '" + d + "'");
          domains.push_back(d);
        }
    }
    if (!fs::is_directory(surfaces_dir)) throw volmap::Error(volmap::ErrorKind::Io, surfaces_dir, 0, "not a folder");
    std::vector<fs::path> surfaces;
    for (const auto& entry : fs::directory_iterator(surfaces_dir)) {
      std::string ext = entry.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
      if (entry.is_regular_file() && (ext == ".obj" || ext == ".off" || ext == ".stl" || ext == ".ply" || is_tet_mesh(entry.path())))
        surfaces.push_back(entry.path());
    }
    std::sort(surfaces.begin(), surfaces.end());
    if (surfaces.empty()) throw volmap::Error(volmap::ErrorKind::BadInput, surfaces_dir, 0, "no surfaces found");
    fs::create_directories(dataset_dir);

    std::vector<SurfaceOutcome> outcomes(surfaces.size());
    std::atomic<std::size_t> next{0};
    std::mutex print;
    auto worker = [&] {
      for (std::size_t i; (i = next++) < surfaces.size();) {
        try {
          outcomes[i] = process_surface(surfaces[i], dataset_dir, group, opt);
        } catch (const std::exception& e) {  // one bad surface never stops the others
          outcomes[i].name = surfaces[i].stem().string();
          outcomes[i].reason = e.what();
        }
        if (!json) {
          std::lock_guard<std::mutex> lock(print);
          std::cerr << outcomes[i].name << ": " << (outcomes[i].ok ? "added" : "skipped: " + outcomes[i].reason) << "\n";
        }
      }
    };
    std::vector<std::thread> threads;
    for (int j = 0; j < jobs; ++j) threads.emplace_back(worker);
    for (auto& t : threads) t.join();
    fs::remove_all(fs::path(dataset_dir) / (".work_" + group));

    std::ostringstream log;
    std::size_t added = 0;
    nlohmann::json list = nlohmann::json::array();
    for (const auto& o : outcomes) {
      added += o.ok;
      log << o.name << "\t" << (o.ok ? "added" : "skipped") << "\t" << (o.ok ? "" : o.reason) << "\n";
      nlohmann::json failed = nlohmann::json::array();
      for (const auto& [dom, why] : o.failed_domains) {
        log << o.name << "_" << dom << "\tdomain dropped\t" << why << "\n";
        failed.push_back({{"domain", dom}, {"reason", why}});
      }
      list.push_back({{"name", o.name}, {"added", o.ok}, {"reason", o.reason}, {"passes", o.refinement_passes},
                      {"faces", o.faces}, {"decimated_faces", o.decimated_faces}, {"tetgen_tets", o.tetgen_tets},
                      {"tets", o.tets}, {"failed_domains", failed}});
      if (opt.mesh_per_domain) {
        nlohmann::json per = nlohmann::json::object();
        for (const auto& [dom, n] : o.domain_tets) per[domain_suffix(dom)] = n;
        list.back()["domain_tets"] = per;
      }
    }
    volmap::write_text_atomically((fs::path(dataset_dir) / (group + "_log.txt")).string(), log.str());
    const int code = added > 0 ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed;
    if (json) return volmap_tools::print_json({{"group", group}, {"added", added}, {"surfaces", list}}, code);
    else
      std::cout << group << ": " << added << "/" << surfaces.size() << " surfaces added to " << dataset_dir << " (log "
                << (fs::path(dataset_dir) / (group + "_log.txt")).string() << ")\n";
    return code;
  }, &json);
}
