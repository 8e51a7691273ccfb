// Contract: the monitor's one file-reading edge. read_text_file() returns a file's contents or
// throws InputError naming the path and how to fix it.
#pragma once

#include <filesystem>
#include <string>

namespace smart::grid {

std::string read_text_file(const std::filesystem::path& path, const char* what);

}  // namespace smart::grid
