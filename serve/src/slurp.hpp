// Internal to `smart serve`: a whole file as bytes (empty when it cannot be read; the callers
// check existence first and treat an empty file like a missing one).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace smart::serve {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace smart::serve
