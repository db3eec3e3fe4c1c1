#pragma once
// Whether this build runs under AddressSanitizer: a test of a long run's accuracy (not of memory)
// skips itself there and runs in the release build instead (make test builds it in both).

namespace eco::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

}  // namespace eco::test
