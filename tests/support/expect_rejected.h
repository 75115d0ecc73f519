#pragma once
// Settings and arguments outside their limits are rejected by the constructor or function that
// takes them, with std::invalid_argument naming the field, the limit and the value.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace warpath::testing {

// Expects `make()` to throw std::invalid_argument whose message is `message`.
template <class Make>
void expectRejected(const Make& make, const std::string& message) {
  try {
    make();
    ADD_FAILURE() << "accepted; expected: " << message;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

}  // namespace warpath::testing
