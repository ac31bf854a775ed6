#include "rollsense/last_resort.hpp"

#include <atomic>
#include <mutex>

namespace rollsense {
namespace {
struct Slot {
    std::atomic<LastResortAction> action{nullptr};  // null: free
    std::atomic<void*> context{nullptr};
};
Slot g_slots[16];
}  // namespace

int add_last_resort(LastResortAction action, void* context) {
    static std::mutex registering;  // registrations only: run_last_resort() takes no lock
    std::lock_guard lock(registering);
    for (int i = 0; action && i < 16; ++i) {
        if (g_slots[i].action.load()) continue;
        g_slots[i].context.store(context);  // before the action, which marks the slot taken
        g_slots[i].action.store(action);
        return i;
    }
    return -1;
}

void remove_last_resort(int slot) { if (slot >= 0 && slot < 16) g_slots[slot].action.store(nullptr); }

int run_last_resort() noexcept {
    int ran = 0;
    for (auto& s : g_slots)
        if (auto* action = s.action.load()) {
            action(s.context.load());
            ++ran;
        }
    return ran;
}

}  // namespace rollsense
