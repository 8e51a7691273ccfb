// Contract: a fresh folder under the system's temporary folder (mkdtemp), removed with everything
// in it when the TempDir goes; throws std::runtime_error when it cannot be made.
#pragma once

#include <cerrno>
#include <cstdlib>  // mkdtemp (POSIX)
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace smart::tools {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix) {
    std::string templ = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (mkdtemp(templ.data()) == nullptr) {
      throw std::runtime_error("cannot make a scratch folder " + templ + ": " +
                               std::strerror(errno));
    }
    path_ = templ;
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace smart::tools
