#pragma once
// Index types: 32-bit local indices, 64-bit global ones; never mixed silently.
#include <cstdint>

namespace seam {
using local_index = std::int32_t;
using global_index = std::int64_t;
} // namespace seam
