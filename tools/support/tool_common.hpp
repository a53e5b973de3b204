// Shared scaffolding of the volmap-* tools (header-only, tools only — never used by the library).
// Exit codes: 0 = ok, 1 = a check failed / not injective, 2 = usage or bad input (one-line reason on
// stderr). `--json` tools print exactly one JSON object on stdout.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <volmap/core/error.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <new>
#include <string>

namespace volmap_tools {

constexpr int kExitOk = 0;
constexpr int kExitCheckFailed = 1;
constexpr int kExitBadInput = 2;

// Runs a tool body: parses the CLI11 app, maps exceptions to exit codes with a one-line reason.
// `body` returns the exit code. `json_mode` (when non-null and true) makes bad-input errors also
// print {"ok":false,"error":...} on stdout so `--json` consumers always get one object.
// Refuses an output path whose folder is missing (or which is a folder) before any work is done, so
// that a tool with several outputs never writes the first and then fails on the next one.
inline void require_output_folder(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p(path), dir = p.parent_path().empty() ? "." : p.parent_path();
  if (!std::filesystem::is_directory(dir, ec)) volmap::throw_io(path, "output folder does not exist");
  if (std::filesystem::is_directory(p, ec)) volmap::throw_io(path, "output path is a directory");
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

inline int run_tool(CLI::App& app, int argc, char** argv, const std::function<int()>& body,
                    const bool* json_mode = nullptr) {
  const std::string name = app.get_name();
  auto fail = [&](int code, const std::string& reason) {
    std::cerr << name << ": " << reason << "\n";
    if (json_mode && *json_mode) {
      nlohmann::json j{{"ok", false}, {"exit_code", code}, {"error", reason}};
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
