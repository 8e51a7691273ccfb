#include "smart/record/import.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "smart/dds/topics.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/record/cdr.hpp"

namespace smart::record {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr std::string_view kInputKeys[] = {results::summary_key::kMap, results::summary_key::kScen,
                                           results::summary_key::kPlan,
                                           results::summary_key::kRobot};
constexpr const char* kStateType = "smart::msg::RobotState";

class FileSource : public ByteSource {
 public:
  explicit FileSource(const fs::path& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw std::invalid_argument(path.string() + ": cannot be read; check the name");
  }
  std::size_t read(char* out, std::size_t n) override {
    in_.read(out, static_cast<std::streamsize>(n));
    if (in_.bad()) throw std::runtime_error(path_.string() + ": read failed");
    return static_cast<std::size_t>(in_.gcount());
  }

 private:
  fs::path path_;
  std::ifstream in_;
};

void write_file(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error(path.string() + ": cannot be written; check the folder");
}

// A name from the file, reduced to one harmless path component.
std::string safe_file_name(std::string_view name) {
  std::string out;
  for (const char c : name.substr(0, 100)) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_';
    out.push_back(ok ? c : '_');
  }
  while (!out.empty() && out.front() == '.') out.erase(0, 1);
  return out.empty() ? "file" : out;
}

class Importer : public McapVisitor {
 public:
  Importer(const fs::path& mcap, const fs::path& dir, const ImportOptions& options,
           ImportReport& report)
      : mcap_(mcap.string()), dir_(dir), options_(options), report_(report) {}

  void schema(const McapSchemaInfo& s) override { schema_names_[s.id] = s.name; }
  void channel(const McapChannelInfo& c) override;
  void message(const McapMessageView& m) override;
  void attachment(const McapAttachmentView& a) override;
  void finish();

 private:
  void add_state(const McapMessageView& m);
  void flush_states(bool last);
  void add_input(std::string_view name, std::string_view data);

  std::string mcap_;
  fs::path dir_;
  const ImportOptions& options_;
  ImportReport& report_;
  std::map<uint16_t, std::string> schema_names_;
  std::optional<uint16_t> state_channel_;
  std::optional<std::ofstream> states_out_;
  std::string states_;  // rows not yet written
  uint64_t states_bytes_ = 0;
  std::optional<std::string> summary_;
  std::set<std::string, std::less<>> seen_;
  std::map<std::string, std::string> inputs_;  // summary "files" key -> imported path
};

void Importer::channel(const McapChannelInfo& c) {
  if (c.topic != smart_msg_TOPIC_STATE) return;
  const auto it = schema_names_.find(c.schema_id);
  if (it == schema_names_.end() || it->second != kStateType || c.message_encoding != "cdr") {
    throw std::invalid_argument(mcap_ + ": channel " + c.topic + " is not CDR " + kStateType +
                                "; the recording was not made by `smart run --mcap`");
  }
  state_channel_ = c.id;
}

void Importer::message(const McapMessageView& m) {
  if (state_channel_ && m.channel.id == *state_channel_) add_state(m);
}

void Importer::add_state(const McapMessageView& m) {
  smart_msg_RobotState s{};
  auto fail = [&](const std::string& what) {
    throw std::invalid_argument(mcap_ + ": " + std::string(smart_msg_TOPIC_STATE) + " message " +
                                std::to_string(report_.states + 1) + " (log time " +
                                std::to_string(m.log_time_ns) + " ns): " + what +
                                "; the recording is damaged, record it again");
  };
  try {
    read_cdr(m.data, s);
  } catch (const std::invalid_argument& e) {
    fail(e.what());
  }
  const results::StateRow row{s.sim_time_s,      s.robot_id,    s.pose.x_m,      s.pose.y_m,
                              s.pose.yaw_rad,    s.linear_mps,  s.angular_radps, s.wheel_left_mps,
                              s.wheel_right_mps, s.queue_length};
  for (const double v : {row.t_s, row.x_m, row.y_m, row.yaw_rad, row.v_mps, row.w_radps,
                         row.left_mps, row.right_mps}) {
    if (!std::isfinite(v))
      fail("robot " + std::to_string(row.robot) + " has a number that is not finite");
  }
  if (!states_out_) {
    states_out_.emplace(dir_ / results::kStatesCsv, std::ios::binary);
    states_.append(results::kStatesHeader).push_back('\n');
    report_.files.emplace_back(results::kStatesCsv);
  }
  append_row(states_, row);
  ++report_.states;
  if (states_.size() >= (std::size_t{1} << 20)) flush_states(false);
}

void Importer::flush_states(bool last) {
  if (!states_out_) return;
  states_bytes_ += states_.size();
  if (states_bytes_ > options_.max_states_bytes) {
    throw std::invalid_argument(mcap_ + ": its states would make a states.csv of more than " +
                                std::to_string(options_.max_states_bytes) +
                                " bytes; it is not a run recorded here");
  }
  states_out_->write(states_.data(), static_cast<std::streamsize>(states_.size()));
  states_.clear();
  if (last) states_out_->close();
  if (!*states_out_) {
    throw std::runtime_error((dir_ / results::kStatesCsv).string() + ": write failed (disk full?)");
  }
}

void Importer::attachment(const McapAttachmentView& a) {
  const std::string name(a.name);
  if (!seen_.insert(name).second) {
    throw std::invalid_argument(mcap_ + ": attachment " + name +
                                " appears twice; the recording "
                                "was not made here or is damaged");
  }
  if (name == results::kSummaryJson) {
    summary_ = std::string(a.data);
  } else if ((results::is_results_file(name) && name != results::kStatesCsv) ||
             name == results::kLifelongMap) {
    write_file(dir_ / name, a.data);
    report_.files.push_back(name);
  } else if (name.rfind(kInputAttachmentPrefix, 0) == 0) {
    add_input(std::string_view(name).substr(kInputAttachmentPrefix.size()), a.data);
  } else {
    report_.notes.push_back("attachment '" + safe_file_name(name) + "' skipped: not a run's file");
  }
}

void Importer::add_input(std::string_view name, std::string_view data) {
  const auto slash = name.find('/');
  const auto key = name.substr(0, slash);
  if (slash == std::string_view::npos ||
      std::find(std::begin(kInputKeys), std::end(kInputKeys), key) == std::end(kInputKeys)) {
    report_.notes.push_back("attachment 'input/" + safe_file_name(name) +
                            "' skipped: not a run's map, scen, plan or robot");
    return;
  }
  const fs::path folder = dir_ / "inputs" / std::string(key);
  fs::create_directories(folder);
  const fs::path file = folder / safe_file_name(name.substr(slash + 1));
  write_file(file, data);
  inputs_[std::string(key)] = fs::absolute(file).string();
  report_.files.push_back(fs::relative(file, dir_).string());
}

void Importer::finish() {
  flush_states(true);
  const std::string not_ours =
      "; it was not recorded by `smart run --mcap` or `smart export mcap` "
      "(open other recordings in Foxglove)";
  if (!summary_) throw std::invalid_argument(mcap_ + ": no summary.json attachment" + not_ours);
  if (!state_channel_) {
    throw std::invalid_argument(mcap_ + ": no " + std::string(smart_msg_TOPIC_STATE) + " channel" +
                                not_ours);
  }
  json summary = json::parse(*summary_, nullptr, false);
  if (!summary.is_object()) {
    throw std::invalid_argument(mcap_ + ": attachment summary.json is not a JSON object" +
                                not_ours);
  }
  auto& files = summary[results::summary_key::kFiles];
  if (!files.is_object()) files = json::object();
  for (const auto& [key, path] : inputs_) files[key] = path;
  write_file(dir_ / results::kSummaryJson, summary.dump(2) + "\n");
  report_.files.emplace_back(results::kSummaryJson);
}

}  // namespace

ImportReport import_mcap(const fs::path& mcap, const fs::path& results_dir,
                         const ImportOptions& options) {
  ImportReport report;
  fs::create_directories(results_dir);
  FileSource source(mcap);
  Importer importer(mcap, results_dir, options, report);
  read_mcap(source, importer, mcap.string(), options.limits);
  importer.finish();
  return report;
}

}  // namespace smart::record
