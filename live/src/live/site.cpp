#include "live/site.hpp"

#include "analysis/learn/json_writer.hpp"
#include "live/page_assets.hpp"
#include "live/run_feed.hpp"

namespace rollsense::live {

using learn::json_quote;

namespace {

constexpr std::string_view kJson = "application/json";

Reply not_found(const Request& r) {
    return {http_response(404, "text/plain; charset=utf-8",
                          "not found: " + r.target + " (the live view serves its page, info.json and its data only)\n",
                          {}, r.method == "HEAD")};
}

// The common part of both sites: the method check, the body check and the
// page. Empty when the request is for something else. The method comes first:
// any other method is refused as one (405), with a body or not.
std::optional<Reply> common(const Request& r) {
    if (r.method != "GET" && r.method != "HEAD")
        return Reply{http_response(405, "text/plain; charset=utf-8",
                                   "method " + r.method + " not allowed: the live view is read-only (GET, HEAD)\n",
                                   "Allow: GET, HEAD\r\n")};
    if (r.has_body)
        return Reply{http_response(400, "text/plain; charset=utf-8",
                                   "malformed request: a " + r.method + " with a body (the live view is read-only)\n",
                                   {}, r.method == "HEAD")};
    const std::string path = r.target == "/" ? "/index.html" : r.target;
    for (const auto& a : page_assets())
        if (a.path == path) return Reply{http_response(200, a.content_type, a.content, {}, r.method == "HEAD")};
    return std::nullopt;
}

Reply json(const Request& r, const std::string& body) { return {http_response(200, kJson, body, {}, r.method == "HEAD")}; }

std::string trial_json(const DatasetReader& d, const TrialRecord& rec, const TrialData& data) {
    std::string c = "[", a = "[";
    for (const auto& s : data.channels) c += (c.size() > 1 ? "," : "") + json_numbers(s);
    for (const auto& s : data.joints) a += (a.size() > 1 ? "," : "") + json_numbers(s);
    return "{\"id\":" + json_quote(rec.info.id) + ",\"object\":" + json_quote(rec.info.object) +
           ",\"speed\":" + json_quote(rec.info.speed) + ",\"repetition\":" + std::to_string(rec.info.repetition) +
           ",\"channels\":" + json_strings(d.info().channels) + ",\"channel_units\":" +
           json_strings(d.info().channel_units) + ",\"joints\":" + json_strings(d.info().joints) +
           // The dataset format does not record the joints' units (deg or mm): none sent.
           ",\"joint_units\":[],\"time\":" + json_numbers(data.time) + ",\"c\":" + c + "],\"a\":" + a + "]}";
}

}  // namespace

Site live_site(std::string script, std::string profile) {
    const std::string info = "{\"mode\":\"live\",\"script\":" + json_quote(script) + ",\"profile\":" +
                             json_quote(profile) + "}";
    return [info](const Request& r) -> Reply {
        if (auto reply = common(r)) return *reply;
        if (r.target == "/info.json") return json(r, info);
        if (r.target == "/events") {
            if (r.method == "HEAD") return {http_response(200, "text/event-stream", "", {}, true)};
            return {{}, true};
        }
        return not_found(r);
    };
}

Site dataset_site(std::shared_ptr<const DatasetReader> dataset) {
    return [dataset](const Request& r) -> Reply {
        if (auto reply = common(r)) return *reply;
        const auto& d = *dataset;
        if (r.target == "/info.json")
            return json(r, "{\"mode\":\"view\",\"dataset\":" + json_quote(d.dir().filename().string()) +
                               ",\"profile\":" + json_quote(d.info().profile) +
                               ",\"trials\":" + std::to_string(d.trials().size()) + "}");
        if (r.target == "/dataset/trials.json") {
            std::string list = "[";
            for (const auto& t : d.trials())
                list += (list.size() > 1 ? "," : "") + std::string("{\"id\":") + json_quote(t.info.id) +
                        ",\"object\":" + json_quote(t.info.object) + ",\"speed\":" + json_quote(t.info.speed) +
                        ",\"samples\":" + std::to_string(t.samples) + "}";
            return json(r, list + "]");
        }
        // /dataset/trial/ID.json: the trial is looked up by its id in the
        // manifest; the file it names is the manifest's, never the request's.
        constexpr std::string_view prefix = "/dataset/trial/", suffix = ".json";
        if (r.target.starts_with(prefix) && r.target.ends_with(suffix)) {
            const std::string id = r.target.substr(prefix.size(), r.target.size() - prefix.size() - suffix.size());
            for (const auto& t : d.trials()) {
                if (t.info.id != id) continue;
                auto data = d.load(t);
                if (!data)
                    return {http_response(500, "text/plain; charset=utf-8",
                                          "trial " + id + " cannot be read: " + data.error().message + "\n")};
                return json(r, trial_json(d, t, *data));
            }
        }
        return not_found(r);
    };
}

}  // namespace rollsense::live
