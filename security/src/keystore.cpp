#include "smart/security/keystore.hpp"

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "smart/common/child_process.hpp"
#include "smart/config/yaml_checks.hpp"
#include "smart/dds/topics.hpp"

namespace smart::security {

namespace fs = std::filesystem;

namespace {
const std::string kSchema = "http://www.omg.org/spec/DDS-SECURITY/20170901/";

std::string topics_xml(const std::vector<std::string>& topics,
                       const std::vector<std::string>& partitions = {"*"}) {
  std::string x = "<topics>";
  for (const auto& t : topics) x += "<topic>" + t + "</topic>";
  x += "</topics><partitions>";
  for (const auto& p : partitions) x += "<partition>" + p + "</partition>";
  return x + "</partitions>";
}

std::string t(std::string_view name) { return std::string(name); }

std::string utc(std::chrono::system_clock::time_point when) {
  const std::time_t tt = std::chrono::system_clock::to_time_t(when);
  std::tm tm{};
  gmtime_r(&tt, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%S", &tm);
  return buf;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// The openssl program on PATH (ChildProcess spawns by path, without a shell).
std::string openssl_path() {
  const char* path = std::getenv("PATH");
  std::string_view dirs = path ? path : "/usr/bin:/bin";
  while (!dirs.empty()) {
    const auto colon = std::min(dirs.find(':'), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(0, colon)) / "openssl";
    if (fs::is_regular_file(candidate)) return candidate.string();
    dirs.remove_prefix(std::min(colon + 1, dirs.size()));
  }
  throw std::runtime_error(
      "no openssl program on PATH; install the openssl package "
      "(scripts/install-deps.sh)");
}

void openssl(const std::vector<std::string>& args, const std::string& step) {
  std::vector<std::string> argv{openssl_path()};
  argv.insert(argv.end(), args.begin(), args.end());
  common::ChildProcess p(argv, "/dev/null");
  const auto rc = p.wait(std::chrono::seconds(60));
  if (rc.value_or(-1) != 0) {
    throw std::runtime_error("openssl failed to " + step +
                             " (is the openssl package installed? scripts/install-deps.sh)");
  }
}

void sign(const fs::path& dir, const fs::path& in, const fs::path& out) {
  openssl({"smime", "-sign", "-in", in.string(), "-text", "-out", out.string(), "-signer",
           (dir / "ca.pem").string(), "-inkey", (dir / "ca.key").string()},
          "sign " + in.filename().string());
}

void make_identity(const fs::path& dir, const Grant& g, int days, const std::string& from,
                   const std::string& to) {
  const fs::path d = dir / g.identity;
  fs::create_directories(d);
  const std::string subj = "/O=SMART-DDS/CN=" + g.identity;
  openssl({"req", "-new", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes",
           "-keyout", (d / "key.pem").string(), "-out", (d / "cert.csr").string(), "-subj", subj},
          "make the key of " + g.identity);
  fs::permissions(d / "key.pem", fs::perms::owner_read | fs::perms::owner_write);
  openssl({"x509", "-req", "-in", (d / "cert.csr").string(), "-CA", (dir / "ca.pem").string(),
           "-CAkey", (dir / "ca.key").string(), "-CAcreateserial", "-out",
           (d / "cert.pem").string(), "-days", std::to_string(days)},
          "sign the certificate of " + g.identity);
  fs::remove(d / "cert.csr");
  write_text(d / "permissions.xml", permissions_xml(g, from, to));
  sign(dir, d / "permissions.xml", d / "permissions.p7s");
}
}  // namespace

std::string subject_of(const std::string& identity) { return "CN=" + identity + ",O=SMART-DDS"; }

std::vector<Grant> role_grants(const std::vector<uint32_t>& agent_ids) {
  using namespace dds;
  const std::string monitor_info = smart_msg_TOPIC_MONITOR;
  std::vector<Grant> g{
      {"monitor",
       {t(kActionTopic), t(kClockTopic), monitor_info, t(kPlanProblemTopic), t(kPlanRequestTopic)},
       {t(kProgressTopic), t(kStateTopic), t(kClockTopic), t(kSimStatusTopic), monitor_info,
        t(kPlannerTopic), t(kPlanReplyTopic)},
       {}},
      {"sim",
       {t(kProgressTopic), t(kStateTopic), t(kClockTopic), t(kSimStatusTopic), t(kShardTopic),
        "rt/*"},
       {t(kActionTopic), t(kClockTopic), t(kStateTopic), t(kShardTopic)},
       {}},
      {"viewer", {}, {"*"}, {}},
      // The lifelong planner over DDS (`smart planner`): only it may answer windows.
      {"planner",
       {t(kPlannerTopic), t(kPlanReplyTopic)},
       {t(kPlanProblemTopic), t(kPlanRequestTopic)},
       {}},
  };
  for (const uint32_t id : agent_ids) {
    g.push_back({"agent-" + std::to_string(id),
                 {t(kProgressTopic), t(kStateTopic)},
                 {t(kActionTopic), t(kClockTopic)},
                 {std::string(smart_msg_RUN_PARTITION_PREFIX) + "*" +
                  smart_msg_ROBOT_PARTITION_INFIX + std::to_string(id)}});
  }
  return g;
}

std::string governance_xml() {
  return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
         "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
         "xsi:noNamespaceSchemaLocation=\"" +
         kSchema +
         "omg_shared_ca_governance.xsd\">\n"
         "<domain_access_rules><domain_rule>\n"
         "<domains><id_range><min>0</min><max>230</max></id_range></domains>\n"
         "<allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
         "<enable_join_access_control>true</enable_join_access_control>\n"
         "<discovery_protection_kind>ENCRYPT</discovery_protection_kind>\n"
         "<liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>\n"
         "<rtps_protection_kind>NONE</rtps_protection_kind>\n"
         "<topic_access_rules><topic_rule>\n"
         "<topic_expression>*</topic_expression>\n"
         "<enable_discovery_protection>true</enable_discovery_protection>\n"
         "<enable_liveliness_protection>true</enable_liveliness_protection>\n"
         "<enable_read_access_control>true</enable_read_access_control>\n"
         "<enable_write_access_control>true</enable_write_access_control>\n"
         "<metadata_protection_kind>ENCRYPT</metadata_protection_kind>\n"
         "<data_protection_kind>ENCRYPT</data_protection_kind>\n"
         "</topic_rule></topic_access_rules>\n"
         "</domain_rule></domain_access_rules>\n"
         "</dds>\n";
}

std::string permissions_xml(const Grant& g, const std::string& not_before,
                            const std::string& not_after) {
  std::string x =
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
      "xsi:noNamespaceSchemaLocation=\"" +
      kSchema + "omg_shared_ca_permissions.xsd\">\n<permissions>\n<grant name=\"" + g.identity +
      "\">\n<subject_name>" + subject_of(g.identity) + "</subject_name>\n<validity><not_before>" +
      not_before + "</not_before><not_after>" + not_after + "</not_after></validity>\n";
  if (!g.publish.empty() || !g.subscribe.empty()) {
    x += "<allow_rule>\n<domains><id_range><min>0</min><max>230</max></id_range></domains>\n";
    if (!g.publish.empty()) {
      const auto& parts =
          g.publish_partitions.empty() ? std::vector<std::string>{"*"} : g.publish_partitions;
      x += "<publish>" + topics_xml(g.publish, parts) + "</publish>\n";
    }
    if (!g.subscribe.empty()) x += "<subscribe>" + topics_xml(g.subscribe) + "</subscribe>\n";
    x += "</allow_rule>\n";
  }
  return x + "<default>DENY</default>\n</grant>\n</permissions>\n</dds>\n";
}

void init_keystore(const fs::path& dir, const std::vector<uint32_t>& agent_ids, int valid_days) {
  fs::create_directories(dir);
  openssl({"req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes",
           "-keyout", (dir / "ca.key").string(), "-out", (dir / "ca.pem").string(), "-days",
           std::to_string(valid_days), "-subj", "/O=SMART-DDS/CN=SMART-DDS CA"},
          "make the CA");
  fs::permissions(dir / "ca.key", fs::perms::owner_read | fs::perms::owner_write);
  write_text(dir / "governance.xml", governance_xml());
  sign(dir, dir / "governance.xml", dir / "governance.p7s");
  const auto now = std::chrono::system_clock::now();
  const std::string from = utc(now - std::chrono::hours(24));
  const std::string to = utc(now + std::chrono::hours(24) * valid_days);
  for (const auto& g : role_grants(agent_ids)) make_identity(dir, g, valid_days, from, to);
}

dds::SecurityFiles identity_files(const fs::path& dir, const std::string& identity) {
  const fs::path d = fs::absolute(dir);
  dds::SecurityFiles f{(d / "ca.pem").string(),
                       (d / identity / "cert.pem").string(),
                       (d / identity / "key.pem").string(),
                       (d / "ca.pem").string(),
                       (d / "governance.p7s").string(),
                       (d / identity / "permissions.p7s").string()};
  for (const auto& p :
       {f.identity_ca, f.identity_certificate, f.private_key, f.governance, f.permissions}) {
    if (!fs::is_regular_file(p)) {
      throw config::ConfigError("--security " + dir.string() + ": no " + p + " (identity '" +
                                identity +
                                "'); make the keystore with `smart security init --out " +
                                dir.string() + "` (agents: --agent-ids) or pick --identity");
    }
  }
  return f;
}

}  // namespace smart::security
