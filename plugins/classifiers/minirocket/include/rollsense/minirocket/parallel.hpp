// A minimal fork-join over an index range with std::thread: the project uses
// no OpenMP, and MiniRocket's work (one series per index) needs nothing more.
#pragma once

#include <cstddef>
#include <functional>

namespace rollsense::minirocket {

// Threads to use: `requested`, or all hardware threads when 0 (at least 1).
unsigned resolve_threads(unsigned requested);

// Calls body(begin, end) on contiguous chunks of [0, n), one per thread, and
// waits. Results must not depend on the chunking (each index is independent).
void parallel_for(std::size_t n, unsigned threads, const std::function<void(std::size_t, std::size_t)>& body);

}  // namespace rollsense::minirocket
