#include "smart/common/install_paths.hpp"

#include <system_error>

#include "smart/common/child_process.hpp"

namespace smart::common {

std::optional<std::filesystem::path> share_dir_beside(const std::filesystem::path& exe) {
  const auto dir = exe.parent_path().parent_path() / kInstalledShareDir;
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec)) return dir;
  return std::nullopt;
}

std::optional<std::filesystem::path> installed_share_dir() {
  try {
    return share_dir_beside(self_executable());
  } catch (const std::exception&) {
    return std::nullopt;  // no /proc: not installed as far as we can tell
  }
}

}  // namespace smart::common
