#include "simd.hpp"

#include <cstdlib>
#include <string_view>

namespace rollsense::features::simd {

bool has_avx2() noexcept {
#if ROLLSENSE_HAVE_AVX2_VARIANT
    // ROLLSENSE_SIMD=generic forces the portable kernels, so that tests and
    // benches can check and time the path a CPU without AVX2 takes. libgcc's
    // check includes the OS saving the YMM registers (XGETBV).
    static const bool yes = [] {
        const char* forced = std::getenv("ROLLSENSE_SIMD");
        if (forced && std::string_view(forced) == "generic") return false;
        return __builtin_cpu_supports("avx2") != 0;
    }();
    return yes;
#else
    return false;
#endif
}

}  // namespace rollsense::features::simd
