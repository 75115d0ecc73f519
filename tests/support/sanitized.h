#pragma once
// The sanitizer build (tools/test.sh, step 2) runs the heaviest scenario and random-map tests on
// fewer seeds and maps than Release does. It is there to catch memory errors and undefined
// behaviour, which depend on the code paths a test reaches more than on how often it reaches
// them; and there a battle runs five to ten times slower, so the full sets would take most of
// the suite's 20-minute budget. Release runs every test in full.

namespace warpath::testing {

#ifdef WARPATH_SANITIZED_TESTS
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

// `full` in Release, `sanitized` in the sanitizer build.
template <typename T>
constexpr T fullOrSanitized(T full, T sanitized) {
  return kSanitized ? sanitized : full;
}

}  // namespace warpath::testing
