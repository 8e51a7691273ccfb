// Contract: where an installed `smart` finds its shared files. `cmake --install` (and the .deb
// packages of CPack, docs/lab.md) put the executable in <prefix>/bin and its data in
// <prefix>/share/smart-dds/ (config/, web/, experiment_plot.py); installed_share_dir() is that
// folder when it exists beside the running executable, else nothing (a build tree: the callers
// fall back to the source tree compiled in). Reads /proc/self/exe; never throws.
#pragma once

#include <filesystem>
#include <optional>

namespace smart::common {

inline constexpr const char* kInstalledShareDir = "share/smart-dds";

// <exe>/../share/smart-dds for `exe`, when that folder exists.
std::optional<std::filesystem::path> share_dir_beside(const std::filesystem::path& exe);
// The same for the running executable.
std::optional<std::filesystem::path> installed_share_dir();

}  // namespace smart::common
