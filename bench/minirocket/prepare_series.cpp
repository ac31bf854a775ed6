#include "prepare_series.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "rollsense/csv.hpp"
#include "rollsense/random.hpp"

namespace bench {
using namespace rollsense;

namespace {

Result<std::map<std::string, std::string>> key_values(const std::filesystem::path& file) {
    auto r = csv::Reader::open(file);
    if (!r) return r.error();
    std::map<std::string, std::string> out;
    std::vector<std::string> f;
    while (true) {
        auto more = r->next(f);
        if (!more) return more.error();
        if (!*more) break;
        if (f.size() >= 2) out[f[0]] = f[1];
    }
    return out;
}

std::vector<double> smooth(const std::vector<double>& x) {
    std::vector<double> y(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        const std::size_t b = i >= 2 ? i - 2 : 0, e = std::min(x.size(), i + 3);
        double s = 0;
        for (std::size_t j = b; j < e; ++j) s += x[j];
        y[i] = s / static_cast<double>(e - b);
    }
    return y;
}

std::vector<double> resample(const std::vector<double>& x, std::size_t b, std::size_t e, std::size_t n) {
    std::vector<double> y(n);
    const double span = static_cast<double>(e - 1 - b);
    for (std::size_t i = 0; i < n; ++i) {
        const double pos = static_cast<double>(b) + span * static_cast<double>(i) / static_cast<double>(n - 1);
        const auto lo = static_cast<std::size_t>(std::floor(pos));
        const std::size_t hi = std::min(lo + 1, e - 1);
        y[i] = x[lo] + (pos - static_cast<double>(lo)) * (x[hi] - x[lo]);
    }
    return y;
}

}  // namespace

Result<FeatureTable> prepare_dataset(const std::filesystem::path& dir, std::size_t length, std::size_t& skipped,
                                     bool z_normalise, double crop) {
    auto info = key_values(dir / "dataset-info.csv");
    if (!info) return info.error();
    std::vector<std::string> channels;
    {
        std::istringstream ss((*info)["channels"]);
        for (std::string c; ss >> c;) channels.push_back(c);
    }
    if (channels.empty()) return Error{ErrorCode::parse_error, (dir / "dataset-info.csv").string() + ": no channels"};

    std::map<std::string, bool> clean;  // from features.csv when present
    if (std::filesystem::exists(dir / "features.csv")) {
        auto r = csv::Reader::open(dir / "features.csv");
        if (!r) return r.error();
        auto id = r->column("trial_id"), ok = r->column("clean");
        if (!id || !ok) return Error{ErrorCode::parse_error, (dir / "features.csv").string() + ": no trial_id/clean"};
        std::vector<std::string> f;
        while (true) {
            auto more = r->next(f);
            if (!more) return more.error();
            if (!*more) break;
            clean[f[*id]] = f[*ok] == "1";
        }
    }

    FeatureTable t;
    t.channel_names = channels;
    t.series_length = length;
    std::map<std::string, int> class_of;
    auto m = csv::Reader::open(dir / "manifest.csv");
    if (!m) return m.error();
    auto id_col = m->column("trial_id"), file_col = m->column("file"), object_col = m->column("object");
    if (!id_col || !file_col || !object_col)
        return Error{ErrorCode::parse_error, (dir / "manifest.csv").string() + ": needs trial_id, file, object"};
    std::vector<std::string> f, g;
    skipped = 0;
    while (true) {
        auto more = m->next(f);
        if (!more) return more.error();
        if (!*more) break;
        if (!clean.empty() && !clean[f[*id_col]]) {
            ++skipped;
            continue;
        }
        auto tr = csv::Reader::open(dir / f[*file_col]);
        if (!tr) return tr.error();
        std::vector<std::size_t> cols;
        for (const auto& c : channels) {
            auto col = tr->column(c);
            if (!col) return col.error();
            cols.push_back(*col);
        }
        std::vector<std::vector<double>> x(channels.size());
        bool finite = true;
        while (true) {
            auto row = tr->next(g);
            if (!row) return row.error();
            if (!*row) break;
            for (std::size_t c = 0; c < cols.size(); ++c) {
                auto v = tr->number(g, cols[c]);
                if (!v || !std::isfinite(*v)) finite = false;
                x[c].push_back(v ? *v : 0.0);
            }
        }
        if (!finite || x[0].size() < 10) {
            ++skipped;
            continue;
        }
        std::vector<double> sum(x[0].size(), 0.0);
        for (auto& ch : x) {
            ch = smooth(ch);
            std::vector<double> head(ch.begin(), ch.begin() + 5);
            std::nth_element(head.begin(), head.begin() + 2, head.end());
            for (double& v : ch) v -= head[2];
            for (std::size_t i = 0; i < ch.size(); ++i) sum[i] += ch[i];
        }
        const double peak = *std::max_element(sum.begin(), sum.end());
        std::size_t b = 0, e = sum.size();
        if (peak > 0) {
            while (b < sum.size() && sum[b] <= crop * peak) ++b;
            while (e > b && sum[e - 1] <= crop * peak) --e;
        }
        if (e - b < 2) b = 0, e = sum.size();
        for (auto& ch : x) {
            auto y = resample(ch, b, e, length);
            double mean = 0, var = 0;
            for (double v : y) mean += v;
            mean /= static_cast<double>(length);
            for (double v : y) var += (v - mean) * (v - mean);
            const double sd = std::sqrt(var / static_cast<double>(length));
            for (double v : y) t.x.push_back(!z_normalise ? v : sd > 1e-12 ? (v - mean) / sd : 0.0);
        }
        const std::string& object = f[*object_col];
        auto [it, added] = class_of.emplace(object, static_cast<int>(t.class_names.size()));
        if (added) t.class_names.push_back(object);
        t.y.push_back(it->second);
        ++t.rows;
    }
    return t;
}

FeatureTable synthetic_shapes(std::size_t per_class, std::size_t length, std::uint64_t seed) {
    FeatureTable t;
    t.channel_names = {"ch1", "ch2", "ch3"};
    t.series_length = length;
    t.class_names = {"bump", "two_bumps", "ramp"};
    auto rng = random::Xoshiro256ss::named_stream(seed, "bench-shapes");
    const double L = static_cast<double>(length);
    auto bump = [](double x, double c, double w) { return std::exp(-0.5 * (x - c) * (x - c) / (w * w)); };
    for (std::size_t i = 0; i < per_class * 3; ++i) {
        const int label = static_cast<int>(i % 3);
        const double shift = rng.uniform(-0.15, 0.15) * L, amp = rng.uniform(0.7, 1.3);
        for (std::size_t ch = 0; ch < 3; ++ch)
            for (std::size_t s = 0; s < length; ++s) {
                const double x = static_cast<double>(s), gain = amp * (1.0 - 0.3 * static_cast<double>(ch));
                double v = label == 0   ? bump(x, 0.5 * L + shift, 0.1 * L)
                           : label == 1 ? bump(x, 0.35 * L + shift, 0.07 * L) + bump(x, 0.65 * L + shift, 0.07 * L)
                                        : std::clamp((x - 0.2 * L - shift) / (0.6 * L), 0.0, 1.0);
                t.x.push_back(gain * v + 0.3 * rng.normal());
            }
        t.y.push_back(label);
        ++t.rows;
    }
    return t;
}

}  // namespace bench
