#pragma once
// Output files are written whole or not at all: content goes to a temporary file in the
// target directory, which is then renamed over the target (atomic on POSIX).
#include <filesystem>
#include <string>

namespace nsb {

void write_file_atomic(const std::filesystem::path& path, const std::string& content);

// Creates the directory (and parents); throws InputError when that fails.
void ensure_directory(const std::filesystem::path& dir);

}  // namespace nsb
