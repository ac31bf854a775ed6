#include "live/http.hpp"

#include <boost/beast/core/error.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/asio/buffer.hpp>

namespace rollsense::live {

namespace http = boost::beast::http;

namespace {

// Whether the request target has a form of RFC 9112 §3.2 the live view
// takes: a path ("/x?q"), "*" for OPTIONS and "host:port" for CONNECT (the
// last two only to be refused by their method). Beast lets any token through
// as the target ("G ET/events" parses as method G, target ET/events): found
// by fuzz_http_request.
bool target_form_ok(http::verb method, std::string_view target) {
    if (target.starts_with('/')) return true;
    if (method == http::verb::options) return target == "*";
    if (method == http::verb::connect) return !target.empty() && target.find_first_of("/?#") == std::string_view::npos;
    return false;
}

}  // namespace

ParsedRequest parse_request(std::string_view bytes) {
    ParsedRequest out;
    http::request_parser<http::empty_body> parser;
    parser.header_limit(static_cast<std::uint32_t>(kMaxHead));
    parser.eager(false);  // stop after the head: a body is refused by the site, never parsed
    boost::beast::error_code ec;
    std::size_t used = 0;
    while (used < bytes.size() && !parser.is_header_done()) {
        const std::size_t n = parser.put(boost::asio::buffer(bytes.data() + used, bytes.size() - used), ec);
        if (ec == http::error::need_more) break;
        if (ec) {
            out.state = ParsedRequest::State::malformed;
            out.error = ec.message();
            return out;
        }
        if (n == 0) break;
        used += n;
    }
    if (!parser.is_header_done()) {
        if (bytes.size() >= kMaxHead) {
            out.state = ParsedRequest::State::malformed;
            out.error = "request head longer than " + std::to_string(kMaxHead) + " bytes";
        }
        return out;
    }
    const auto& head = parser.get();
    std::string target(head.target());
    if (!target_form_ok(head.method(), target)) {
        out.state = ParsedRequest::State::malformed;
        out.error = "the request target is not a path starting with '/'";
        return out;
    }
    out.state = ParsedRequest::State::complete;
    out.request.method = std::string(head.method_string());
    if (auto q = target.find('?'); q != std::string::npos) target.resize(q);
    out.request.target = std::move(target);
    out.request.keep_alive = head.keep_alive();
    out.request.has_body = parser.content_length().value_or(0) > 0 || parser.chunked();
    return out;
}

std::string_view reason_phrase(int status) {
    switch (status) {
        case 200: return "OK";
        case 400: return "Bad Request";
        case 404: return "Not Found";
        case 405: return "Method Not Allowed";
        case 500: return "Internal Server Error";
        case 503: return "Service Unavailable";
        default: return "Error";
    }
}

namespace {
std::string status_line(int status) {
    return "HTTP/1.1 " + std::to_string(status) + " " + std::string(reason_phrase(status)) + "\r\n";
}
// Our own page only: no framing by other sites, no guessing of types.
constexpr std::string_view kCommonHeaders =
    "Server: rollsense\r\nX-Content-Type-Options: nosniff\r\nX-Frame-Options: DENY\r\n"
    "Cache-Control: no-store\r\n";
}  // namespace

std::string http_response(int status, std::string_view content_type, std::string_view body,
                          std::string_view extra_headers, bool head_only) {
    std::string r = status_line(status);
    r += kCommonHeaders;
    r += "Content-Type: ";
    r += content_type;
    r += "\r\nContent-Length: " + std::to_string(body.size()) + "\r\nConnection: close\r\n";
    r += extra_headers;
    r += "\r\n";
    if (!head_only) r += body;
    return r;
}

std::string sse_head() {
    return status_line(200) + std::string(kCommonHeaders) +
           "Content-Type: text/event-stream\r\nConnection: close\r\n\r\n";
}

}  // namespace rollsense::live
