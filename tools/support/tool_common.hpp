// Shared scaffolding of the volmap-* tools (header-only, tools only — never used by the library).
// Exit codes: 0 = ok, 1 = a check failed / not injective, 2 = usage or bad input (one-line reason on
// stderr naming the file). `--json` tools print exactly one JSON object on stdout, always with
// "ok" (true exactly when the exit code is 0: the verdict passed) and "exit_code".
// Every run follows the same order: options validated (ranges, NaN) by CLI11; inputs named and
// outputs prepared (RunFiles: each output checked against the inputs and the other outputs, its
// extension checked, its temporary file created) before any work; input tet meshes read through the
// format dispatcher and validated (read_input_tet_mesh) before any work; all outputs committed
// together at the end. SIGINT/SIGTERM/SIGHUP remove the temporary files.
#pragma once

#include "input_mesh.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <volmap/check/input_mesh.hpp>
#include <volmap/core/error.hpp>
#include <volmap/io/atomic_file.hpp>
#include <volmap/io/io.hpp>
#include <volmap/io/output_paths.hpp>
#include <volmap/io/temp_cleanup.hpp>
#include <volmap/surface/domain.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <new>
#include <string>
#include <vector>

namespace volmap_tools {

constexpr int kExitOk = 0;
constexpr int kExitCheckFailed = 1;
constexpr int kExitBadInput = 2;

// ---- options --------------------------------------------------------------------------------------
// CLI11's Range/NonNegativeNumber let NaN through (every comparison with NaN is false): these do not.
inline CLI::Validator finite_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double v = 0;
        try {
          std::size_t used = 0;
          v = std::stod(text, &used);
          if (used != text.size()) return "'" + text + "' is not a number";
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (!std::isfinite(v) || v < lo || v > hi)
          return "value " + text + " is not a finite number in [" + CLI::detail::to_string(lo) + ", " +
                 CLI::detail::to_string(hi) + "]";
        return std::string();
      },
      "FINITE in [" + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]");
}
inline CLI::Validator finite_non_negative() { return finite_range(0.0, 1e300); }
inline CLI::Validator finite_positive() { return finite_range(1e-300, 1e300); }

// ---- inputs and outputs -----------------------------------------------------------------------------
// The files of one run. input() names what the run reads; output() prepares what it writes (call
// every input() first): the output must not be an input or another output, must be a new path or a
// regular file, and its temporary file is created now. commit() publishes every prepared output
// that was not dropped, all together.
class RunFiles {
 public:
  void input(const std::string& path, const std::string& role) {
    if (!path.empty()) inputs_.push_back({path, role});
  }
  volmap::AtomicOutput& output(const std::string& path, const std::string& role) {
    volmap::check_output_path({path, role}, inputs_, outputs_);
    outputs_.push_back({path, role});
    return transaction_.add(path);
  }
  // A tet mesh output: its extension picks the format (.mesh, .vtk, .vtu) or it is refused.
  volmap::AtomicOutput& tet_mesh_output(const std::string& path, const std::string& role) {
    volmap::check_output_path({path, role}, inputs_, outputs_);  // an input named first, then the extension
    volmap::require_tet_mesh_extension(path, /*for_writing=*/true);
    return output(path, role);
  }
  void commit() { transaction_.commit(); }

 private:
  std::vector<volmap::NamedPath> inputs_, outputs_;
  volmap::OutputTransaction transaction_;
};

// Reads a tet mesh through the format dispatcher, keeping the reader's notes in `inputs`
// (support/input_mesh.hpp), and refuses it (exit 2, naming the file and the reason) unless it is a
// valid input (volmap/check/input_mesh.hpp: what volmap-tetmesh-check accepts).
inline volmap::TetMeshData read_input_tet_mesh(InputMeshes& inputs, const std::string& path) {
  volmap::TetMeshData mesh = inputs.read(path);
  volmap::require_valid_input_mesh(mesh, path);
  return mesh;
}

// A base domain by name (cube, tet, ...) or from a custom domain file, read with the text vetting of
// lib/io (no NUL bytes, bounded lines), so /dev/zero or a binary file is refused at once.
inline volmap::Domain domain_from_name_or_file(const std::string& name_or_path) {
  if (volmap::is_builtin_domain_name(name_or_path)) return volmap::builtin_domain(name_or_path);
  return volmap::parse_custom_domain(volmap::read_text_file(name_or_path, 1 << 16), name_or_path);
}

// Refuses coordinates so large that squaring them (norms, energies, linear solves) overflows
// doubles; `what` names the file they came from.
inline void require_moderate_coordinates(const std::vector<double>& xyz, const std::string& what) {
  constexpr double kLimit = 1e100;
  double largest = 0;
  for (double c : xyz) largest = std::max(largest, std::abs(c));
  if (largest > kLimit) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g", largest);
    throw volmap::Error(volmap::ErrorKind::Unsupported, what, 0,
                        std::string("coordinates up to ") + buf +
                            " exceed 1e100: the solvers would overflow double arithmetic (rescale the input)");
  }
}

// Runs `f`; a volmap::Error that names no file (library functions working on arrays cannot know
// it) is re-thrown naming `file`, so the tool's one-line reason says which input was at fault.
template <class F>
auto naming_file(const std::string& file, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const volmap::Error& e) {
    if (!e.file().empty()) throw;
    throw volmap::Error(e.kind(), file, 0, e.reason());
  }
}

// ---- results ----------------------------------------------------------------------------------------
// Prints the one JSON object of a --json run with the contract fields and returns the exit code.
inline int print_json(nlohmann::json j, int exit_code) {
  j["ok"] = exit_code == kExitOk;
  j["exit_code"] = exit_code;
  std::cout << j.dump() << "\n";
  return exit_code;
}

// Runs a tool body: parses the CLI11 app, maps exceptions to exit codes with a one-line reason.
// `body` returns the exit code. `json_mode` (when non-null and true) makes errors also print
// {"ok":false,"exit_code":..,"error":...} on stdout so `--json` consumers always get one object.
inline int run_tool(CLI::App& app, int argc, char** argv, const std::function<int()>& body,
                    const bool* json_mode = nullptr) {
  volmap::install_temp_cleanup_on_signals();
  const std::string name = app.get_name();
  // A usage error stops parsing before --json is stored: the flag is then read from argv itself.
  bool json_in_argv = false;
  for (int i = 1; i < argc; ++i) json_in_argv = json_in_argv || std::string(argv[i]) == "--json";
  auto fail = [&](int code, const std::string& reason) {
    std::string line = reason;
    for (char& c : line)
      if (c == '\n' || c == '\r') c = ' ';
    std::cerr << name << ": " << line << "\n";
    if (json_mode && (*json_mode || json_in_argv)) {
      nlohmann::json j{{"ok", false}, {"exit_code", code}, {"error", line}};
      std::cout << j.dump() << "\n";
    }
    return code;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    return fail(kExitBadInput, "usage: " + what + " (see --help)");
  }
  try {
    return body();
  } catch (const volmap::Error& e) {
    return fail(e.kind() == volmap::ErrorKind::Failed ? kExitCheckFailed : kExitBadInput, e.what());
  } catch (const std::bad_alloc&) {
    return fail(kExitBadInput, "out of memory (input too large?)");
  } catch (const std::exception& e) {
    return fail(kExitBadInput, e.what());
  }
}

}  // namespace volmap_tools
