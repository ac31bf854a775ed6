// `rollsense run --live`: the event hub, the run's feed and the HTTP server,
// hooked into a run through the Session's observer options, rs.status and the
// analysis layer's prediction observer. One per process at a time.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "live/event_hub.hpp"
#include "live/http_server.hpp"
#include "live/run_feed.hpp"
#include "runtime/session/session.hpp"

namespace rollsense::live {

struct LiveOptions {
    std::string address = "127.0.0.1";
    std::uint16_t port = 8027;  // 0: any free port
};
constexpr std::uint16_t kDefaultPort = 8027;

class LiveView {
public:
    // Listen, and hook the view into `options` (on_sample, on_progress).
    static Result<std::unique_ptr<LiveView>> start(const LiveOptions& live, runtime::SessionOptions& options);
    ~LiveView();  // unhooks rs.status and identification, ends the stream, stops the server

    std::string where() const { return server_->where(); }  // the view's URL, for its line on stderr
    // The run's outcome, for the page (after Session::run).
    void finished(const runtime::RunSummary& summary);
    EventHub& hub() { return hub_; }  // what the page's clients read

private:
    LiveView(std::string script, std::string profile);
    EventHub hub_;
    RunFeed feed_;
    std::unique_ptr<HttpServer> server_;
};

// rs.status("clamping") reports here; nothing when no live view runs.
void set_status_feed(RunFeed* feed);

}  // namespace rollsense::live
