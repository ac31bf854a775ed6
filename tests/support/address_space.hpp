// Whether a test may cap its address space (RLIMIT_AS). An address-space cap
// cannot coexist with AddressSanitizer's shadow memory (terabytes of reserved
// address space): under ASan a limited child runs without the cap, and the
// sanitizer run's ASAN_OPTIONS=max_allocation_size_mb (tools/sanitize.sh)
// makes a huge allocation end the child with a report instead.
#pragma once

namespace rollsense::testing {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kCanLimitAddressSpace = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kCanLimitAddressSpace = false;
#else
inline constexpr bool kCanLimitAddressSpace = true;
#endif
#else
inline constexpr bool kCanLimitAddressSpace = true;
#endif

}  // namespace rollsense::testing
