// Portable short vectors for the feature pipeline's inner loops (internal).
//
// GCC/Clang vector extensions: element-wise IEEE operations, so a lane computes
// bit for bit what the same scalar expression computes. That is what lets the
// vectorised Goertzel sweep and Gaussian filter keep every window and every
// feature identical to the scalar definition. The SDK is compiled with
// -ffp-contract=off (kernel/CMakeLists.txt), so the compiler never fuses a
// multiply and an add (which would round once instead of twice and change
// results), also on targets with FMA such as AArch64.
//
// `Vec2` (SSE2 on x86-64, NEON on AArch64) is always available. `Vec4` is used
// only inside functions compiled for AVX2 and called after has_avx2() said yes.
#pragma once

#include <cstddef>
#include <cstring>

namespace rollsense::features::simd {

typedef double Vec2 __attribute__((vector_size(16)));
typedef double Vec4 __attribute__((vector_size(32)));

template <class V>
inline constexpr std::size_t lanes = sizeof(V) / sizeof(double);

// Unaligned load and store (memcpy compiles to one move). Vectors go by
// reference: returning a 32-byte vector from a function not compiled for AVX
// would use a different calling convention (GCC's -Wpsabi).
template <class V>
[[gnu::always_inline]] inline void load(V& v, const double* p) {
    std::memcpy(&v, p, sizeof v);
}
template <class V>
[[gnu::always_inline]] inline void store(double* p, const V& v) {
    std::memcpy(p, &v, sizeof v);
}

// True when the CPU and the OS support AVX2 (checked once), unless the
// environment sets ROLLSENSE_SIMD=generic. Always false off x86.
bool has_avx2() noexcept;

}  // namespace rollsense::features::simd

// Marks a function to be compiled for AVX2 (x86 only; elsewhere the AVX2
// variants are not built and ROLLSENSE_HAVE_AVX2_VARIANT is 0).
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define ROLLSENSE_HAVE_AVX2_VARIANT 1
#define ROLLSENSE_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define ROLLSENSE_HAVE_AVX2_VARIANT 0
#define ROLLSENSE_TARGET_AVX2
#endif
