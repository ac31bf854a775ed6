#include "live/event_hub.hpp"

#include <algorithm>

namespace rollsense::live {

std::string sse_event(const std::string& name, const std::string& json) {
    return "event: " + name + "\ndata: " + json + "\n\n";
}

EventHub::EventHub(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)), ring_(capacity_) {}

void EventHub::push_locked(std::string event) {
    ring_[next_ % capacity_] = std::move(event);
    ++next_;
}

void EventHub::publish(std::string event) {
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock) {
        dropped_.fetch_add(1, std::memory_order_relaxed);
        return;
    }
    push_locked(std::move(event));
    lock.unlock();
    ready_.notify_all();
}

void EventHub::publish_state(const std::string& key, std::string event) {
    {
        std::lock_guard lock(mutex_);
        states_[key] = event;
        push_locked(std::move(event));
    }
    ready_.notify_all();
}

EventHub::Batch EventHub::join() {
    std::lock_guard lock(mutex_);
    Batch b;
    for (const auto& [key, event] : states_) b.events.push_back(event);
    b.next = next_;
    b.closed = closed_;
    return b;
}

EventHub::Batch EventHub::take(std::uint64_t from, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    ready_.wait_for(lock, timeout, [&] { return closed_ || next_ > from; });
    Batch b;
    b.closed = closed_;
    const std::uint64_t oldest = next_ > capacity_ ? next_ - capacity_ : 0;
    if (from < oldest) {
        b.missed = oldest - from;
        from = oldest;
    }
    const std::uint64_t end = std::min<std::uint64_t>(next_, from + kMaxBatch);
    for (std::uint64_t s = from; s < end; ++s) b.events.push_back(ring_[s % capacity_]);
    b.next = end;
    return b;
}

void EventHub::close() {
    {
        std::lock_guard lock(mutex_);
        closed_ = true;
    }
    ready_.notify_all();
}

std::uint64_t EventHub::dropped() const { return dropped_.load(std::memory_order_relaxed); }

std::uint64_t EventHub::published() const {
    std::lock_guard lock(mutex_);
    return next_;
}

}  // namespace rollsense::live
