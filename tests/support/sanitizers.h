// Whether this build runs under the sanitizers (tools/test.sh's second suite, build-sanitize/).
// A test whose work is large (many frames, scenes or tolerances through the same code) takes
// fewer of them there: the sanitizers check memory and undefined behaviour on the same code
// paths, and the Release suite runs the full size (docs/testing.md).
#pragma once

namespace voxspan::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderSanitizers = true;
#else
inline constexpr bool kUnderSanitizers = false;
#endif

}  // namespace voxspan::test
