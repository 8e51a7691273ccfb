#include "smart/serve/run_registry.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

namespace smart::serve {

std::string_view to_string(RunState s) {
  switch (s) {
    case RunState::kQueued:
      return "queued";
    case RunState::kRunning:
      return "running";
    case RunState::kDone:
      return "done";
    case RunState::kFailed:
      return "failed";
  }
  return "unknown";
}

std::string RunRegistry::add(std::string map_name, std::size_t robots) {
  char id[32];
  std::snprintf(id, sizeof(id), "run-%06llu", static_cast<unsigned long long>(next_++));
  runs_[id] = {id, RunState::kQueued, {}, std::move(map_name), robots};
  return id;
}

std::string RunRegistry::add_done(std::string map_name, std::size_t robots) {
  auto id = add(std::move(map_name), robots);
  runs_[id].state = RunState::kDone;
  return id;
}

bool RunRegistry::adopt(RunEntry entry) {
  if (!is_run_id(entry.id) || entry.id.size() > 16 || runs_.count(entry.id)) return false;
  const uint64_t n = std::stoull(entry.id.substr(4));  // at most 12 digits
  next_ = std::max(next_, n + 1);
  runs_[entry.id] = std::move(entry);
  return true;
}

std::vector<std::string> RunRegistry::start_ready(std::size_t max_running) {
  std::vector<std::string> started;
  std::size_t busy = running();
  for (auto& [id, run] : runs_) {
    if (busy >= max_running) break;
    if (run.state != RunState::kQueued) continue;
    run.state = RunState::kRunning;
    started.push_back(id);
    ++busy;
  }
  return started;
}

void RunRegistry::finish(const std::string& id, bool ok, std::string error) {
  auto it = runs_.find(id);
  if (it == runs_.end()) return;
  it->second.state = ok ? RunState::kDone : RunState::kFailed;
  it->second.error = std::move(error);
}

std::optional<RunEntry> RunRegistry::get(const std::string& id) const {
  auto it = runs_.find(id);
  if (it == runs_.end()) return std::nullopt;
  return it->second;
}

std::vector<RunEntry> RunRegistry::list() const {
  std::vector<RunEntry> out;
  for (const auto& [id, run] : runs_) out.push_back(run);
  return out;
}

std::size_t RunRegistry::running() const {
  std::size_t n = 0;
  for (const auto& [id, run] : runs_) n += run.state == RunState::kRunning ? 1 : 0;
  return n;
}

bool is_run_id(std::string_view t) {
  if (t.size() < 10 || t.size() > 24 || t.substr(0, 4) != "run-") return false;
  for (const char c : t.substr(4)) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

}  // namespace smart::serve
