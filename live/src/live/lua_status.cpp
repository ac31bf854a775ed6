// rs.status("clamping"): the step the script is at, for the live view. A
// plain string of at most kMaxStatus bytes; without a live view it is kept
// nowhere (the call costs nothing and the script runs the same).
#include <atomic>
#include <string>

#include "live/live_view.hpp"
#include "runtime/lua/api_internal.hpp"

namespace rollsense::live {

namespace {
std::atomic<RunFeed*> status_feed{nullptr};
constexpr std::size_t kMaxStatus = 200;

int l_status(lua_State* L) {
    std::size_t len = 0;
    const char* text = luaL_checklstring(L, 1, &len);
    if (len > kMaxStatus)
        return luaL_error(L, "rs.status: the step is %d bytes, at most %d are shown (name the step, e.g. \"clamping\")",
                          static_cast<int>(len), static_cast<int>(kMaxStatus));
    if (auto* feed = status_feed.load()) feed->status(runtime::Session::of(L), std::string(text, len));
    return 0;
}

void register_status(lua_State* L) {
    lua_pushcfunction(L, l_status);
    lua_setfield(L, -2, "status");
}

const runtime::lua_api::ExtraRegistration registration{&register_status};
}  // namespace

void set_status_feed(RunFeed* feed) { status_feed = feed; }

}  // namespace rollsense::live
