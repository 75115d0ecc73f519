#pragma once
// WARPATH_INVARIANT(condition, message): an internal invariant, checked in debug builds and in
// the sanitizer build (CMake option WARPATH_SANITIZE defines WARPATH_CHECK_INVARIANTS), compiled
// out of Release builds. A broken invariant is a bug in warpath, not bad input: it prints where
// and why and aborts, so tests and fuzzers stop on the first one. Bad input is never checked
// with this; it gets a status result at the library boundary.

#include <cstdio>
#include <cstdlib>

#if !defined(NDEBUG) || defined(WARPATH_CHECK_INVARIANTS)
#define WARPATH_INVARIANTS_ON 1
#define WARPATH_INVARIANT(condition, message)                                                 \
  do {                                                                                        \
    if (!(condition)) {                                                                       \
      std::fprintf(stderr, "%s:%d: invariant broken: %s (%s)\n", __FILE__, __LINE__, message, \
                   #condition);                                                               \
      std::abort();                                                                           \
    }                                                                                         \
  } while (false)
#else
#define WARPATH_INVARIANTS_ON 0
#define WARPATH_INVARIANT(condition, message) \
  do {                                        \
  } while (false && (condition))
#endif
