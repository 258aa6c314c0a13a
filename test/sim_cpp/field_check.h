// Test helper for configuration checks: a call must throw
// std::invalid_argument whose message names the offending field.
#ifndef SIM_FIELD_CHECK_H
#define SIM_FIELD_CHECK_H

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace simtest {

template <class F>
void expect_rejects_field(F&& call, const std::string& field)
{
  try {
    call();
    ADD_FAILURE() << "accepted, expected a rejection naming " << field;
  } catch (const std::invalid_argument& x) {
    EXPECT_NE(std::string(x.what()).find(field), std::string::npos) << x.what();
  }
}

}  // namespace simtest

#endif  // SIM_FIELD_CHECK_H
