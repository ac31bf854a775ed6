#include "live/live_view.hpp"

#include "analysis/lua/prediction_observer.hpp"
#include "live/site.hpp"

namespace rollsense::live {

LiveView::LiveView(std::string script, std::string profile) : feed_(hub_, std::move(script), std::move(profile)) {}

Result<std::unique_ptr<LiveView>> LiveView::start(const LiveOptions& live, runtime::SessionOptions& options) {
    const std::string script = options.script.filename().string();
    std::unique_ptr<LiveView> view(new LiveView(script, options.profile));
    auto server = HttpServer::start(live.address, live.port, live_site(script, options.profile), &view->hub_);
    if (!server) return server.error();
    view->server_ = std::move(*server);
    RunFeed* feed = &view->feed_;
    options.on_sample = [feed](runtime::Session& s) { feed->sampled(s); };
    options.on_progress = [feed](std::size_t done, std::size_t total, const std::string& label, double) {
        feed->progress(done, total, label);
    };
    set_status_feed(feed);
    runtime::lua_api::set_prediction_observer(
        [feed](lua_State* L, const std::vector<std::string>& classes, const Prediction& p) {
            feed->identified(runtime::Session::of(L).trial().id, classes, p);
        });
    return view;
}

LiveView::~LiveView() {
    set_status_feed(nullptr);
    runtime::lua_api::set_prediction_observer({});
    hub_.close();
    server_.reset();
}

void LiveView::finished(const runtime::RunSummary& summary) {
    const std::string outcome = summary.status.ok() ? "done" : summary.cancelled ? "cancelled" : "failed";
    feed_.finished(outcome, summary.status.ok() ? "" : summary.status.error().describe(), summary.trials_saved);
}

}  // namespace rollsense::live
