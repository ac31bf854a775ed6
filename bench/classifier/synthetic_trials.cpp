#include "synthetic_trials.hpp"

#include <cmath>

namespace bench {
namespace {

struct Gen {
    std::uint64_t s;
    double uniform() {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(s >> 11) / 9007199254740992.0;
    }
    double normal() {
        const double u1 = std::max(uniform(), 1e-300), u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
    }
};

struct Shape {
    const char* id;
    int sides;         // 0 = cylinder
    double diameter;   // circumscribed, mm
};

}  // namespace

std::vector<SyntheticTrial> synthetic_trials(int runs, std::uint64_t seed) {
    const Shape shapes[] = {{"C1", 0, 18.0}, {"C2", 0, 27.0}, {"C3", 0, 36.0}, {"S1", 4, 18.4}, {"S2", 4, 25.5},
                            {"P1", 5, 22.1}, {"P2", 5, 30.6}, {"H1", 6, 26.0}, {"H2", 6, 36.0}};
    const struct {
        const char* label;
        int samples;
    } speeds[] = {{"10", 205}, {"15", 140}, {"20", 106}};
    Gen g{seed};
    std::vector<SyntheticTrial> out;
    for (const auto& sh : shapes)
        for (const auto& sp : speeds)
            for (int r = 0; r < runs; ++r) {
                SyntheticTrial t;
                t.object = sh.id;
                t.speed = sp.label;
                t.repetition = r + 1;
                t.id = std::string(sh.id) + "-v" + sp.label + "-r" + std::to_string(r + 1);
                const int n = sp.samples + static_cast<int>(std::lround(2.0 * g.normal()));
                const double nd = static_cast<double>(n);
                // The contact patch crosses the 24 mm sensor: wider objects roll
                // further per degree, so their peaks are wider and more spread.
                const double width = nd * (0.10 + 0.0025 * sh.diameter) * (1.0 + 0.05 * g.normal());
                const double spacing = nd * (0.06 + 0.0030 * sh.diameter) * (1.0 + 0.05 * g.normal());
                const double start = nd * (0.30 + 0.08 * (g.uniform() - 0.5));
                const double orientation = g.uniform() * 6.283185307179586;
                // Polygons: a fraction of runs stop before the object leaves ch3.
                const bool stuck = sh.sides > 0 && g.uniform() < 0.21;
                const double amp0 = 0.25 + 0.006 * (36.0 - sh.diameter) + 0.03 * g.normal();
                t.channels.assign(3, std::vector<double>(static_cast<std::size_t>(n)));
                for (int c = 0; c < 3; ++c) {
                    const double centre = start + spacing * c + (stuck && c == 2 ? nd * 0.45 : 0.0);
                    const double amp = amp0 * (1.0 + 0.15 * g.normal()) * (c == 1 ? 1.1 : 1.0);
                    const double skew = sh.sides ? 0.15 * std::sin(orientation + c * 2.1) : 0.02 * g.normal();
                    for (int i = 0; i < n; ++i) {
                        const double u = (i - centre) / width;
                        const double side = u < 0 ? (1.0 - skew) : (1.0 + skew);
                        double v = std::exp(-0.5 * (u / side) * (u / side) * 4.0);
                        if (sh.sides > 0)  // faces: lobes at the edge passages
                            v *= 1.0 + 0.25 * std::cos(sh.sides * (u * 1.2) + orientation);
                        t.channels[static_cast<std::size_t>(c)][static_cast<std::size_t>(i)] =
                            amp * v + 0.004 * g.normal();
                    }
                }
                for (int i = 0; i < n; ++i) t.time.push_back(i / 31.1);
                out.push_back(std::move(t));
            }
    return out;
}

}  // namespace bench
