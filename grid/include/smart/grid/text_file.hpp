// Contract: the one file-reading edge of the readers (map, scenario, plan). read_text_file()
// returns a file's contents or throws InputError naming the path and how to fix it: missing or
// unreadable, a directory, or larger than kMaxTextFileBytes (read in chunks, so /dev/zero is
// refused, not exhausted).
#pragma once

#include <filesystem>
#include <string>

namespace smart::grid {

// The largest file read_text_file accepts (SMART's 1000-robot plan is 1.25 MB).
inline constexpr std::size_t kMaxTextFileBytes = std::size_t{256} << 20;

std::string read_text_file(const std::filesystem::path& path, const char* what);

}  // namespace smart::grid
