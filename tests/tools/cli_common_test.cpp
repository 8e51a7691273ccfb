// The shared command-line pieces: robot id lists, the network interface, link-model warnings.
#include "smart/tools/cli_common.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::tools {
namespace {

using ::testing::HasSubstr;

TEST(CliCommon, IdListsTakeIdsAndRangesAndNameTheBadPart) {
  EXPECT_EQ(parse_id_ranges("0-3,7"), (std::vector<uint32_t>{0, 1, 2, 3, 7}));
  EXPECT_EQ(parse_id_ranges("5"), (std::vector<uint32_t>{5}));
  for (const char* bad : {"", "3-1", "a", "1,,2", "-4", "2x", "0-4294967296", "4,2", "1,1"}) {
    EXPECT_THROW(parse_id_ranges(bad), std::invalid_argument) << bad;
  }
  EXPECT_THAT([] { parse_id_ranges("0-3,x"); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  HasSubstr("'x' is not a robot index (0..1000000); write e.g. 0-9,12")));
}

// Issue 26: no way to pick the network interface (wlan0 beside docker0 and l4tbr0 on a Jetson).
TEST(CliCommon, TheInterfaceIsOneOfThisHostsAndGoesToCycloneAndToChildren) {
  DdsOptions o;
  o.interface = "lo";
  EXPECT_THROW(check_interface(o), std::invalid_argument);  // loopback runs use lo anyway
  o.network = Network::kNetwork;
  EXPECT_NO_THROW(check_interface(o));
  const auto c = domain_config(o, dds::find_qos_profile("lan"), "monitor");
  EXPECT_EQ(c.interfaces, std::vector<std::string>{"lo"});
  EXPECT_THAT(dds::render_cyclone_config(c),
              ::testing::HasSubstr("<NetworkInterface name=\"lo\"/>"));
  const auto argv = dds_argv(o);
  EXPECT_THAT(argv, ::testing::Contains("--interface"));
  o.interface = "wlan9x";
  try {
    check_interface(o);
    FAIL() << "a missing interface must be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("--interface wlan9x: no such network interface"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("it has lo"));
  }
}

// Issue 26: --qos wifi added an invented delay and loss on top of a real network, silently.
TEST(CliCommon, ARealTimeRunWithALinkModelIsWarnedThatTheDelayIsAdded) {
  DdsOptions o;
  bool lockstep = false;
  o.qos = "sim-wifi";
  const auto wifi = dds::find_qos_profile("sim-wifi");
  ASSERT_TRUE(wifi.link.active());
  EXPECT_FALSE(link_model_warning(lockstep, o, dds::find_qos_profile("wifi")))
      << "the real network's profile models nothing";
  const auto warning = link_model_warning(lockstep, o, wifi);
  ASSERT_TRUE(warning);
  EXPECT_THAT(*warning, HasSubstr("--qos sim-wifi models a link ("));
  EXPECT_THAT(*warning, HasSubstr("added to the real network's own delay and loss"));
  lockstep = true;  // the model is the only link: nothing to warn of
  EXPECT_FALSE(link_model_warning(lockstep, o, wifi));
  lockstep = false;
  EXPECT_FALSE(link_model_warning(lockstep, o, dds::find_qos_profile("lan")));
}

// Issue 26: lossy-wifi dropped real packets in lock-step too, 3.4x real time instead of 113x.
TEST(CliCommon, ALockstepRunThatDropsRealPacketsIsWarnedOfTheWallTimeCost) {
  DdsOptions o;
  const bool lockstep = true;
  o.qos = "protocol-loss-test";
  const auto warning = link_model_warning(lockstep, o, dds::find_qos_profile(o.qos));
  ASSERT_TRUE(warning);
  EXPECT_THAT(*warning, HasSubstr("drops 200 per mille of the real packets"));
  EXPECT_THAT(*warning, HasSubstr("use --qos sim-lossy-wifi"));
  o.qos = "sim-lossy-wifi";
  EXPECT_FALSE(link_model_warning(lockstep, o, dds::find_qos_profile(o.qos)));
  EXPECT_EQ(dds::find_qos_profile("sim-lossy-wifi").transport.loss_per_mille, 0);
  EXPECT_DOUBLE_EQ(dds::find_qos_profile("sim-lossy-wifi").link.to_host.loss_per_mille, 200);
}

// `smart run --help` showed `--execution adg|switchable|...=0`: CLI11 printed an enum
// option's default as its number.
TEST(CliCommon, AnEnumFlagsHelpShowsItsDefaultByName) {
  enum class Mode { kPlain, kFast };
  const EnumNames<Mode> names{{"plain", Mode::kPlain}, {"fast", Mode::kFast}};
  CLI::App app;
  Mode mode = Mode::kFast;
  std::optional<Mode> unset, set = Mode::kPlain;
  add_enum_option(&app, "--mode", mode, names, "a mode")->capture_default_str();
  add_enum_option(&app, "--unset", unset, names, "no default")->capture_default_str();
  add_enum_option(&app, "--set", set, names, "an optional one")->capture_default_str();
  EXPECT_EQ(app.get_option("--mode")->get_default_str(), "fast");
  EXPECT_EQ(app.get_option("--unset")->get_default_str(), "");
  EXPECT_EQ(app.get_option("--set")->get_default_str(), "plain");
  EXPECT_THAT(app.help(), HasSubstr("plain|fast=fast"));
  EXPECT_THAT(app.help(), ::testing::Not(HasSubstr("=1")));
  app.parse(std::vector<std::string>{"plain", "--mode"});  // CLI11 takes them reversed
  EXPECT_EQ(mode, Mode::kPlain);
}

}  // namespace
}  // namespace smart::tools
