#include "smart/serve/run_store.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "slurp.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/serve/robot_detail.hpp"

namespace smart::serve {

namespace fs = std::filesystem;

RunStore::RunStore(fs::path data_dir) : data_dir_(std::move(data_dir)) {
  fs::create_directories(data_dir_);
}

RunStore::~RunStore() { stop_all(); }

fs::path RunStore::results_file(const std::string& id, std::string_view name) const {
  return dir(id) / "results" / name;
}

fs::path RunStore::stage() {
  fs::path p;
  {
    std::lock_guard lock(m_);
    p = data_dir_ / ("upload-" + std::to_string(++staged_));
  }
  fs::create_directories(p);
  return p;
}

std::string RunStore::add_queued(
    const fs::path& staged, const std::string& map_name, std::size_t robots,
    const std::function<std::vector<std::string>(const std::string&)>& argv) {
  std::lock_guard lock(m_);
  auto id = registry_.add(map_name, robots);
  fs::rename(staged, dir(id));
  argv_[id] = argv(id);
  return id;
}

std::string RunStore::add_done(const fs::path& staged, const std::string& map_name,
                               std::size_t robots) {
  std::lock_guard lock(m_);
  auto id = registry_.add_done(map_name, robots);
  fs::rename(staged, dir(id));
  return id;
}

std::optional<RunEntry> RunStore::entry(const std::string& id) const {
  std::lock_guard lock(m_);
  return is_run_id(id) ? registry_.get(id) : std::nullopt;
}

std::size_t RunStore::queued() const {
  std::lock_guard lock(m_);
  const auto all = registry_.list();
  return static_cast<std::size_t>(std::count_if(
      all.begin(), all.end(), [](const RunEntry& e) { return e.state == RunState::kQueued; }));
}

std::vector<RunEntry> RunStore::list() const {
  std::lock_guard lock(m_);
  return registry_.list();
}

std::shared_ptr<const monitor::Instance> RunStore::instance(const std::string& id,
                                                            const Loader& load) {
  {
    std::lock_guard lock(m_);
    if (auto it = instances_.find(id); it != instances_.end()) return it->second;
  }
  auto in = std::make_shared<const monitor::Instance>(load(dir(id)));
  std::lock_guard lock(m_);
  return instances_.emplace(id, std::move(in)).first->second;
}

std::shared_ptr<const std::vector<double>> RunStore::action_times(const std::string& id,
                                                                  const monitor::Instance& in) {
  {
    std::lock_guard lock(m_);
    if (auto it = action_times_.find(id); it != action_times_.end()) return it->second;
  }
  const auto csv = results_file(id, results::kActionsCsv);
  const auto e = entry(id);
  if (!e || e->state != RunState::kDone || !fs::exists(csv)) {
    return std::make_shared<const std::vector<double>>();
  }
  auto t = std::make_shared<const std::vector<double>>(parse_action_times(slurp(csv), in.actions));
  std::lock_guard lock(m_);
  return action_times_.emplace(id, std::move(t)).first->second;
}

void RunStore::tend(std::size_t max_running) {
  std::lock_guard lock(m_);
  for (const auto& id : registry_.start_ready(max_running)) {
    children_.emplace(id, common::ChildProcess(argv_.at(id), dir(id) / "run.out"));
    spdlog::info("serve: {} started", id);
  }
  for (auto it = children_.begin(); it != children_.end();) {
    const auto rc = it->second.wait(std::chrono::milliseconds(0));
    if (!rc) {
      ++it;
      continue;
    }
    const bool summary = fs::exists(results_file(it->first, results::kSummaryJson));
    const bool ok = (*rc == 0 || *rc == 1) && summary;
    registry_.finish(it->first, ok,
                     ok ? ""
                        : "smart run exited with code " + std::to_string(*rc) + "; see " +
                              (dir(it->first) / "run.out").string());
    spdlog::info("serve: {} ended (exit code {})", it->first, *rc);
    it = children_.erase(it);
  }
}

void RunStore::stop_all() {
  std::lock_guard lock(m_);
  children_.clear();  // ChildProcess stops what still runs
}

}  // namespace smart::serve
