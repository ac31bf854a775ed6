// The live view's request parser (live/src/live/http.cpp, Boost.Beast): the
// input is what a client sends, fed as it might arrive (growing prefixes, the
// step from the input itself). A complete request has a method and a target
// starting with '/' (or, only to be refused by its method, OPTIONS * and
// CONNECT host:port); nothing crashes, and the answer never changes once the
// head is complete or malformed.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.hpp"
#include "live/http.hpp"

namespace live = rollsense::live;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::size_t step = 1 + data[0] % 97;
    const std::string_view all(reinterpret_cast<const char*>(data + 1), size - 1);
    live::ParsedRequest settled;
    for (std::size_t end = 0; end <= all.size(); end = end == all.size() ? end + 1 : std::min(all.size(), end + step)) {
        auto p = live::parse_request(all.substr(0, end));
        const auto& r = p.request;
        const bool path = !r.target.empty() && r.target[0] == '/';
        const bool refused_form = (r.method == "OPTIONS" && r.target == "*") || (r.method == "CONNECT" && !r.target.empty());
        if (p.state == live::ParsedRequest::State::complete && (r.method.empty() || !(path || refused_form)))
            rollsense::fuzz::invariant_broken("a complete request without a method or a path");
        if (settled.state != live::ParsedRequest::State::incomplete && p.state != settled.state)
            rollsense::fuzz::invariant_broken("more bytes changed a settled request");
        if (settled.state == live::ParsedRequest::State::incomplete) settled = p;
    }
    return 0;
}
