// Linked into every GoogleTest binary (tests/CMakeLists.txt, smart_add_test): the files and
// folders a test process made with temp_file() (dds_test_support.hpp: the system temp folder,
// "smart_test_<pid>_<name>") are removed when it exits. Before, every run of the suite left
// them behind (1175 entries in /tmp after a few days of `make test`, results folders of whole
// runs among them). SMART_KEEP_TEST_FILES=1 keeps them, to look at a failure's files.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace {

class TempCleanup {
 public:
  TempCleanup() : pid_(::getpid()) {}
  TempCleanup(const TempCleanup&) = delete;
  TempCleanup& operator=(const TempCleanup&) = delete;
  ~TempCleanup() {
    // A forked child that exits normally runs this too: only the process that made them.
    if (::getpid() != pid_ || std::getenv("SMART_KEEP_TEST_FILES") != nullptr) return;
    const std::string prefix = "smart_test_" + std::to_string(pid_) + "_";
    std::error_code ec;
    const auto dir = std::filesystem::temp_directory_path(ec);
    if (ec) return;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      if (entry.path().filename().string().rfind(prefix, 0) == 0) {
        std::filesystem::remove_all(entry.path(), ec);
      }
    }
  }

 private:
  pid_t pid_;
};

const TempCleanup cleanup;

}  // namespace
