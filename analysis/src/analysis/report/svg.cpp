#include "analysis/report/svg.hpp"

#include <cmath>
#include <cstdio>

namespace rollsense::report {

std::string escape_xml(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string fixed(double value, int decimals) {
    if (!std::isfinite(value)) return "\u2013";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    std::string s = buf;
    // "-0.0" reads like a sign that means something; it does not.
    if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
    return s;
}

std::vector<double> nice_ticks(double lo, double hi, int count) {
    std::vector<double> out;
    if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi) || count < 1) return out;
    const double raw = (hi - lo) / count;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (const double m : {1.0, 2.0, 5.0, 10.0})
        if (m * mag >= raw) {
            step = m * mag;
            break;
        }
    for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1.0) out.push_back(k * step);
    return out;
}

std::string tick_label(double value, double step) {
    const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    return fixed(value, decimals);
}

double text_width(std::string_view text, double size) {
    std::size_t glyphs = 0;
    for (const unsigned char c : text) glyphs += (c & 0xC0) != 0x80;  // UTF-8: count characters, not bytes
    return 0.6 * size * static_cast<double>(glyphs);
}

std::string percent(double fraction, int decimals) {
    if (!std::isfinite(fraction)) return "\u2013";
    return fixed(100.0 * fraction, decimals) + "\u00a0%";
}

namespace {

// Two decimals are far below a pixel at any print size and keep files small.
std::string num(double v) {
    return fixed(v, 2);
}

std::string stroke_attrs(const Stroke& s) {
    std::string a = " stroke=\"" + escape_xml(s.colour) + "\" stroke-width=\"" + num(s.width) + "\"";
    if (!s.dash.empty()) a += " stroke-dasharray=\"" + escape_xml(s.dash) + "\"";
    return a;
}

}  // namespace

Svg::Svg(double width, double height, std::string_view id, std::string_view title) : width_(width), height_(height) {
    head_ = "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"" + escape_xml(id) + "\" viewBox=\"0 0 " + num(width) +
            " " + num(height) + "\" width=\"" + num(width) + "\" height=\"" + num(height) +
            "\" role=\"img\" aria-labelledby=\"" + escape_xml(id) + "-title\" font-family=\"sans-serif\">\n<title id=\"" +
            escape_xml(id) + "-title\">" + escape_xml(title) + "</title>\n";
}

void Svg::rect(double x, double y, double w, double h, std::string_view fill, const Stroke* stroke) {
    body_ += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" + num(h) +
             "\" fill=\"" + escape_xml(fill) + "\"" + (stroke ? stroke_attrs(*stroke) : std::string()) + "/>\n";
}

void Svg::line(double x1, double y1, double x2, double y2, const Stroke& stroke) {
    body_ += "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) + "\" y2=\"" + num(y2) + "\"" +
             stroke_attrs(stroke) + "/>\n";
}

void Svg::polyline(const std::vector<std::pair<double, double>>& points, const Stroke& stroke) {
    if (points.empty()) return;
    body_ += "<polyline fill=\"none\" stroke-linejoin=\"round\"" + stroke_attrs(stroke) + " points=\"";
    for (const auto& [x, y] : points) body_ += num(x) + "," + num(y) + " ";
    body_ += "\"/>\n";
}

void Svg::polygon(const std::vector<std::pair<double, double>>& points, std::string_view fill, const Stroke& stroke) {
    if (points.empty()) return;
    body_ += "<polygon fill=\"" + escape_xml(fill) + "\"" + stroke_attrs(stroke) + " points=\"";
    for (const auto& [x, y] : points) body_ += num(x) + "," + num(y) + " ";
    body_ += "\"/>\n";
}

void Svg::circle(double cx, double cy, double r, std::string_view fill, const Stroke& stroke) {
    body_ += "<circle cx=\"" + num(cx) + "\" cy=\"" + num(cy) + "\" r=\"" + num(r) + "\" fill=\"" + escape_xml(fill) +
             "\"" + stroke_attrs(stroke) + "/>\n";
}

void Svg::arrow(double x1, double y1, double x2, double y2, const Stroke& stroke, bool head_start, bool head_end) {
    line(x1, y1, x2, y2, stroke);
    const double len = std::hypot(x2 - x1, y2 - y1);
    if (len <= 0.0) return;
    const double ux = (x2 - x1) / len, uy = (y2 - y1) / len;
    const double size = 3.0 + 2.0 * stroke.width;
    auto head = [&](double tx, double ty, double dx, double dy) {
        // Tip at (tx, ty), pointing along (dx, dy).
        const double bx = tx - dx * size, by = ty - dy * size;
        polygon({{tx, ty}, {bx - dy * size * 0.5, by + dx * size * 0.5}, {bx + dy * size * 0.5, by - dx * size * 0.5}},
                stroke.colour, Stroke{stroke.colour, 0.5, {}});
    };
    if (head_end) head(x2, y2, ux, uy);
    if (head_start) head(x1, y1, -ux, -uy);
}

void Svg::text(double x, double y, std::string_view content, const TextStyle& style) {
    const char* anchor = style.anchor == Anchor::middle ? "middle" : style.anchor == Anchor::end ? "end" : "start";
    body_ += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(style.size) + "\" text-anchor=\"" +
             anchor + "\" fill=\"" + escape_xml(style.colour) + "\"";
    if (style.bold) body_ += " font-weight=\"bold\"";
    if (style.rotate != 0.0)
        body_ += " transform=\"rotate(" + num(style.rotate) + " " + num(x) + " " + num(y) + ")\"";
    body_ += ">" + escape_xml(content) + "</text>\n";
}

void Svg::open_group(std::string_view css_class) {
    body_ += "<g class=\"" + escape_xml(css_class) + "\">\n";
}

void Svg::close_group() {
    body_ += "</g>\n";
}

std::string Svg::str() const {
    return head_ + body_ + "</svg>\n";
}

}  // namespace rollsense::report
