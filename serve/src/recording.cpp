#include "smart/serve/recording.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>

#include "smart/monitor/results_format.hpp"

namespace smart::serve {

namespace {
constexpr uint32_t kVersion = 2;
constexpr std::size_t kHeader = 4 + 3 * 4 + 3 * 8;
constexpr std::size_t kPerRobot = 7;

template <class T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}
template <class T>
T get(std::string_view in, std::size_t& at) {
  if (at + sizeof(T) > in.size()) throw std::invalid_argument("recording is truncated");
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

}  // namespace

std::vector<PoseRow> parse_states_csv(std::string_view text) {
  std::vector<PoseRow> rows;
  results::for_each_state_row(text, [&](const results::StateRow& s) {
    rows.push_back({s.t_s, s.robot, s.x_m, s.y_m, s.yaw_rad, s.queue});
  });
  return rows;
}

namespace {
constexpr std::size_t kHeaderBytes = 4 + 3 * 4 + 3 * 8, kPoseBytes = 2 + 2 + 2 + 1;
}  // namespace

std::size_t recording_bytes(const std::vector<PoseRow>& rows) {
  uint32_t robots = 0;
  std::set<double> times;
  for (const auto& r : rows) {
    robots = std::max(robots, r.robot + 1);
    times.insert(r.t_s);
  }
  return kHeaderBytes + times.size() * (4 + std::size_t{robots} * kPoseBytes);
}

void check_recording_size(const std::vector<PoseRow>& rows, std::size_t csv_bytes) {
  const std::size_t limit =
      std::min(kMaxRecordingBytes, kRecordingPerCsvByte * csv_bytes + (1 << 20));
  const std::size_t bytes = recording_bytes(rows);
  if (bytes <= limit) return;
  throw std::invalid_argument(
      "states.csv would make a recording of " + std::to_string(bytes >> 20) +
      " MB (every robot "
      "in every one of its time stamps), more than the " +
      std::to_string(limit >> 20) +
      " MB allowed for its size: give the states.csv `smart run --out` wrote");
}

std::string encode_recording(const std::vector<PoseRow>& rows) {
  uint32_t robots = 0;
  double min_x = 0, min_y = 0, max_x = 1, max_y = 1;
  if (!rows.empty()) min_x = max_x = rows[0].x_m, min_y = max_y = rows[0].y_m;
  std::map<double, std::vector<const PoseRow*>> frames;
  for (const auto& r : rows) {
    robots = std::max(robots, r.robot + 1);
    min_x = std::min(min_x, r.x_m), max_x = std::max(max_x, r.x_m);
    min_y = std::min(min_y, r.y_m), max_y = std::max(max_y, r.y_m);
    frames[r.t_s].push_back(&r);
  }
  const double quantum = std::max({max_x - min_x, max_y - min_y, 1e-3}) / 65535.0;
  std::string out = "SMRC";
  put(out, kVersion), put(out, robots), put(out, static_cast<uint32_t>(frames.size()));
  put(out, min_x), put(out, min_y), put(out, quantum);
  std::vector<uint16_t> qx(robots, 0), qy(robots, 0);
  std::vector<int16_t> yaw(robots, 0);
  std::vector<uint8_t> queue(robots, 0);
  for (const auto& [t, frame] : frames) {
    for (const PoseRow* r : frame) {
      queue[r->robot] = static_cast<uint8_t>(std::min<uint32_t>(r->queue, 255));
      qx[r->robot] = static_cast<uint16_t>(std::lround((r->x_m - min_x) / quantum));
      qy[r->robot] = static_cast<uint16_t>(std::lround((r->y_m - min_y) / quantum));
      const double wrapped = std::remainder(r->yaw_rad, 2 * M_PI);
      yaw[r->robot] = static_cast<int16_t>(std::lround(wrapped * 1e4));
    }
    put(out, static_cast<float>(t));
    for (uint32_t i = 0; i < robots; ++i) {
      put(out, qx[i]), put(out, qy[i]), put(out, yaw[i]), put(out, queue[i]);
    }
  }
  return out;
}

void PoseTail::feed(std::string_view appended) {
  partial_.append(appended);
  std::size_t start = 0;
  for (std::size_t nl; (nl = partial_.find('\n', start)) != std::string::npos; start = nl + 1) {
    std::string_view line(partial_.data() + start, nl - start);
    if (!header_seen_) {
      header_seen_ = true;
      continue;
    }
    const auto s = results::parse_state_line(line);
    if (!s || s->robot > 1000000) continue;  // the tail keeps a pose per robot id
    if (latest_.size() <= s->robot) latest_.resize(s->robot + 1);
    latest_[s->robot] = *s;
    time_s_ = std::max(time_s_, s->t_s);
  }
  partial_.erase(0, start);
}

const char* live_status(const results::StateRow& s) {
  // Below these a simulated robot stands still (its controller stops within centimetres per
  // second; sim states carry no sensor noise).
  constexpr double kMovingMps = 0.01, kTurningRadps = 0.02;
  if (std::abs(s.v_mps) > kMovingMps || std::abs(s.w_radps) > kTurningRadps) return "moving";
  return s.queue > 0 ? "waiting" : "idle";
}

Recording decode_recording(std::string_view in) {
  if (in.size() < kHeader || in.substr(0, 4) != "SMRC") {
    throw std::invalid_argument("not a SMART-DDS recording (no SMRC header)");
  }
  std::size_t at = 4;
  if (get<uint32_t>(in, at) != kVersion) throw std::invalid_argument("recording version is not 2");
  Recording rec;
  rec.robots = get<uint32_t>(in, at);
  const auto frames = get<uint32_t>(in, at);
  if (rec.robots > 10000000) throw std::invalid_argument("recording claims too many robots");
  const auto min_x = get<double>(in, at), min_y = get<double>(in, at), q = get<double>(in, at);
  if (in.size() != kHeader + std::size_t{frames} * (4 + std::size_t{rec.robots} * kPerRobot)) {
    throw std::invalid_argument("recording size does not match its header");
  }
  for (uint32_t f = 0; f < frames; ++f) {
    rec.times_s.push_back(get<float>(in, at));
    for (uint32_t r = 0; r < rec.robots; ++r) {
      const auto x = get<uint16_t>(in, at), y = get<uint16_t>(in, at);
      const auto yaw = get<int16_t>(in, at);
      const auto queue = get<uint8_t>(in, at);
      rec.poses.push_back({rec.times_s.back(), r, min_x + x * q, min_y + y * q, yaw * 1e-4, queue});
    }
  }
  return rec;
}

}  // namespace smart::serve
