#pragma once
#include <cstdint>

namespace hpcplan {

// Bytes the kernel reports as available for new allocations (MemAvailable), or 0 if unknown.
std::uint64_t available_memory_bytes();

}  // namespace hpcplan
