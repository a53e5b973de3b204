// volmap-view in a real browser: runs viewer/test/run.sh (headless Debian Chromium driven by npm
// playwright-core) on pages written by the built volmap-view from ../shared/data. The script skips
// with a message (and this test with it) when chromium or viewer/node_modules is absent.
// Checks inside the script: no console errors, histogram and colour bar drawn, a slice changes the
// drawn face count, a click picks a tet, exact inverted counts shown, no network; screenshots and
// load timings land in <build>/view-test/.
#include <doctest/doctest.h>

#include "test_support.hpp"
#include "view_test_support.hpp"

#include <cstdlib>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {
void run_browser_cases(const std::string& cases) {
  const fs::path script = fs::path(VOLMAP_SOURCE_DIR) / "viewer" / "test" / "run.sh";
  const fs::path build = fs::path(VOLMAP_BIN_DIR).parent_path();
  REQUIRE(fs::exists(script));
  const fs::path log = build / ("view-test-run-" + std::to_string(cases.size()) + ".log");
  const std::string cmd = "VOLMAP_VIEW_CASES='" + cases + "' bash '" + script.string() + "' '" + build.string() + "' >'" +
                          log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  const std::string out = view_test::read_all(log.string());
  if (out.find("view test skipped:") != std::string::npos) {
    MESSAGE(out);
    return;
  }
  INFO(out);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(out.find(" 0 failed") != std::string::npos);
  const bool bunny_ran = out.find("ok   bunny-map: slice changes the drawn face count") != std::string::npos;
  const bool bunny_skipped = out.find("view test bunny-map skipped") != std::string::npos;
  if (cases.find("bunny-map") != std::string::npos) CHECK((bunny_ran || bunny_skipped));
}
}  // namespace

// The G1-sized volume map (bunny, 98,840 tets), a map with exact inverted/degenerate tets (hand) and a
// star boundary map (24 charts, 14 corners).
TEST_CASE("volmap-view pages work headless in Chromium (viewer/test/run.sh)") {
  run_browser_cases("bunny-map hand-map duck-star-boundary");
}

TEST_SUITE("long") {
  // A cube boundary map, the 100,695-tet G1 buste alone and mapped to the cube by volmap-tutte3d
  // (295 inverted tets), the max polycube pair (45 + 198 bad tets).
  TEST_CASE("volmap-view boundary-map and single-mesh pages headless in Chromium") {
    run_browser_cases("bunny-cube-boundary buste-mesh max-map buste-tutte-map");
  }
}
