// `smart security init`: flags into security::init_keystore (security/keystore.hpp).
#include <iostream>
#include <nlohmann/json.hpp>

#include "smart/security/keystore.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

namespace smart::tools {

namespace {
struct SecurityInitOptions {
  std::string out;
  std::string agent_ids = "0-15";
  int days = 365;
};

int security_init(const SecurityInitOptions& o) {
  const auto ids = parse_id_ranges(o.agent_ids);
  security::init_keystore(o.out, ids, o.days);
  nlohmann::json identities = nlohmann::json::array();
  for (const auto& g : security::role_grants(ids)) identities.push_back(g.identity);
  std::cout << nlohmann::json{{"keystore", o.out}, {"identities", identities}, {"days", o.days}}
            << "\n";
  return kExitSuccess;
}
}  // namespace

void register_security_command(CLI::App& app, int& exit_code) {
  auto* security = app.add_subcommand("security", "DDS Security keystores");
  security->require_subcommand(1);
  auto o = std::make_shared<SecurityInitOptions>();
  auto* init = security->add_subcommand(
      "init",
      "Make a keystore with openssl: a CA, signed governance (authentication required, topics "
      "encrypted) and identities with signed permissions for monitor, sim, viewer and agents");
  init->add_option("--out", o->out, "keystore directory (created)")->required();
  init->add_option("--agent-ids", o->agent_ids, "robot ids with an agent identity, e.g. 0-9,12")
      ->capture_default_str();
  init->add_option("--days", o->days, "validity of certificates and permissions")
      ->check(CLI::Range(1, 3650))
      ->capture_default_str();
  init->callback([o, &exit_code] { exit_code = security_init(*o); });
}

}  // namespace smart::tools
