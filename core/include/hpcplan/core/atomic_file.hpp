#pragma once
#include <string>
#include <string_view>

namespace hpcplan {

// Writes `content` to a temporary file beside `path`, flushes it, then renames it over `path`,
// so readers see either the old file or the complete new one. Throws RunError on failure.
void write_file_atomically(const std::string& path, std::string_view content);

// Checks, before a long run, that `path` could be written later: its directory exists and is
// writable and the path is not a directory. Throws InputError naming `option` otherwise.
void require_writable_destination(const std::string& path, std::string_view option);

}  // namespace hpcplan
