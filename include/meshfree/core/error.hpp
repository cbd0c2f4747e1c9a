#pragma once
// Errors with context. MF_REQUIRE is always on (user input, run-time conditions);
// MF_ASSERT checks internal invariants in debug builds only.
#include <sstream>
#include <stdexcept>
#include <string>

namespace mf {

/// An error the user can act on: bad input, a failed solve, a diverging run.
class Error : public std::runtime_error {
public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

namespace detail {
template <class... Args> std::string concat(const Args&... args) {
  std::ostringstream os;
  os.precision(10);
  (os << ... << args);
  return os.str();
}
} // namespace detail

template <class... Args> [[noreturn]] void fail(const Args&... args) {
  throw Error(detail::concat(args...));
}

} // namespace mf

#define MF_REQUIRE(cond, ...)                                                                      \
  do {                                                                                             \
    if (!(cond)) ::mf::fail(__VA_ARGS__);                                                          \
  } while (0)

#ifndef NDEBUG
#define MF_ASSERT(cond)                                                                            \
  do {                                                                                             \
    if (!(cond))                                                                                   \
      ::mf::fail("internal invariant violated: ", #cond, " at ", __FILE__, ":", __LINE__);         \
  } while (0)
#else
#define MF_ASSERT(cond)                                                                            \
  do {                                                                                             \
  } while (0)
#endif
