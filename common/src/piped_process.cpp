#include "smart/common/piped_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>  // NOLINT(modernize-deprecated-headers): sigaction is POSIX, not <csignal>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace smart::common {

namespace {

void ignore_sigpipe() {
  struct sigaction old {};
  if (sigaction(SIGPIPE, nullptr, &old) == 0 && old.sa_handler == SIG_DFL) {
    struct sigaction ign {};
    ign.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &ign, nullptr);
  }
}

std::array<int, 2> cloexec_pipe() {
  std::array<int, 2> fds{-1, -1};
  if (pipe2(fds.data(), O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  }
  return fds;
}

}  // namespace

PipedProcess::PipedProcess(const std::string& shell_command) {
  ignore_sigpipe();
  const auto in = cloexec_pipe();   // parent writes in[1], child reads in[0]
  const auto out = cloexec_pipe();  // child writes out[1], parent reads out[0]
  try {
    child_.emplace(std::vector<std::string>{"/bin/sh", "-c", shell_command},
                   std::filesystem::path{},
                   std::vector<std::pair<int, int>>{{in[0], STDIN_FILENO}, {out[1], STDOUT_FILENO}},
                   /*own_group=*/true);
  } catch (...) {
    for (const int fd : {in[0], in[1], out[0], out[1]}) close(fd);
    throw;
  }
  close(in[0]);
  close(out[1]);
  to_child_ = in[1];
  from_child_ = out[0];
  fcntl(to_child_, F_SETFL, fcntl(to_child_, F_GETFL) | O_NONBLOCK);
  fcntl(from_child_, F_SETFL, fcntl(from_child_, F_GETFL) | O_NONBLOCK);
}

PipedProcess::~PipedProcess() {
  if (to_child_ >= 0) close(to_child_);
  if (from_child_ >= 0) close(from_child_);
  // ChildProcess's destructor terminates and reaps the child.
}

int PipedProcess::milliseconds_to(Deadline deadline) {
  const auto left =
      std::chrono::ceil<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
  return static_cast<int>(std::clamp<int64_t>(left.count(), 0, 60'000));
}

PipedProcess::Io PipedProcess::write_line(std::string_view line, Deadline deadline) {
  if (to_child_ < 0) return Io::kClosed;
  std::string data(line);
  data.push_back('\n');
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(to_child_, data.data() + done, data.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EPIPE) return Io::kClosed;
    if (n < 0 && errno != EAGAIN && errno != EINTR) return Io::kClosed;
    pollfd p{to_child_, POLLOUT, 0};
    const int ms = milliseconds_to(deadline);
    if (ms == 0 || ::poll(&p, 1, ms) == 0) {
      // Half a line is in the pipe: nothing written later could be read right. The child sees
      // its input end.
      close(to_child_);
      to_child_ = -1;
      return Io::kTimeout;
    }
    if ((p.revents & (POLLERR | POLLHUP)) != 0) return Io::kClosed;
  }
  return Io::kOk;
}

PipedProcess::Io PipedProcess::read_line(std::string& line, std::size_t max_line_bytes,
                                         Deadline deadline) {
  std::array<char, 65536> chunk{};
  for (;;) {
    const auto nl = buffer_.find('\n');
    if (nl != std::string::npos) {
      const bool was_skipping = std::exchange(skipping_, false);
      const bool too_long = was_skipping || nl > max_line_bytes;
      if (!too_long) line.assign(buffer_, 0, nl);
      buffer_.erase(0, nl + 1);
      return too_long ? Io::kTooLong : Io::kOk;
    }
    if (buffer_.size() > max_line_bytes) {  // keep nothing of a line too long
      skipping_ = true;
      buffer_.clear();
    }
    if (from_child_ < 0) return Io::kClosed;
    // Checked before every read, not only when the pipe is empty: a child that writes faster
    // than lines are taken would otherwise keep this loop going past the deadline.
    if (std::chrono::steady_clock::now() >= deadline) return Io::kTimeout;
    const ssize_t n = ::read(from_child_, chunk.data(), chunk.size());
    if (n > 0) {
      buffer_.append(chunk.data(), static_cast<std::size_t>(n));
      continue;
    }
    if (n == 0) {
      close(from_child_);
      from_child_ = -1;
      return Io::kClosed;
    }
    if (errno != EAGAIN && errno != EINTR) return Io::kClosed;
    pollfd p{from_child_, POLLIN, 0};
    const int ms = milliseconds_to(deadline);
    if (ms == 0 || ::poll(&p, 1, ms) == 0) return Io::kTimeout;
  }
}

std::optional<int> PipedProcess::exit_code(std::chrono::milliseconds wait) {
  return child_->wait(wait);
}

}  // namespace smart::common
