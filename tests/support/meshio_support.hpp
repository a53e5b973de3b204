// Finding a Python interpreter with meshio (Debian python3-meshio), the third-party reader and writer
// the format tests compare against. The pyenv shim on PATH may hide Debian's package, so
// /usr/bin/python3 is tried too. Tests skip with a message when none is found.
#pragma once

#include <cstdlib>
#include <string>
#include <sys/wait.h>

namespace volmap_test {

inline std::string meshio_python() {
  for (const char* py : {"python3", "/usr/bin/python3"}) {
    const int status = std::system((std::string(py) + " -c 'import meshio' > /dev/null 2>&1").c_str());
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return py;
  }
  return "";
}

}  // namespace volmap_test
