#include "rollsense/minirocket/parallel.hpp"

#include <algorithm>
#include <thread>
#include <vector>

namespace rollsense::minirocket {

unsigned resolve_threads(unsigned requested) {
    if (requested) return requested;
    return std::max(1u, std::thread::hardware_concurrency());
}

void parallel_for(std::size_t n, unsigned threads, const std::function<void(std::size_t, std::size_t)>& body) {
    const std::size_t t = std::min<std::size_t>(std::max(1u, threads), n);
    if (t <= 1) {
        if (n) body(0, n);
        return;
    }
    std::vector<std::thread> pool;
    pool.reserve(t - 1);
    const std::size_t chunk = (n + t - 1) / t;
    for (std::size_t i = 1; i < t; ++i) {
        const std::size_t b = i * chunk, e = std::min(n, b + chunk);
        if (b < e) pool.emplace_back(body, b, e);
    }
    body(0, std::min(n, chunk));  // the calling thread takes the first chunk
    for (auto& th : pool) th.join();
}

}  // namespace rollsense::minirocket
