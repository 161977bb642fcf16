#pragma once
// Tests of bad input: the call must throw InputError with the given rule and a message containing
// the given fragment.
#include <gtest/gtest.h>
#include <kontur/error.hpp>

#include <string>

namespace kontur::testing {

/// Calls f(); passes when it throws InputError whose rule() is `rule` and whose message contains
/// `fragment`.
template <class F>
void expect_input_error(F&& f, const std::string& rule, const std::string& fragment) {
  try {
    f();
    FAIL() << "no InputError, expected " << rule;
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), rule) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace kontur::testing
