// main() of every GoogleTest executable, host and target.  It also checks
// that no test left an unexpected FSW assertion behind.
#include <gtest/gtest.h>

#include "kestrel_test_support.h"

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
