// Contract: the runs a `smart serve` holds and the order they execute in, decided without I/O:
// add() queues a run and gives its id (run-000001, ...: safe as a folder name and a URL part);
// start_ready(max_running) says which queued runs start now (oldest first, at most max_running
// at once); finish() records how one ended. is_run_id() accepts exactly the ids add() makes, so
// nothing else from a URL ever becomes a path. Not thread-safe: the server holds one lock.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace smart::serve {

enum class RunState { kQueued, kRunning, kDone, kFailed };
std::string_view to_string(RunState state);

struct RunEntry {
  std::string id;
  RunState state = RunState::kQueued;
  std::string error;     // why it failed (kFailed)
  std::string map_name;  // as uploaded, for the list
  std::size_t robots = 0;
};

class RunRegistry {
 public:
  std::string add(std::string map_name, std::size_t robots);
  // A run that already happened (a `smart run --out` folder to replay): done at once.
  std::string add_done(std::string map_name, std::size_t robots);
  // A run a previous server left (its id must be a run id, not held here yet): ids go on after
  // the largest adopted. False when the entry cannot be adopted.
  bool adopt(RunEntry entry);
  // Forgets a run just added whose folder turned out taken (its id is not used again).
  void drop(const std::string& id) { runs_.erase(id); }
  std::vector<std::string> start_ready(std::size_t max_running);
  void finish(const std::string& id, bool ok, std::string error);
  std::optional<RunEntry> get(const std::string& id) const;
  std::vector<RunEntry> list() const;  // oldest first
  std::size_t running() const;

 private:
  uint64_t next_ = 1;
  std::map<std::string, RunEntry> runs_;  // ids sort in creation order
};

bool is_run_id(std::string_view text);

}  // namespace smart::serve
