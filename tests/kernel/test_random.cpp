// rollsense/random.hpp: the SDK's seeded generator, shared by the bagged trees
// (numbered streams) and the sim sensor (named streams). Recorded datasets and
// trained models depend on every bit of it, so the expected values below were
// produced by the two generators it replaced (bagged_trees/rng.cpp and
// sensors/sim/rng.hpp before the merge).
#include <catch2/catch.hpp>

#include <cmath>

#include "rollsense/random.hpp"

using rollsense::random::Xoshiro256ss;

TEST_CASE("splitmix64 and xoshiro256** match their reference implementations", "[random]") {
    // splitmix64 seeded with 0: first output of Vigna's splitmix64.c.
    CHECK(rollsense::random::splitmix64(0) == 0xE220A8397B1DCDAFull);
    // xoshiro256** from the state {1, 2, 3, 4}: s1·5 rotated by 7, ·9, …
    auto g = Xoshiro256ss::from_state(1, 2, 3, 4);
    CHECK(g.next() == 11520u);
    CHECK(g.next() == 0u);
    CHECK(g.next() == 1509978240u);
    CHECK(g.next() == 1215971899390074240u);
    CHECK(rollsense::random::fnv1a64("") == 0xcbf29ce484222325ull);
    CHECK(rollsense::random::fnv1a64("a") == 0xaf63dc4c8601ec8cull);
}

TEST_CASE("numbered streams draw what the bagged trees' generator drew", "[random]") {
    auto t = Xoshiro256ss::numbered_stream(1, 0);
    CHECK(t.next() == 0x7e8e735316626359ull);
    CHECK(t.next() == 0xb952addd8b50363bull);
    CHECK(t.next() == 0x733b8080acbdffabull);
    CHECK(t.below(943) == 95u);
    CHECK(t.below(943) == 824u);
    CHECK(t.below(943) == 119u);
    CHECK(Xoshiro256ss::numbered_stream(42, 29).next() == 0x857c6207d7b70768ull);
    auto s = Xoshiro256ss::splitmix64_sequence(5);
    CHECK(s.next() == 0x49d55178ca54cf69ull);
    CHECK(s.uniform() == 0x1.344422b49a4c4p-1);
}

TEST_CASE("named streams draw what the sim's generator drew", "[random]") {
    auto a = Xoshiro256ss::named_stream(12345, "noise-ch1");
    CHECK(a.next() == 0x1de04eeff1eb1abeull);
    CHECK(a.next() == 0x2bfd12924dcdad8cull);
    CHECK(a.next() == 0x1a823496a33796b9ull);
    // Normals go through libm's log/sin/cos: equal to the last bit on this
    // platform, within rounding anywhere.
    CHECK(a.normal() == Approx(0x1.fc6fbe970d239p-5).epsilon(1e-14));
    CHECK(a.normal() == Approx(-0x1.15d6596ccbadap-2).epsilon(1e-14));
    CHECK(a.normal() == Approx(0x1.091c3fa57dd4ep+0).epsilon(1e-14));
    CHECK(a.uniform(2.0, 5.0) == 0x1.dae47c4f985fdp+1);
    auto b = Xoshiro256ss::splitmix64_chain(77);
    CHECK(b.next() == 0x823a9e1e6f47423bull);
    CHECK(b.next() == 0xbd2e6be6fbfce10cull);
}

TEST_CASE("streams are independent of each other and distributions stay in range", "[random]") {
    CHECK(Xoshiro256ss::numbered_stream(1, 0).next() != Xoshiro256ss::numbered_stream(1, 1).next());
    CHECK(Xoshiro256ss::numbered_stream(1, 0).next() != Xoshiro256ss::numbered_stream(2, 0).next());
    CHECK(Xoshiro256ss::named_stream(1, "a").next() != Xoshiro256ss::named_stream(1, "b").next());
    auto g = Xoshiro256ss::numbered_stream(3, 4);
    double sum = 0.0, sum_sq = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const auto k = g.below(7);
        REQUIRE(k < 7u);
        const double u = g.uniform();
        REQUIRE(u >= 0.0);
        REQUIRE(u < 1.0);
        const double z = g.normal();
        sum += z;
        sum_sq += z * z;
    }
    // Fixed seed, so deterministic; the bounds are 5 standard errors wide.
    CHECK(std::abs(sum / n) < 5.0 / std::sqrt(n));
    CHECK(std::abs(sum_sq / n - 1.0) < 5.0 * std::sqrt(2.0 / n));
}

TEST_CASE("SplitMix64 is the splitmix64 counter: output n is splitmix64(seed + n * gamma)", "[random]") {
    using namespace rollsense::random;
    SplitMix64 g(0);
    CHECK(g.next() == 0xE220A8397B1DCDAFull);  // Vigna's splitmix64.c, seed 0
    SplitMix64 h(12345);
    for (std::uint64_t n = 0; n < 5; ++n) CHECK(h.next() == splitmix64(12345 + n * kGoldenGamma));
    SplitMix64 u(7);
    for (int i = 0; i < 1000; ++i) {
        const double x = u.uniform();
        REQUIRE(x >= 0.0);
        REQUIRE(x < 1.0);
        REQUIRE(u.below(9) < 9);
    }
}
