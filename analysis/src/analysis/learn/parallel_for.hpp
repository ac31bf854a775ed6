// Index-parallel loop for independent jobs whose results go to slots by index,
// so the outcome does not depend on the thread count or the scheduling.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace rollsense::learn {

// Runs work(i) for i in [0, n) on `threads` threads (0 = all cores), the
// calling thread among them. `work` must not throw.
template <typename F>
void parallel_for(std::size_t n, unsigned threads, F&& work) {
    unsigned t = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
    t = static_cast<unsigned>(std::min<std::size_t>(t, std::max<std::size_t>(n, 1)));
    std::atomic<std::size_t> next{0};
    auto loop = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < n;) work(i);
    };
    std::vector<std::thread> pool;
    for (unsigned k = 1; k < t; ++k) pool.emplace_back(loop);
    loop();
    for (auto& th : pool) th.join();
}

}  // namespace rollsense::learn
