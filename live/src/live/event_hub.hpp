// The bounded, lossy queue between a run and the live view's clients. The run
// publishes preformatted Server-Sent Events; each client takes the events it
// has not seen. The run's thread never waits for a client: a sample that finds
// the queue busy is dropped (counted), and a client that falls more than the
// capacity behind skips to the oldest event still kept (its loss counted).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace rollsense::live {

// One SSE message: "event: NAME\ndata: JSON\n\n".
std::string sse_event(const std::string& name, const std::string& json);

class EventHub {
public:
    explicit EventHub(std::size_t capacity = 4096);

    // A sample: dropped (and counted) rather than waiting when a client holds the queue.
    void publish(std::string event);
    // A state that a client connecting later must see too (trial header,
    // progress, status, state): kept under `key` as the latest of its kind.
    // Waits at most for a client copying out one batch.
    void publish_state(const std::string& key, std::string event);

    struct Batch {
        std::vector<std::string> events;
        std::uint64_t next = 0;    // where the client goes on
        std::uint64_t missed = 0;  // events it lost by falling behind
        bool closed = false;
    };
    // The latest states and where the stream stands now: a new client's start.
    Batch join();
    // Up to kMaxBatch events from `from` on, waiting up to `timeout` for the first.
    Batch take(std::uint64_t from, std::chrono::milliseconds timeout);
    // No more events: every waiting client returns with `closed`.
    void close();

    std::uint64_t dropped() const;    // samples dropped because the queue was busy
    std::uint64_t published() const;  // events in the stream so far

    static constexpr std::size_t kMaxBatch = 256;

private:
    void push_locked(std::string event);

    const std::size_t capacity_;
    mutable std::mutex mutex_;
    std::condition_variable ready_;
    std::vector<std::string> ring_;
    std::uint64_t next_ = 0;  // sequence number of the next event
    std::map<std::string, std::string> states_;
    std::atomic<std::uint64_t> dropped_{0};
    bool closed_ = false;
};

}  // namespace rollsense::live
