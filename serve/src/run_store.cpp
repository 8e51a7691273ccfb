#include "smart/serve/run_store.hpp"

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "slurp.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/serve/bounded_json.hpp"
#include "smart/serve/robot_detail.hpp"

namespace smart::serve {

namespace fs = std::filesystem;

namespace {
constexpr const char* kEntryJson = "entry.json";

void write_entry(const fs::path& dir, const std::string& map_name, std::size_t robots) {
  std::ofstream(dir / kEntryJson) << nlohmann::json{{"map", map_name}, {"robots", robots}}.dump();
}

// What a previous server recorded of a run folder; a damaged entry.json leaves the defaults.
RunEntry read_entry(const fs::path& dir) {
  RunEntry e{dir.filename().string(), RunState::kFailed, {}, "?", 0};
  try {
    std::error_code ec;
    if (fs::file_size(dir / kEntryJson, ec) > 65536 || ec) {
      throw std::runtime_error("no entry.json of at most 64 KB");
    }
    const auto j = parse_bounded_json(slurp(dir / kEntryJson), (dir / kEntryJson).string());
    e.map_name = j.value("map", e.map_name).substr(0, 256);
    e.robots = j.value("robots", std::size_t{0});
  } catch (const std::exception& ex) {
    spdlog::warn("serve: {}: {} (listed without its map name)", dir.string(), ex.what());
  }
  if (fs::exists(dir / "results" / results::kSummaryJson)) {
    e.state = RunState::kDone;
  } else {
    e.error = "interrupted: the server stopped before this run ended; upload it again";
  }
  return e;
}
}  // namespace

RunStore::RunStore(fs::path data_dir) : data_dir_(std::move(data_dir)) {
  fs::create_directories(data_dir_);
  lock_data_dir();
  adopt_previous();
}

RunStore::~RunStore() {
  stop_all();
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

void RunStore::lock_data_dir() {
  const auto file = data_dir_ / ".lock";
  lock_fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) {
    throw std::runtime_error("cannot open " + file.string() + ": " + std::strerror(errno) +
                             "; give --data a folder you can write to");
  }
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw std::runtime_error("the data folder " + data_dir_.string() +
                             " is in use by another `smart serve`; stop it, or give this one "
                             "another --data");
  }
}

void RunStore::adopt_previous() {
  std::error_code ec;
  std::vector<fs::path> found;
  for (fs::directory_iterator it(data_dir_, ec), end; !ec && it != end; it.increment(ec)) {
    found.push_back(it->path());
  }
  std::sort(found.begin(), found.end());
  for (const auto& p : found) {
    const auto name = p.filename().string();
    if (name.rfind("upload-", 0) == 0) {  // half-written: an upload is a run whole or not at all
      fs::remove_all(p, ec);
    } else if (is_run_id(name) && fs::is_directory(p, ec)) {
      if (!registry_.adopt(read_entry(p))) spdlog::warn("serve: {} not adopted", p.string());
    } else if (is_run_id(name)) {
      spdlog::warn("serve: {} is not a run folder; skipped", p.string());
    }
  }
  if (!registry_.list().empty()) {
    spdlog::info("serve: {} runs adopted from {}", registry_.list().size(), data_dir_.string());
  }
}

std::string RunStore::fresh_id(const std::string& map_name, std::size_t robots, bool done) {
  for (;;) {
    auto id = done ? registry_.add_done(map_name, robots) : registry_.add(map_name, robots);
    std::error_code ec;
    if (!fs::exists(dir(id), ec) && !ec) return id;
    spdlog::warn("serve: {} is taken by something else in the data folder; skipped", id);
    registry_.drop(id);
  }
}

fs::path RunStore::results_file(const std::string& id, std::string_view name) const {
  return dir(id) / "results" / name;
}

fs::path RunStore::stage() {
  std::lock_guard lock(m_);
  for (;;) {  // a fresh folder, whatever the data folder holds
    auto p = data_dir_ / ("upload-" + std::to_string(++staged_));
    if (fs::create_directory(p)) return p;
  }
}

std::string RunStore::add_queued(
    const fs::path& staged, const std::string& map_name, std::size_t robots,
    const std::function<std::vector<std::string>(const std::string&)>& argv) {
  std::lock_guard lock(m_);
  auto id = fresh_id(map_name, robots, false);
  fs::rename(staged, dir(id));
  write_entry(dir(id), map_name, robots);
  argv_[id] = argv(id);
  return id;
}

std::string RunStore::add_done(const fs::path& staged, const std::string& map_name,
                               std::size_t robots) {
  std::lock_guard lock(m_);
  auto id = fresh_id(map_name, robots, true);
  fs::rename(staged, dir(id));
  write_entry(dir(id), map_name, robots);
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

std::shared_ptr<const monitor::Adg> RunStore::ended_adg(const std::string& id,
                                                        const monitor::Instance& in) {
  {
    std::lock_guard lock(m_);
    if (auto it = ended_adgs_.find(id); it != ended_adgs_.end()) return it->second;
  }
  const auto csv = results_file(id, results::kSwitchesCsv);
  const auto e = entry(id);
  if (!e || e->state != RunState::kDone || !fs::is_regular_file(csv)) return nullptr;
  const auto times = action_times(id, in);
  auto adg = std::make_shared<const monitor::Adg>(
      serve::ended_adg(in, results::parse_switches_csv(slurp(csv)), *times));
  std::lock_guard lock(m_);
  return ended_adgs_.emplace(id, std::move(adg)).first->second;
}

void RunStore::tend(std::size_t max_running) {
  std::lock_guard lock(m_);
  for (const auto& id : registry_.start_ready(max_running)) {
    try {  // a run that cannot start fails alone (it used to end the server: std::terminate)
      children_.emplace(id, common::ChildProcess(argv_.at(id), dir(id) / "run.out"));
      spdlog::info("serve: {} started", id);
    } catch (const std::exception& e) {
      registry_.finish(id, false, std::string("could not start: ") + e.what());
      spdlog::error("serve: {} could not start: {}", id, e.what());
    }
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
