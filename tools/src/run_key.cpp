#include "smart/tools/run_key.hpp"

#include <fcntl.h>
#include <sys/random.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "smart/grid/text_file.hpp"
#include "smart/tools/cli_common.hpp"

namespace smart::tools {

namespace {
wire::RunKey random_key() {
  wire::RunKey key;
  key.bytes.resize(32);
  std::size_t got = 0;
  while (got < key.bytes.size()) {
    const auto n = getrandom(key.bytes.data() + got, key.bytes.size() - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::system_error(errno, std::generic_category(), "getrandom for a run key");
    got += static_cast<std::size_t>(n);
  }
  return key;
}

// Writes a fresh key to an open descriptor and closes it; removes the file when that failed.
void write_key(int fd, const std::filesystem::path& file) {
  const auto text = wire::format_run_key(random_key());
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const int err = errno;
  ::close(fd);
  if (!ok) {
    std::error_code ec;
    std::filesystem::remove(file, ec);
    throw std::system_error(err, std::generic_category(), "writing the run key " + file.string());
  }
}
}  // namespace

wire::RunKey read_run_key(const std::filesystem::path& file) {
  return wire::parse_run_key(grid::read_text_file(file.string(), "run key"), file.string());
}

void make_run_key(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    throw std::invalid_argument(file.string() + ": cannot make a run key file (" +
                                std::strerror(errno) +
                                "); name a new file in a folder you can "
                                "write to");
  }
  write_key(fd, file);
}

bool prove_member(dds::Participant& participant, const DdsOptions& options,
                  const std::string& role) {
  if (options.run_key.empty()) return false;
  participant.prove(read_run_key(options.run_key), role);
  return true;
}

PrivateRunKey::PrivateRunKey() {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern =
      std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/smart-run-key-XXXXXX";
  const int fd = ::mkstemp(pattern.data());  // mode 0600
  if (fd < 0) {
    throw std::system_error(errno, std::generic_category(),
                            "making a private run key in " + pattern);
  }
  file_ = pattern;
  write_key(fd, file_);
}

PrivateRunKey::~PrivateRunKey() {
  std::error_code ec;
  std::filesystem::remove(file_, ec);
}

}  // namespace smart::tools
