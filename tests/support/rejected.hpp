#pragma once
// The one check every bad-input test makes: a call throws std::invalid_argument naming what it
// refused.

#include <gtest/gtest.h>

#include <initializer_list>
#include <stdexcept>
#include <string>

namespace eco::test {

/// Runs `call`, expects std::invalid_argument whose message contains every one of `words`.
template <class Call>
void expect_rejected(Call&& call, std::initializer_list<std::string> words) {
  try {
    call();
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    for (const std::string& w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
  }
}

}  // namespace eco::test
