#include "smart/grid/text_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "smart/grid/problem.hpp"

namespace smart::grid {

namespace {
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message) {
  throw InputError({{path.string(), 0, -1, message}});
}
[[noreturn]] void too_large(const std::filesystem::path& path, const char* what) {
  fail(path, std::string("the ") + what + " file is larger than " +
                 std::to_string(kMaxTextFileBytes >> 20) +
                 " MiB, more than any map, scenario or plan this reads; is it the right file?");
}
}  // namespace

std::string read_text_file(const std::filesystem::path& path, const char* what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    fail(path, std::string("is a directory, not a ") + what + " file; give the file's path");
  }
  if (std::filesystem::is_regular_file(path, ec) &&
      std::filesystem::file_size(path, ec) > kMaxTextFileBytes) {
    too_large(path, what);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail(path, std::string("cannot open the ") + what + " file: " + std::strerror(errno) +
                   "; check the path");
  }
  // Read in chunks up to the limit: a device or pipe (/dev/zero) has no size to trust.
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxTextFileBytes) too_large(path, what);
  }
  return text;
}

}  // namespace smart::grid
