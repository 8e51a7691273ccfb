// Contract: the command-line flags of a physical robot's backend (jetbot or ros2), its pose
// source and an emulated JetBot's flaws, bound to hw::RobotIoOptions (hw/robot_io.hpp opens the
// robot), shared by `smart agent`, `smart doctor` and `smart calibrate` so all accept the same
// flags.
#pragma once

#include <CLI/CLI.hpp>

#include "smart/hw/robot_io.hpp"

namespace smart::tools {

using BackendOptions = hw::RobotIoOptions;
using hw::Backend;
using hw::PoseKind;
using hw::RobotIo;

void add_backend_options(CLI::App* cmd, BackendOptions& o);

}  // namespace smart::tools
