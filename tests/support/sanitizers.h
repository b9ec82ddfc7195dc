#pragma once
/// Test support: whether this build runs under AddressSanitizer, which makes long
/// simulations ten times slower, so that a test can run fewer frames there.

namespace voxhap::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif

}  // namespace voxhap::test
