#pragma once
#include <string>
#include <string_view>

namespace hpcplan {

// Writes `content` to a temporary file beside `path`, flushes it, then renames it over `path`,
// so readers see either the old file or the complete new one. Throws RunError on failure.
void write_file_atomically(const std::string& path, std::string_view content);

}  // namespace hpcplan
