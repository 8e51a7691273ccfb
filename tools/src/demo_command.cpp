// `smart demo`: the default job run by `make demo`. Until the end-to-end run exists it is a DDS
// round trip: a `smart dds-echo` child process answers 100 robots' action windows.
#include "smart/tools/child_process.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

namespace smart::tools {

void register_demo_command(CLI::App& app, int& exit_code) {
  auto* demo = app.add_subcommand("demo", "Run the default demonstration job");
  auto domain = std::make_shared<int>(42);
  demo->add_option("--domain", *domain, "DDS domain id")->capture_default_str();
  demo->callback([&exit_code, domain] {
    ChildProcess ping({self_executable().string(), "dds-ping", "--spawn-echo", "--robots", "100",
                       "--rounds", "20", "--domain", std::to_string(*domain)});
    exit_code = ping.wait(std::chrono::minutes(2)).value_or(124);
  });
}

}  // namespace smart::tools
