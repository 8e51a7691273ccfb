#include "smart/common/memory.hpp"

#include <fstream>
#include <sstream>
#include <string>

namespace smart::common {

double peak_rss_mb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmHWM:", 0) != 0) continue;
    std::istringstream in(line.substr(6));
    double kib = 0;
    in >> kib;
    return kib / 1024.0;
  }
  return 0;
}

}  // namespace smart::common
