// The mutation suite: good inputs of every kind (tet mesh, boundary map, surface, custom domain,
// rationals) mutated at random (fixed seed: the same files every run) — bytes flipped, lines deleted,
// duplicated or swapped, the file cut short, a number replaced by NaN, infinity, a huge or negative
// value or a word, a NUL or a garbage line inserted — and run through the real tools that read them.
// No mutant is expected to be accepted or refused; every run must be clean:
//   no crash (signal), no hang (60 s alarm, 20 s budget), an exit code of 0, 1 or 2, on exit 2 one
//   stderr line naming an input of the run, on exit 2 no output, no temporary file, no input changed,
//   and honest: a mapper or checker that exits 0 or prints a certificate on a mutated mesh only does
//   so when volmap-tetmesh-check accepts that mesh.
// Counts (tried / clean and each kind of defect) are written to <build>/mutation_suite.txt.
// Under AddressSanitizer (CI's sanitizer stage) every third mutant is run: the same files are made,
// every kind and every tool is still covered, and the stage stays within CI's time.
#include <doctest/doctest.h>

#include <volmap/io/io.hpp>
#include <volmap/testing/generate.hpp>

#include "tool_run.hpp"

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <sstream>

namespace fs = std::filesystem;
using volmap_test::RunResult;

namespace {

// ---- mutations ----------------------------------------------------------------------------------------
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream s(text);
  for (std::string l; std::getline(s, l);) lines.push_back(l);
  return lines;
}
std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

class Mutator {
 public:
  explicit Mutator(unsigned seed) : rng_(seed) {}

  // One to three random mutations of `text`.
  std::string mutate(std::string text) {
    const int n = 1 + pick(3);
    for (int k = 0; k < n && !text.empty(); ++k) text = once(std::move(text));
    return text;
  }

 private:
  std::mt19937 rng_;
  std::size_t pick(std::size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }

  std::string once(std::string text) {
    std::vector<std::string> lines = split_lines(text);
    switch (pick(8)) {
      case 0:  // one byte replaced by any byte
        text[pick(text.size())] = static_cast<char>(pick(256));
        return text;
      case 1:  // a line deleted
        lines.erase(lines.begin() + pick(lines.size()));
        return join_lines(lines);
      case 2: {  // a line duplicated
        const std::size_t i = pick(lines.size());
        lines.insert(lines.begin() + i, lines[i]);
        return join_lines(lines);
      }
      case 3:  // two lines swapped
        std::swap(lines[pick(lines.size())], lines[pick(lines.size())]);
        return join_lines(lines);
      case 4:  // cut short
        return text.substr(0, pick(text.size()));
      case 5:
        return replace_token(std::move(lines));
      case 6:  // a NUL byte inserted
        return text.insert(pick(text.size()), 1, '\0');
      default: {  // a garbage line inserted
        static const char* garbage[] = {"hello world", "1 2", "-1 -1 -1 -1", "Vertices", "End", "99999999999 0 0 0",
                                        "3 0 1", "nm 0 0", "a 0", "\xEF\xBB\xBF", "1/0", "\t\t"};
        lines.insert(lines.begin() + pick(lines.size() + 1), garbage[pick(std::size(garbage))]);
        return join_lines(lines);
      }
    }
  }

  // A whitespace-separated token of a random line replaced by a hostile value.
  std::string replace_token(std::vector<std::string> lines) {
    static const char* values[] = {"nan", "inf", "-inf", "-1", "0", "1e308", "-1e308", "1e-320", "4294967296",
                                   "99999999999999999999", "abc", "1.5", "0x10", "", "2000000000"};
    std::string& line = lines[pick(lines.size())];
    std::vector<std::pair<std::size_t, std::size_t>> tokens;
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      const std::size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i > start) tokens.emplace_back(start, i - start);
    }
    if (!tokens.empty()) {
      const auto [at, len] = tokens[pick(tokens.size())];
      line.replace(at, len, values[pick(std::size(values))]);
    }
    return join_lines(lines);
  }
};

// ---- runs and their verdicts ----------------------------------------------------------------------------
struct Counts {
  int tried = 0, clean = 0, crashes = 0, hangs = 0, wrong_exits = 0, partial_outputs = 0, unclear_messages = 0,
      dishonest = 0, accepted = 0, check_failed = 0, refused = 0;
};

class Suite : public volmap_test::ToolTree {
 public:
  std::map<std::string, Counts> by_kind;
  std::vector<std::string> failures;

  Suite() : ToolTree("mutation_suite") {}

  std::string file(const std::string& name, const std::string& bytes) const { return volmap_test::write_bytes(in / name, bytes); }
  std::string o(const std::string& name) const { return (out / name).string(); }

  RunResult run(const std::vector<std::string>& args) const {
    std::vector<std::string> argv = args;
    argv.front() = volmap_test::tool(argv.front()).string();
    return volmap_test::run_tool_process(argv, scratch, 60);
  }

  // One run of `args` (tool name first) on the mutant `mutant`; `inputs` are the file names a refusal
  // may name; `honest_when` is the verdict of volmap-tetmesh-check on the mutant when the tool maps
  // or checks it (nullopt: the tool is not bound by it).
  RunResult judge(const std::string& kind, const std::string& label, const std::vector<std::string>& args,
             const std::vector<std::string>& inputs, std::optional<bool> tetmesh_check_accepts = std::nullopt) {
    const std::string before = volmap_test::fingerprint(in);
    const RunResult r = run(args);
    std::string err = r.err;
    while (!err.empty() && err.back() == '\n') err.pop_back();
    Counts& c = by_kind[kind];
    ++c.tried;
    std::vector<std::string> problems;
    if (r.signaled && r.signal == SIGALRM) ++c.hangs, problems.push_back("hang");
    else if (r.signaled) ++c.crashes, problems.push_back("signal " + std::to_string(r.signal));
    else if (r.exit_code < 0 || r.exit_code > 2) ++c.wrong_exits, problems.push_back("exit " + std::to_string(r.exit_code));
    if (r.seconds > 20 && !r.signaled) ++c.hangs, problems.push_back("took " + std::to_string(int(r.seconds)) + " s");
    if (!r.signaled) {
      (r.exit_code == 0 ? c.accepted : r.exit_code == 1 ? c.check_failed : c.refused) += 1;
    }
    if (!r.signaled && r.exit_code == 2) {
      bool named = false;
      for (const auto& name : inputs) named = named || err.find(name) != std::string::npos;
      if (err.empty() || err.find('\n') != std::string::npos || !named)
        ++c.unclear_messages, problems.push_back("stderr is not one line naming an input");
      if (!volmap_test::listing(out).empty()) ++c.partial_outputs, problems.push_back("left " + volmap_test::listing(out).front());
    }
    bool leftover = false;
    for (const auto& dir : {in, out})
      for (const auto& name : volmap_test::listing(dir)) leftover = leftover || name.find(".tmp.") != std::string::npos;
    if (leftover) ++c.partial_outputs, problems.push_back("temporary file left");
    if (volmap_test::fingerprint(in) != before) ++c.partial_outputs, problems.push_back("changed an input");
    if (r.peak_rss_kb > (1l << 20)) ++c.wrong_exits, problems.push_back("peak RSS over 1 GiB");
    if (tetmesh_check_accepts && !*tetmesh_check_accepts) {
      bool certificate = !r.signaled && r.exit_code == 0;
      for (const char* phrase : {"certified injective", "The map is valid (certified", "Check result: SUCCESS"})
        certificate = certificate || r.out.find(phrase) != std::string::npos;
      if (certificate) ++c.dishonest, problems.push_back("exit 0 or a certificate for a mesh volmap-tetmesh-check rejects");
    }
    if (problems.empty()) {
      ++c.clean;
    } else {
      std::string line = kind + " " + label + " " + args.front() + ": ";
      for (const auto& p : problems) line += p + "; ";
      failures.push_back(line + "| stderr: " + err.substr(0, 300));
    }
    clear_out();
    return r;
  }

  // volmap-tetmesh-check's verdict on a mutated mesh (it is also a run of the suite).
  bool tetmesh_check_accepts(const std::string& label, const std::string& mesh) {
    const RunResult r = judge("mesh", label, {"volmap-tetmesh-check", mesh}, {fs::path(mesh).filename().string()});
    return !r.signaled && r.exit_code == 0;
  }
};

bool all_built(const std::vector<std::string>& tools) {
  for (const auto& t : tools)
    if (!fs::exists(volmap_test::tool(t))) {
      MESSAGE("skipped: " << t << " is not built");
      return false;
    }
  return true;
}

#ifdef VOLMAP_TEST_ASAN
constexpr int kSampleStride = 3;
#else
constexpr int kSampleStride = 1;
#endif
bool sampled(int k) { return k % kSampleStride == 0; }

}  // namespace

TEST_CASE("mutation suite: mutated inputs of every kind through the tools that read them") {
  if (!all_built({"volmap-tetmesh-check", "volmap-tutte3d", "volmap-map", "volmap-map-check", "volmap-metrics",
                  "volmap-surface-map", "volmap-surface-map-check", "volmap-tetrahedralize", "volmap-convert"}))
    return;
  Suite s;
  Mutator mutator(20261124);
  const volmap::TetMeshData grid = volmap::generate_kuhn_grid(2, 2, 2);
  const std::string mesh_text = volmap_test::medit_text(grid), map_text = volmap_test::boundary_identity_map_text(grid);
  const std::string mesh = s.file("good.mesh", mesh_text), map = s.file("good_map.txt", map_text);
  std::string rat;
  for (double x : grid.xyz) rat += std::to_string(static_cast<int>(x)) + "\n";
  const std::string off = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::string domain = "n 0\nn 1\nn 2\nn 4\nnm 0 0 0\nnm 0 0 100\nnm 100 0 50\nnm 30 100 30\n"
                             "a 0 1\na 1 2\na 2 0\na 3 0\na 3 1\na 3 2\n";
  volmap::write_vtk((s.in / "good.vtk").string(), grid);
  const std::string vtk_text = volmap_test::read_bytes(s.in / "good.vtk");

  // Tet meshes (Medit and legacy VTK): the checker, the mappers and the map checkers.
  for (int k = 0; k < 140; ++k) {
    const bool vtk = k % 4 == 3;
    const std::string name = "mesh" + std::to_string(k) + (vtk ? ".vtk" : ".mesh");
    const std::string m = s.file(name, mutator.mutate(vtk ? vtk_text : mesh_text));
    if (!sampled(k)) continue;
    const bool accepts = s.tetmesh_check_accepts(name, m);
    s.judge("mesh", name, {"volmap-tutte3d", m, map, s.o("t.mesh")}, {name, "good_map.txt"}, accepts);
    s.judge("mesh", name, {"volmap-map-check", m, m, "--absolute", "--boundary", map}, {name, "good_map.txt"}, accepts);
    s.judge("mesh", name, {"volmap-metrics", m, m}, {name}, accepts);
    s.judge("mesh", name, {"volmap-convert", m, s.o("c.vtu")}, {name});
    if (k % 4 == 0)
      s.judge("mesh", name, {"volmap-map", m, map, s.o("m.mesh"), "--time-limit", "5"}, {name, "good_map.txt"}, accepts);
    if (k % 4 == 1) s.judge("mesh", name, {"volmap-surface-map-check", m, map}, {name, "good_map.txt"}, accepts);
    // The mutant as the mapped mesh of a pair (the source is good): a map check, never a certificate
    // unless the map is injective — judged by exit code and message only.
    if (k % 4 == 2) s.judge("mesh", name, {"volmap-map-check", mesh, m, "--absolute"}, {name, "good.mesh"});
  }
  // Boundary maps.
  for (int k = 0; k < 60; ++k) {
    const std::string name = "map" + std::to_string(k) + ".txt";
    const std::string m = s.file(name, mutator.mutate(map_text));
    if (!sampled(k)) continue;
    s.judge("map", name, {"volmap-tutte3d", mesh, m, s.o("t.mesh")}, {name, "good.mesh"});
    s.judge("map", name, {"volmap-map-check", mesh, mesh, "--boundary", m}, {name, "good.mesh"});
    s.judge("map", name, {"volmap-surface-map-check", mesh, m}, {name, "good.mesh"});
    if (k % 3 == 0) s.judge("map", name, {"volmap-map", mesh, m, s.o("m.mesh"), "--time-limit", "5"}, {name, "good.mesh"});
  }
  // Triangle surfaces (OFF).
  for (int k = 0; k < 40; ++k) {
    const std::string name = "surface" + std::to_string(k) + ".off";
    const std::string m = s.file(name, mutator.mutate(off));
    if (!sampled(k)) continue;
    s.judge("surface", name, {"volmap-tetmesh-check", m}, {name});
    s.judge("surface", name, {"volmap-tetrahedralize", m, s.o("t.mesh")}, {name});
  }
  // Custom domains.
  for (int k = 0; k < 40; ++k) {
    const std::string name = "domain" + std::to_string(k) + ".txt";
    const std::string m = s.file(name, mutator.mutate(domain));
    if (!sampled(k)) continue;
    s.judge("domain", name, {"volmap-surface-map", "custom", mesh, s.o("s.txt"), "--domain", m}, {name, "good.mesh"});
  }
  // Exact rationals.
  for (int k = 0; k < 40; ++k) {
    const std::string name = "rationals" + std::to_string(k) + ".rat";
    const std::string m = s.file(name, mutator.mutate(rat));
    if (!sampled(k)) continue;
    s.judge("rationals", name, {"volmap-map-check", mesh, mesh, "--rationals-in", m}, {name, "good.mesh"});
  }

  std::ostringstream summary;
  Counts total;
  auto line = [&](const std::string& what, const Counts& c) {
    summary << what << ": tried " << c.tried << ", clean " << c.clean << " (exit 0/1/2: " << c.accepted << "/"
            << c.check_failed << "/" << c.refused << "); crashes " << c.crashes << ", hangs " << c.hangs << ", wrong exits "
            << c.wrong_exits << ", partial outputs " << c.partial_outputs << ", unclear messages " << c.unclear_messages
            << ", dishonest " << c.dishonest << "\n";
  };
  for (const auto& [kind, c] : s.by_kind) {
    line(kind, c);
    total.tried += c.tried, total.clean += c.clean, total.crashes += c.crashes, total.hangs += c.hangs;
    total.wrong_exits += c.wrong_exits, total.partial_outputs += c.partial_outputs;
    total.unclear_messages += c.unclear_messages, total.dishonest += c.dishonest;
    total.accepted += c.accepted, total.check_failed += c.check_failed, total.refused += c.refused;
  }
  line("total", total);
  std::ofstream((fs::path(VOLMAP_BIN_DIR).parent_path() / "mutation_suite.txt").string()) << summary.str();
  std::cout << "mutation suite\n" << summary.str();
  MESSAGE(summary.str());
  for (const auto& f : s.failures) MESSAGE(f);
  CHECK(s.failures.empty());
  CHECK(total.tried > 800 / kSampleStride);
}
