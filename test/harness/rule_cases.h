// rule_cases.h: scenario rules checked by overriding keys of a base file:
// each case must be rejected with an issue at `key` whose message contains
// `words` (harness::ScenarioError, docs/harness.md "Validation").
#ifndef KESTREL_TEST_HARNESS_RULE_CASES_H
#define KESTREL_TEST_HARNESS_RULE_CASES_H

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "harness/scenario/scenario.h"

namespace testutil {

struct RuleCase {
  std::vector<harness::Override> set;
  const char* key;
  const char* words;
};

inline void expect_rules_named(const std::string& file, const std::vector<RuleCase>& cases)
{
  for (const RuleCase& c : cases) {
    SCOPED_TRACE(c.key);
    try {
      harness::load_scenario(file, c.set);
      ADD_FAILURE() << "accepted";
    } catch (const harness::ScenarioError& e) {
      bool found = false;
      for (const auto& is : e.issues())
        found = found || (is.key == c.key && is.message.find(c.words) != std::string::npos);
      EXPECT_TRUE(found) << e.what();
    }
  }
}

}  // namespace testutil

#endif  // KESTREL_TEST_HARNESS_RULE_CASES_H
