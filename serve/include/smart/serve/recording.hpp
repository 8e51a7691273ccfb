// Contract: the recording a browser plays back, made from a run's robot states (states.csv as
// the monitor writes it, results.hpp). Pure: text or rows in, bytes out, and back.
//
// Format "SMRC" version 2, little endian, fixed size per frame so a viewer can seek by index
// (and draw the first frame from the first bytes, before the rest arrived):
//   char[4] "SMRC"; u32 version = 2; u32 robots; u32 frames;
//   f64 min_x_m, min_y_m, quantum_m   (x_m = min_x_m + qx * quantum_m, same for y)
//   frames x { f32 t_s; robots x { u16 qx; u16 qy; i16 yaw (1e-4 rad); u8 queue } }
// queue: the robot's queue length as its agent reported it (actions sent, not finished; 255 and
// more are 255).
// A frame is one state time stamp; a robot not reported at a time keeps its last pose. The
// quantum is the map extent / 65535 (1 m cells: 7.7 mm on the 500 x 140 sortation map).
// 1000 robots at 2 Hz for 1218 s: 2437 frames of 7 kB, 17.1 MB.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "smart/monitor/results_format.hpp"

namespace smart::serve {

struct PoseRow {
  double t_s = 0;
  uint32_t robot = 0;
  double x_m = 0, y_m = 0, yaw_rad = 0;
  uint32_t queue = 0;
};

// Rows of states.csv; throws std::invalid_argument naming the line of a malformed row.
std::vector<PoseRow> parse_states_csv(std::string_view text);
// The size encode_recording gives these rows (every robot in every frame: a few rows at many
// time stamps of a large fleet make a huge recording, issue 25: 16 KB became 668 MB).
std::size_t recording_bytes(const std::vector<PoseRow>& rows);
// At most this much, and at most kRecordingPerCsvByte times the states.csv it comes from (+1 MB):
// a lock-step run's recording is smaller than its states.csv (7 bytes per pose against ~60); a
// real-time run's states each have their own time stamp, a frame of the whole fleet each
// (100 robots: 12 times the states.csv).
inline constexpr std::size_t kMaxRecordingBytes = std::size_t{1} << 30;
inline constexpr std::size_t kRecordingPerCsvByte = 64;
// Throws std::invalid_argument naming the frames and robots when the rows' recording would be
// larger than those bounds allow for a states.csv of `csv_bytes`.
void check_recording_size(const std::vector<PoseRow>& rows, std::size_t csv_bytes);
std::string encode_recording(const std::vector<PoseRow>& rows);

struct Recording {
  uint32_t robots = 0;
  std::vector<float> times_s;
  std::vector<PoseRow> poses;  // frames x robots, frame-major (decoded, within one quantum)
};
// Throws std::invalid_argument on bytes that are not a version 2 recording.
Recording decode_recording(std::string_view bytes);

// The newest state of every robot from states.csv as it grows (a live run): feed() takes the
// bytes appended since the last call, in any pieces; a partial last line waits for its end.
// Malformed rows are skipped (the file is being written).
class PoseTail {
 public:
  void feed(std::string_view appended);
  const std::vector<results::StateRow>& latest() const { return latest_; }  // by robot id
  double time_s() const { return time_s_; }

 private:
  std::string partial_;
  bool header_seen_ = false;
  std::vector<results::StateRow> latest_;
  double time_s_ = 0;
};

// A live robot's status as the replay colours it (web/src/view.js): "moving" (turning or
// driving), "waiting" (standing with actions queued: its dependencies are not finished) or
// "idle" (standing, nothing queued: done, or between windows).
const char* live_status(const results::StateRow& s);

}  // namespace smart::serve
