#include "smart/serve/server.hpp"

#include <httplib.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "slurp.hpp"
#include "smart/agent/robot_model.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/serve/bounded_json.hpp"
#include "smart/serve/content_policy.hpp"
#include "smart/serve/recording.hpp"
#include "smart/serve/robot_detail.hpp"
#include "smart/serve/run_store.hpp"
#include "smart/serve/task_timeline.hpp"
#include "smart/serve/upload_budget.hpp"
#include "uploads.hpp"

namespace smart::serve {

namespace fs = std::filesystem;
using nlohmann::json;
namespace key = results::summary_key;

namespace {

void reply(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

// An upload's scratch folder, removed unless it became a run (also when a check throws).
class Staged {
 public:
  explicit Staged(fs::path p) : path_(std::move(p)) {}
  Staged(const Staged&) = delete;
  Staged& operator=(const Staged&) = delete;
  ~Staged() {
    std::error_code ec;
    if (!kept_) fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  void keep() { kept_ = true; }

 private:
  fs::path path_;
  bool kept_ = false;
};

bool loopback(const std::string& address) {
  return address == "127.0.0.1" || address == "::1" || address == "localhost";
}

// Live streams open now; the guard counts one while its stream lives.
// The request's Content-Length, when it has a valid one.
std::optional<std::size_t> content_length(const httplib::Request& req) {
  const auto text = req.get_header_value("Content-Length");
  if (text.empty() || text.size() > 18 ||
      text.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  return static_cast<std::size_t>(std::stoull(text));
}

struct StreamSlot {
  std::shared_ptr<std::atomic<std::size_t>> open;
  bool taken = false;
};
}  // namespace

// The routes: each reads the request, asks the run store or the upload checks, and answers.
struct Server::Impl {
  ServeOptions opt;
  httplib::Server http;
  RunStore store;
  std::atomic<bool> stopping{false};
  std::shared_ptr<std::atomic<std::size_t>> streams = std::make_shared<std::atomic<std::size_t>>(0);
  UploadBudget uploads;  // what all uploads being read hold at once

  explicit Impl(ServeOptions o)
      : opt(std::move(o)), store(opt.data_dir), uploads(opt.max_upload_memory_bytes) {}

  // An upload's multipart fields, read as they arrive within the upload budget (one copy, not
  // cpp-httplib's body plus its parsed fields) and only once the writer may write: the request
  // with its files, or nothing (answered: 400, 401/403, 503 when the budget is spent).
  std::optional<httplib::Request> read_upload(const httplib::Request& req, httplib::Response& res,
                                              const httplib::ContentReader& content) {
    if (!may_write(req, res)) return std::nullopt;
    if (!req.is_multipart_form_data()) {
      reply(res, 400, {{"error", "expected a multipart/form-data upload (an HTML form's files)"}});
      return std::nullopt;
    }
    httplib::Request out = req;
    UploadBudget::Lease lease(uploads);
    // The whole upload is reserved before its body is read, when its length is known: first come,
    // first served (taking bit by bit, concurrent uploads starved each other); else as it comes.
    const auto length = content_length(req);
    bool over = length && !lease.take(*length);
    auto field = out.files.end();
    const bool read = content(
        [&](const httplib::MultipartFormData& f) {
          field = out.files.emplace(f.name, f);
          return true;
        },
        [&](const char* data, std::size_t n) {
          // Past the budget the rest is read and dropped (at most --max-upload-mb), so that the
          // client is still listening for the 503.
          over = over || (!length && !lease.take(n));
          if (!over && field != out.files.end()) field->second.content.append(data, n);
          return true;
        });
    if (over && read) {
      reply(res, 503,
            {{"error", "the server is reading other uploads (" +
                           std::to_string(uploads.capacity() >> 20) +
                           " MB at once); send it again in a moment"}});
      return std::nullopt;
    }
    if (!read) {
      reply(res, 400, {{"error", "the upload was cut off or is not valid multipart/form-data"}});
      return std::nullopt;
    }
    return out;
  }

  fs::path dir(const std::string& id) const { return store.dir(id); }
  std::optional<RunEntry> entry(const std::string& id) const { return store.entry(id); }

  // Write endpoints: with --token, only with it; bound beyond loopback without one, never.
  bool may_write(const httplib::Request& req, httplib::Response& res) const {
    if (opt.token.empty() && !loopback(opt.bind)) {
      reply(res, 403,
            {{"error", "uploads are off: this server listens on " + opt.bind +
                           " without --token; restart it with --token SECRET"}});
      return false;
    }
    if (!opt.token.empty() && req.get_header_value("Authorization") != "Bearer " + opt.token) {
      reply(res, 401,
            {{"error",
              "this server needs its token: send \"Authorization: Bearer "
              "TOKEN\" (the viewer: open it with #token=TOKEN)"}});
      return false;
    }
    return true;
  }

  void post_run(const httplib::Request& req, httplib::Response& res) {
    if (!may_write(req, res)) return;
    auto r = upload::read_fields(req, opt.config_dir / "robots");
    if (!r.error.empty()) return reply(res, 400, {{"error", r.error}, {"problems", json::array()}});
    if (store.queued() >= opt.max_queued) {
      return reply(res, 503,
                   {{"error", std::to_string(store.queued()) +
                                  " runs are queued already; upload again later"}});
    }
    Staged staged(store.stage());
    auto bad = upload::write_robot(staged.path(), opt.config_dir, r);  // first: with its robot
    if (!bad) bad = upload::check_run(req, staged.path(), r);
    if (bad) return reply(res, 400, *bad);
    if (!r.lifelong)
      std::ofstream(staged.path() / "request.json") << upload::request_json(r).dump();
    const auto id = store.add_queued(
        staged.path(), upload::run_name(req, r), r.agents,
        [&](const std::string& run) { return upload::run_argv(opt, dir(run), r); });
    staged.keep();
    reply(res, 200, {{"id", id}});
  }

  // A checked replay becomes a done run.
  std::string adopt(const fs::path& staged) {
    const auto [map, robots] = upload::replay_entry(staged);
    return store.add_done(staged, map, robots);
  }

  // POST /api/results: a results folder (fields "files", many) with the run's map (and scen and
  // plan for the robot panel), replayed like --open.
  void post_results(const httplib::Request& req, httplib::Response& res) {
    if (!may_write(req, res)) return;
    Staged guard(store.stage());
    const fs::path& staged = guard.path();
    fs::create_directories(staged / "results");
    const auto [first, last] = req.files.equal_range("files");
    for (auto it = first; it != last; ++it) {
      const auto name = fs::path(it->second.filename).filename().string();
      if (results::is_results_file(name)) {
        std::ofstream(staged / "results" / name) << it->second.content;
      }
    }
    for (const auto& [field, name] : kRunFiles) {
      if (req.has_file(field)) std::ofstream(staged / name) << req.get_file_value(field).content;
    }
    if (auto bad = upload::check_results(staged)) return reply(res, 400, *bad);
    const auto id = adopt(staged);
    guard.keep();
    reply(res, 200, {{"id", id}});
  }

  // GET /api/runs/{id}/results/{name}: a results file as a download, streamed from disk.
  void get_result_file(const std::string& id, const std::string& name, httplib::Response& res) {
    const auto path = store.results_file(id, name);
    if (!entry(id) || !results::is_results_file(name) || !fs::is_regular_file(path)) {
      return reply(res, 404, {{"error", "no " + name + " in the results of " + id}});
    }
    res.set_header("Content-Disposition", "attachment; filename=\"" + id + "-" + name + "\"");
    auto in = std::make_shared<std::ifstream>(path, std::ios::binary);
    res.set_content_provider(
        fs::file_size(path), name.ends_with(".json") ? "application/json" : "text/csv",
        [in](size_t offset, size_t length, httplib::DataSink& sink) {
          std::vector<char> buf(std::min<size_t>(length, 1 << 16));
          in->seekg(static_cast<std::streamoff>(offset));
          in->read(buf.data(), static_cast<std::streamsize>(buf.size()));
          return in->gcount() > 0 && sink.write(buf.data(), static_cast<size_t>(in->gcount()));
        });
  }

  json entry_json(const RunEntry& e) const {
    return {{"id", e.id},
            {"state", to_string(e.state)},
            {"map", e.map_name},
            {"robots", e.robots},
            {"error", e.error}};
  }

  void get_run(const std::string& id, httplib::Response& res) {
    const auto e = entry(id);
    if (!e) return reply(res, 404, {{"error", "no run " + id}});
    json j = entry_json(*e);
    const auto summary = store.results_file(id, results::kSummaryJson);
    if (e->state == RunState::kDone && fs::exists(summary)) {
      try {
        j["summary"] = parse_bounded_json(slurp(summary), "summary.json of " + id);
      } catch (const std::invalid_argument& ex) {
        j["summary_error"] = ex.what();
      }
    }
    j["files"] = json::array();
    for (const auto f : results::kFiles) {
      if (e->state == RunState::kDone && fs::exists(store.results_file(id, f)))
        j["files"].push_back(f);
    }
    reply(res, 200, j);
  }

  void get_recording(const std::string& id, httplib::Response& res) {
    const auto e = entry(id);
    const auto states = store.results_file(id, results::kStatesCsv);
    if (!e || e->state != RunState::kDone || !fs::exists(states)) {
      return reply(res, 404, {{"error", "no recording of " + id + " (yet)"}});
    }
    const auto cached = dir(id) / "recording-v2.smrc";
    if (!fs::exists(cached)) {
      const auto text = slurp(states);
      const auto rows = parse_states_csv(text);
      try {
        check_recording_size(rows, text.size());
      } catch (const std::invalid_argument& ex) {
        return reply(res, 413, {{"error", ex.what()}});
      }
      std::ofstream(cached, std::ios::binary) << encode_recording(rows);
    }
    res.set_content(slurp(cached), "application/octet-stream");
  }

  // The run's newest progress.csv row (the file's last few hundred bytes), if any yet.
  std::optional<results::ProgressRow> live_progress(const std::string& id) {
    std::ifstream in(store.results_file(id, results::kProgressCsv),
                     std::ios::binary | std::ios::ate);
    if (!in) return std::nullopt;
    const auto size = static_cast<std::streamoff>(in.tellg());
    in.seekg(std::max<std::streamoff>(0, size - 256));
    const std::string tail((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return results::last_progress_row(tail);
  }

  // One event per call, paced; the stream ends after the event that shows the run ended.
  bool live_event(const std::string& id, PoseTail& tail, std::uintmax_t& offset,
                  httplib::DataSink& sink) {
    const auto e = entry(id);
    const auto states = store.results_file(id, results::kStatesCsv);
    std::ifstream in(states, std::ios::binary);
    if (in && in.seekg(static_cast<std::streamoff>(offset))) {
      std::string chunk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      offset += chunk.size();
      tail.feed(chunk);
    }
    json poses = json::array(), status = json::array(), queue = json::array();
    for (const auto& p : tail.latest()) {
      poses.push_back({p.x_m, p.y_m, p.yaw_rad});
      status.push_back(live_status(p));
      queue.push_back(p.queue);
    }
    json event = {{"state", std::string(to_string(e->state))},
                  {"t_s", tail.time_s()},
                  {"poses", poses},
                  {"status", status},
                  {"queue", queue}};
    if (const auto p = live_progress(id)) {
      event["progress"] = {{"t_s", p->t_s}, {"finished", p->finished}, {"total", p->total}};
    }
    // Written by the run this server started (never uploaded): each robot's finished actions.
    const auto finished =
        results::parse_finished_csv(slurp(store.results_file(id, results::kFinishedCsv)));
    if (finished.size() == tail.latest().size()) event["finished"] = finished;
    const auto msg = "data: " + event.dump() + "\n\n";
    if (!sink.write(msg.data(), msg.size())) return false;
    if (e->state == RunState::kDone || e->state == RunState::kFailed) {
      sink.done();
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
    return true;
  }

  // A live stream holds a request thread while it is open: at most max_live_streams at once.
  template <class Provider>
  void stream(httplib::Response& res, Provider provider) {
    if (streams->fetch_add(1) >= opt.max_live_streams) {
      streams->fetch_sub(1);
      return reply(res, 503,
                   {{"error", std::to_string(opt.max_live_streams) +
                                  " live streams are open; close one (another tab)"}});
    }
    res.set_chunked_content_provider("text/event-stream", std::move(provider),
                                     [open = streams](bool) { open->fetch_sub(1); });
  }

  void get_live(const std::string& id, httplib::Response& res) {
    if (!entry(id)) return reply(res, 404, {{"error", "no run " + id}});
    auto tail = std::make_shared<PoseTail>();
    auto offset = std::make_shared<std::uintmax_t>(0);
    stream(res, [this, id, tail, offset](size_t, httplib::DataSink& sink) {
      return live_event(id, *tail, *offset, sink);
    });
  }

  // The run's instance (plan, actions, ADG) and its actions' finish times, loaded once.
  std::shared_ptr<const monitor::Instance> instance(const std::string& id) {
    return store.instance(id, upload::load_run);
  }
  std::shared_ptr<const std::vector<double>> times(const std::string& id) {
    return store.action_times(id, *instance(id));
  }

  // Finished actions over time (the stats panel's plot), from actions.csv.
  void get_progress(const std::string& id, httplib::Response& res) {
    const auto e = entry(id);
    if (!e || !fs::exists(dir(id) / "request.json")) {
      return reply(res, 404, {{"error", "no finished actions of " + id + " (no plan files)"}});
    }
    try {
      reply(res, 200, finished_curve(*times(id)));
    } catch (const std::exception& ex) {
      reply(res, 404, {{"error", ex.what()}});
    }
  }

  // A lifelong run's tasks and throughput (task_timeline.hpp), from its results files.
  void get_tasks(const std::string& id, httplib::Response& res) {
    const auto e = entry(id);
    if (!e || !fs::exists(store.results_file(id, results::kEventsCsv))) {
      return reply(res, 404, {{"error", "no tasks of " + id + " (not a lifelong run)"}});
    }
    // Whole lines only: a running run may be writing its last one.
    const auto text = [&](std::string_view name) {
      const auto f = store.results_file(id, name);
      auto t = fs::exists(f) ? slurp(f) : std::string();
      t.resize(t.rfind('\n') == std::string::npos ? 0 : t.rfind('\n') + 1);
      return t;
    };
    try {
      reply(res, 200,
            task_timeline(text(results::kTasksCsv), text(results::kEventsCsv),
                          text(results::kThroughputCsv)));
    } catch (const std::invalid_argument& ex) {
      reply(res, 422, {{"error", ex.what()}});
    }
  }

  // A switchable run's switches of passing orders (issue 29), column-wise for the viewer:
  // {t_s, x, y, first, second} (x, y in cells); 404 for a run that never switched.
  void get_switches(const std::string& id, httplib::Response& res) {
    const auto e = entry(id);
    const auto f = store.results_file(id, results::kSwitchesCsv);
    if (!e || e->state != RunState::kDone || !fs::is_regular_file(f)) {
      return reply(res, 404, {{"error", "no switches of " + id + " (not a switchable run)"}});
    }
    try {
      json t = json::array(), x = json::array(), y = json::array(), first = json::array(),
           second = json::array();
      for (const auto& r : results::parse_switches_csv(slurp(f))) {
        t.push_back(r.time_s);
        x.push_back(r.x);
        y.push_back(r.y);
        first.push_back(r.first);
        second.push_back(r.second);
      }
      reply(res, 200, {{"t_s", t}, {"x", x}, {"y", y}, {"first", first}, {"second", second}});
    } catch (const std::invalid_argument& ex) {
      reply(res, 422, {{"error", ex.what()}});
    }
  }

  // robots.csv's row of `robot` as JSON (finish and waiting time, stops, lower bound), if the
  // run wrote one; an unknown value (not finished, bound unknown) is null.
  json robot_results(const std::string& id, uint32_t robot) const {
    const auto csv = store.results_file(id, results::kRobotsCsv);
    if (!fs::is_regular_file(csv)) return json::object();
    const auto or_null = [](const std::optional<double>& v) { return v ? json(*v) : json(); };
    for (const auto& row : results::parse_robots_csv(slurp(csv))) {
      if (row.robot != robot) continue;
      return {{"finish_time_s", or_null(row.finish_time_s)},
              {"waiting_time_s", row.waiting_time_s},
              {"stops", row.stops},
              {"lower_bound_s", or_null(row.lower_bound_s)}};
    }
    return json::object();
  }

  void get_robot(const std::string& id, const std::string& robot_text, httplib::Response& res) {
    const auto e = entry(id);
    if (!e || !fs::exists(dir(id) / "request.json") ||
        robot_text.find_first_not_of("0123456789") != std::string::npos || robot_text.size() > 7) {
      return reply(res, 404, {{"error", "no robot " + robot_text + " in " + id}});
    }
    try {
      const auto robot = static_cast<uint32_t>(std::stoul(robot_text));
      const auto in = instance(id);
      const auto ended = store.ended_adg(id, *in);
      json j = robot_detail(*in, robot, summary_cell_m(id), *times(id), ended.get());
      j["results"] = robot_results(id, robot);
      reply(res, 200, j);
    } catch (const std::exception& ex) {
      reply(res, 404, {{"error", ex.what()}});
    }
  }

  double summary_cell_m(const std::string& id) const {
    const auto s = store.results_file(id, results::kSummaryJson);
    if (!fs::exists(s)) return 1.0;
    try {
      const auto j = parse_bounded_json(slurp(s), "summary.json");
      return j.is_object() && j[key::kCellM].is_number() ? j[key::kCellM].get<double>() : 1.0;
    } catch (const std::invalid_argument&) {
      return 1.0;
    }
  }

  // GET /api/robots: the robot models an upload may name, with their limits (the form's
  // sliders start there).
  void get_robots(httplib::Response& res) const {
    json out = json::array();
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(opt.config_dir / "robots")) {
      if (e.path().extension() == ".yaml" && upload::plain_name(e.path().stem().string())) {
        files.push_back(e.path());
      }
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      try {
        const auto m = agent::load_robot_model(f.string());
        out.push_back({{"name", f.stem().string()},
                       {"max_speed_mps", m.max_speed_mps},
                       {"max_accel_mps2", m.max_accel_mps2},
                       {"max_turn_rate_radps", m.max_turn_rate_radps}});
      } catch (const std::exception& e) {
        spdlog::warn("serve: robot model {} not offered: {}", f.string(), e.what());
      }
    }
    reply(res, 200, out);
  }

  // --watch: the board as JSON, once or as a stream (until the page goes away).
  void watch_routes() {
    const auto run_of = [](const httplib::Request& req) -> uint64_t {
      const auto v = req.get_param_value("run_id");
      uint64_t id = 0;
      std::from_chars(v.data(), v.data() + v.size(), id);
      return id;
    };
    http.Get("/api/watch", [this, run_of](const auto& req, auto& res) {
      if (!opt.watch)
        return reply(res, 404, {{"error", "not watching: start smart serve --watch"}});
      auto j = opt.watch(run_of(req));
      j["cell_m"] = opt.watch_cell_m;
      if (opt.watch_plan) j["total_actions"] = opt.watch_plan->actions.actions.size();
      reply(res, 200, j);
    });
    http.Get(R"(/api/watch/robots/(\d{1,7}))", [this](const auto& req, auto& res) {
      if (!opt.watch_plan) return reply(res, 404, {{"error", "no plan: give --plan with --watch"}});
      try {
        const auto robot = static_cast<uint32_t>(std::stoul(req.matches[1].str()));
        reply(res, 200, robot_detail(*opt.watch_plan, robot, opt.watch_cell_m));
      } catch (const std::exception& ex) {
        reply(res, 404, {{"error", ex.what()}});
      }
    });
    http.Get("/api/watch/map", [this](const auto&, auto& res) {
      if (opt.watch_map.empty()) return reply(res, 404, {{"error", "no map: give --map"}});
      res.set_content(slurp(opt.watch_map), "text/plain");
    });
    http.Get("/api/watch/live", [this, run_of](const auto& req, auto& res) {
      if (!opt.watch)
        return reply(res, 404, {{"error", "not watching: start smart serve --watch"}});
      const uint64_t run = run_of(req);
      stream(res, [this, run](size_t, httplib::DataSink& sink) {
        if (stopping.load()) return false;  // the server is going down: end the stream
        const auto msg = "data: " + opt.watch(run).dump() + "\n\n";
        if (!sink.write(msg.data(), msg.size())) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(250));
        return true;
      });
    });
  }

  // What no client may take: threads (slow or streaming clients each hold one), time to send a
  // request, an answer's exception text; and what no page may run (issue 25).
  void limits() {
    http.new_task_queue = [n = opt.threads] { return new httplib::ThreadPool(n); };
    http.set_read_timeout(opt.read_timeout_s, 0);
    http.set_write_timeout(opt.read_timeout_s, 0);
    http.set_keep_alive_timeout(2);
    http.set_keep_alive_max_count(100);
    http.set_exception_handler([](const auto& req, auto& res, const std::exception_ptr& ep) {
      try {
        std::rethrow_exception(ep);
      } catch (const std::exception& e) {
        spdlog::error("serve: {} {} failed: {}", req.method, req.path, e.what());
      } catch (...) {
        spdlog::error("serve: {} {} failed", req.method, req.path);
      }
      reply(res, 500, {{"error", "internal error; the server's log says more"}});
    });
    // Data is shown as text (web/src/page.js setRows); the policy forbids scripts that are not
    // the app's own (content_policy.hpp), so markup smuggled into data could not run either.
    const auto index = opt.web_dir.empty() ? std::string() : slurp(opt.web_dir / "index.html");
    http.set_default_headers({{"Content-Security-Policy", content_security_policy(index)},
                              {"X-Content-Type-Options", "nosniff"}});
  }

  void routes() {
    limits();
    // Without TCP_NODELAY (cpp-httplib's default is off) Nagle's algorithm and delayed ACKs held
    // static files back: three.js (0.7 MB) took 1.9 s over loopback, 0.1 s with it.
    http.set_tcp_nodelay(true);
    // cpp-httplib's default sets SO_REUSEPORT too, and a second server on a port in use started
    // and shared its requests (issue 26): only SO_REUSEADDR (a restart may bind at once).
    http.set_socket_options([](int sock) {
      int yes = 1;
      ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });
    watch_routes();
    http.Get("/api/robots", [this](const auto&, auto& res) { get_robots(res); });
    http.set_payload_max_length(opt.max_upload_bytes);
    http.Post("/api/runs", [this](const httplib::Request& req, httplib::Response& res,
                                  const httplib::ContentReader& content) {
      if (const auto upload = read_upload(req, res, content)) post_run(*upload, res);
    });
    http.Get("/api/runs", [this](const auto&, auto& res) {
      json list = json::array();
      for (const auto& e : store.list()) list.push_back(entry_json(e));
      reply(res, 200, list);
    });
    http.Get(R"(/api/runs/([^/]+))",
             [this](const auto& req, auto& res) { get_run(req.matches[1], res); });
    http.Get(R"(/api/runs/([^/]+)/recording)",
             [this](const auto& req, auto& res) { get_recording(req.matches[1], res); });
    http.Get(R"(/api/runs/([^/]+)/map)", [this](const auto& req, auto& res) {
      const std::string id = req.matches[1];
      if (!entry(id) || !fs::exists(dir(id) / "map.map")) {
        return reply(res, 404, {{"error", "no map of " + id}});
      }
      res.set_content(slurp(dir(id) / "map.map"), "text/plain");
    });
    http.Get(R"(/api/runs/([^/]+)/marks)", [this](const auto& req, auto& res) {
      const std::string id = req.matches[1];
      if (!entry(id) || !fs::exists(dir(id) / "request.json")) {
        return reply(res, 404, {{"error", "no plan files for " + id}});
      }
      try {
        reply(res, 200, starts_and_goals(*instance(id), summary_cell_m(id)));
      } catch (const std::exception& ex) {
        reply(res, 404, {{"error", ex.what()}});
      }
    });
    http.Get(R"(/api/runs/([^/]+)/robots/([^/]+))", [this](const auto& req, auto& res) {
      get_robot(req.matches[1], req.matches[2], res);
    });
    http.Post("/api/results", [this](const httplib::Request& req, httplib::Response& res,
                                     const httplib::ContentReader& content) {
      if (const auto upload = read_upload(req, res, content)) post_results(*upload, res);
    });
    http.Get(R"(/api/runs/([^/]+)/progress)",
             [this](const auto& req, auto& res) { get_progress(req.matches[1], res); });
    http.Get(R"(/api/runs/([^/]+)/tasks)",
             [this](const auto& req, auto& res) { get_tasks(req.matches[1], res); });
    http.Get(R"(/api/runs/([^/]+)/switches)",
             [this](const auto& req, auto& res) { get_switches(req.matches[1], res); });
    http.Get(R"(/api/runs/([^/]+)/results/([^/]+))", [this](const auto& req, auto& res) {
      get_result_file(req.matches[1], req.matches[2], res);
    });
    http.Get(R"(/api/runs/([^/]+)/live)",
             [this](const auto& req, auto& res) { get_live(req.matches[1], res); });
    if (!opt.web_dir.empty()) http.set_mount_point("/", opt.web_dir.string());
  }
};

Server::Server(ServeOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {
  impl_->routes();
}

Server::~Server() = default;

std::string Server::open_results(const fs::path& folder) {
  auto& I = *impl_;
  const fs::path scratch = I.store.stage();
  fs::create_directories(scratch / "results");
  for (const auto f : results::kFiles) {
    if (fs::is_regular_file(folder / f)) fs::copy_file(folder / f, scratch / "results" / f);
  }
  // The files the run was made on, when still where summary.json says (for the robot panel).
  json files = json::object();
  if (fs::is_regular_file(folder / results::kSummaryJson)) {
    try {
      const auto summary = parse_bounded_json(slurp(folder / results::kSummaryJson),
                                              (folder / results::kSummaryJson).string());
      if (summary.is_object()) files = summary.value(key::kFiles, files);
    } catch (const std::invalid_argument&) {
      // check_results below names what is wrong with it
    }
  }
  for (const auto& [field, name] : kRunFiles) {
    fs::path src = files.is_object() ? files.value(field, std::string()) : std::string();
    // A lifelong run's map is beside its results (summary.json may name a LoRR problem).
    if (std::string(field) == "map" && fs::is_regular_file(folder / results::kLifelongMap)) {
      src = folder / results::kLifelongMap;
    }
    if (!src.empty() && fs::is_regular_file(src)) fs::copy_file(src, scratch / name);
  }
  if (auto bad = upload::check_results(scratch)) {
    fs::remove_all(scratch);
    throw std::runtime_error("--open " + folder.string() + ": " + bad->value("error", "") +
                             "; give a folder written by `smart run --out`");
  }
  return I.adopt(scratch);
}

int Server::bind() {
  auto& I = *impl_;
  const int port = I.opt.port == 0
                       ? I.http.bind_to_any_port(I.opt.bind)
                       : (I.http.bind_to_port(I.opt.bind, I.opt.port) ? I.opt.port : -1);
  if (port < 0) {
    throw std::runtime_error("cannot listen on " + I.opt.bind + ":" + std::to_string(I.opt.port) +
                             ": the port is in use (another `smart serve`?) or the address is "
                             "not this host's; choose another with --port or --bind");
  }
  return port;
}

void Server::run(const std::atomic<bool>& stop) {
  auto& I = *impl_;
  std::thread listener([&] { I.http.listen_after_bind(); });
  while (!stop.load()) {
    I.store.tend(I.opt.max_running);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  I.stopping = true;
  I.http.stop();
  listener.join();
  I.store.stop_all();
}

}  // namespace smart::serve
