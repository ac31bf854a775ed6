// The few SVG primitives the report's figures need, written as inline SVG so
// the page needs no plotting runtime, no JavaScript and no network, and every
// label stays selectable text.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rollsense::report {

// Text safe inside XML/HTML element content and attribute values.
std::string escape_xml(std::string_view text);

// Fixed-point number with `decimals` digits ("-0.0" printed as "0.0"); NaN and
// infinities as "–" so a missing figure never looks like a measured one.
std::string fixed(double value, int decimals);
// "91.2 %" from a fraction 0.912.
std::string percent(double fraction, int decimals = 1);

// Round values to label an axis over [lo, hi]: multiples of 1, 2 or 5 × 10^k,
// about `count` of them, all inside the interval.
std::vector<double> nice_ticks(double lo, double hi, int count = 5);
// The text of a tick value: as many decimals as the tick spacing needs.
std::string tick_label(double value, double step);
// About how wide `text` renders at font size `size` (0.6 em per character,
// generous for the report's sans-serif): what layouts reserve for labels.
double text_width(std::string_view text, double size);

// Maps a data interval onto a pixel interval (either may be reversed).
struct LinearScale {
    double d0 = 0.0, d1 = 1.0;  // data
    double r0 = 0.0, r1 = 1.0;  // pixels
    double operator()(double v) const { return d1 == d0 ? r0 : r0 + (v - d0) * (r1 - r0) / (d1 - d0); }
};

struct Stroke {
    std::string colour = "#000";
    double width = 1.0;
    std::string dash;  // SVG stroke-dasharray, empty for solid
};

enum class Anchor { start, middle, end };

struct TextStyle {
    double size = 12.0;
    Anchor anchor = Anchor::start;
    bool bold = false;
    std::string colour = "#000";
    double rotate = 0.0;  // degrees about the anchor point
};

// An <svg> element built up shape by shape. Coordinates are user units (the
// viewBox); the figure scales with the page width.
class Svg {
public:
    Svg(double width, double height, std::string_view id, std::string_view title);

    void rect(double x, double y, double w, double h, std::string_view fill, const Stroke* stroke = nullptr);
    void line(double x1, double y1, double x2, double y2, const Stroke& stroke);
    void polyline(const std::vector<std::pair<double, double>>& points, const Stroke& stroke);
    void polygon(const std::vector<std::pair<double, double>>& points, std::string_view fill, const Stroke& stroke);
    void circle(double cx, double cy, double r, std::string_view fill, const Stroke& stroke);
    // A line with arrow heads at the ends asked for (drawn as small triangles,
    // so no <marker> definitions have to be unique across figures).
    void arrow(double x1, double y1, double x2, double y2, const Stroke& stroke, bool head_start, bool head_end);
    void text(double x, double y, std::string_view content, const TextStyle& style = {});
    // Raw markup for a group opening/closing with a CSS class (e.g. "cell").
    void open_group(std::string_view css_class);
    void close_group();

    double width() const { return width_; }
    double height() const { return height_; }
    std::string str() const;

private:
    double width_, height_;
    std::string head_;
    std::string body_;
};

}  // namespace rollsense::report
