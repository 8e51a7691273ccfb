#include "smart/grid/text_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "smart/grid/problem.hpp"

namespace smart::grid {

std::string read_text_file(const std::filesystem::path& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError({{path.string(), 0, -1,
                       std::string("cannot open the ") + what + " file: " + std::strerror(errno) +
                           "; check the path"}});
  }
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace smart::grid
