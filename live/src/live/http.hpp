// HTTP/1.1 for the live view: a request head parsed by Boost.Beast's parser
// from the bytes a client sent, and responses written out. Only the head
// matters: the view is read-only, so a request with a body is refused (by the
// site, after the method: a POST gets 405 whether or not it has a body).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace rollsense::live {

struct Request {
    std::string method;  // as sent, e.g. "GET"
    std::string target;  // the path, without the query ("*" for OPTIONS *)
    bool keep_alive = false;
    bool has_body = false;  // Content-Length above 0 or chunked
};

struct ParsedRequest {
    enum class State { incomplete, complete, malformed } state = State::incomplete;
    Request request;
    std::string error;  // why it is malformed, for the 400 page
};

// Parse the request head in `bytes` (everything received so far).
// Heads longer than kMaxHead bytes are malformed.
ParsedRequest parse_request(std::string_view bytes);
constexpr std::size_t kMaxHead = 8192;

// A whole response with Content-Length (and Connection: close).
std::string http_response(int status, std::string_view content_type, std::string_view body,
                          std::string_view extra_headers = {}, bool head_only = false);
// The head of an event stream (text/event-stream, no length).
std::string sse_head();
std::string_view reason_phrase(int status);

}  // namespace rollsense::live
