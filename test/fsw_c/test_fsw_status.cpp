// Status codes, health counters and the integrator's assert hook.
#include <gtest/gtest.h>

#include <climits>
#include <cstdio>
#include <cstring>

#include "fsw/fsw_config.h"
#include "fsw/fsw_linalg.h"
#include "fsw/fsw_status.h"
#include "fsw/fsw_version.h"
#include "kestrel_test_support.h"

namespace {

// Verifies: REQ-GEN-005
TEST(FswStatus, ErrorsNegativeWarningsPositive)
{
  EXPECT_EQ(0, FSW_OK);
  const FswStatus errors[] = {FSW_E_NULL_ARG, FSW_E_CONFIG,   FSW_E_CAPACITY,    FSW_E_SINGULAR,
                              FSW_E_BAD_INPUT, FSW_E_TIME,    FSW_E_UNSUPPORTED, FSW_E_NOT_INIT};
  for (FswStatus s : errors) {
    EXPECT_LT(static_cast<int>(s), 0) << fsw_status_name(s);
    EXPECT_TRUE(fsw_status_is_error(s));
  }
  const FswStatus warnings[] = {FSW_W_SINGULAR, FSW_W_SAT, FSW_W_RATE};
  for (FswStatus s : warnings) {
    EXPECT_GT(static_cast<int>(s), 0) << fsw_status_name(s);
    EXPECT_FALSE(fsw_status_is_error(s));
  }
  EXPECT_FALSE(fsw_status_is_error(FSW_OK));
  EXPECT_EQ(FSW_E_INPUT, FSW_E_BAD_INPUT);  // the alternative spelling
}

// Verifies: REQ-GEN-005
TEST(FswStatus, NamesAreDistinctAndUnknownIsReported)
{
  const FswStatus all[] = {FSW_OK,          FSW_W_SINGULAR, FSW_W_SAT,      FSW_W_RATE,
                           FSW_E_NULL_ARG,  FSW_E_CONFIG,   FSW_E_CAPACITY, FSW_E_SINGULAR,
                           FSW_E_BAD_INPUT, FSW_E_TIME,     FSW_E_UNSUPPORTED, FSW_E_NOT_INIT};
  const size_t n = sizeof(all) / sizeof(all[0]);
  for (size_t i = 0; i < n; i++) {
    EXPECT_STRNE("FSW_UNKNOWN", fsw_status_name(all[i]));
    for (size_t j = i + 1; j < n; j++) EXPECT_STRNE(fsw_status_name(all[i]), fsw_status_name(all[j]));
  }
  EXPECT_STREQ("FSW_OK", fsw_status_name(FSW_OK));
  EXPECT_STREQ("FSW_E_TIME", fsw_status_name(FSW_E_TIME));
  EXPECT_STREQ("FSW_UNKNOWN", fsw_status_name(static_cast<FswStatus>(42)));
}

// Verifies: REQ-GEN-006
TEST(FswHealth, EachStatusBumpsItsCounter)
{
  FswHealth h;
  std::memset(&h, 0xA5, sizeof h);
  fsw_health_clear(&h);
  EXPECT_EQ(0u, h.calls);
  EXPECT_EQ(FSW_OK, h.last);

  EXPECT_EQ(FSW_OK, fsw_health_record(&h, FSW_OK));
  EXPECT_EQ(FSW_E_BAD_INPUT, fsw_health_record(&h, FSW_E_BAD_INPUT));
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_health_record(&h, FSW_E_NULL_ARG));
  fsw_health_record(&h, FSW_E_TIME);
  fsw_health_record(&h, FSW_W_SAT);
  fsw_health_record(&h, FSW_W_SAT);
  fsw_health_record(&h, FSW_W_SINGULAR);
  fsw_health_record(&h, FSW_E_SINGULAR);
  fsw_health_record(&h, FSW_W_RATE);
  fsw_health_record(&h, FSW_E_CONFIG);
  fsw_health_record(&h, FSW_E_UNSUPPORTED);

  EXPECT_EQ(11u, h.calls);
  EXPECT_EQ(2u, h.bad_input);
  EXPECT_EQ(1u, h.bad_time);
  EXPECT_EQ(2u, h.saturated);
  EXPECT_EQ(2u, h.singular);
  EXPECT_EQ(1u, h.rate);
  EXPECT_EQ(2u, h.other_error);
  EXPECT_EQ(FSW_E_UNSUPPORTED, h.last);
}

// Verifies: REQ-GEN-006
TEST(FswHealth, CountersSaturateInsteadOfWrapping)
{
  FswHealth h;
  fsw_health_clear(&h);
  h.bad_input = UINT32_MAX - 1u;
  h.calls = UINT32_MAX - 1u;
  fsw_health_record(&h, FSW_E_BAD_INPUT);
  fsw_health_record(&h, FSW_E_BAD_INPUT);
  fsw_health_record(&h, FSW_E_BAD_INPUT);
  EXPECT_EQ(UINT32_MAX, h.bad_input);
  EXPECT_EQ(UINT32_MAX, h.calls);
}

// Verifies: REQ-GEN-006
TEST(FswHealth, NullHealthIsIgnored)
{
  EXPECT_EQ(FSW_W_SAT, fsw_health_record(nullptr, FSW_W_SAT));
}

// Verifies: REQ-GEN-007
TEST(FswAssert, HookIsCalledOnProgrammerErrorAndFunctionReturnsNullArg)
{
  kestrel_assert_reset();
  fsw_real b[3] = {FSW_R(1.0), FSW_R(0.0), FSW_R(0.0)};
  fsw_real x[FSW_MAX_EFF];
  EXPECT_EQ(FSW_E_NULL_ARG, fsw_minnorm_solve(x, nullptr, b, 1, 1));
  EXPECT_EQ(1ul, kestrel_assert_count());
  ASSERT_NE(nullptr, kestrel_assert_last_file());
  EXPECT_NE(nullptr, std::strstr(kestrel_assert_last_file(), "fsw_linalg.c"));
  EXPECT_GT(kestrel_assert_last_line(), 0);

  fsw_health_clear(nullptr);  // void function: asserts, then does nothing
  EXPECT_EQ(2ul, kestrel_assert_count());
  kestrel_assert_reset();
  EXPECT_EQ(0ul, kestrel_assert_count());
}

// Verifies: REQ-GEN-008
TEST(FswConfig, CapacitiesAndRealType)
{
  EXPECT_GE(FSW_MAX_RW, 3);
  EXPECT_GE(FSW_MAX_THR, 1);
  EXPECT_EQ(FSW_MAX_EFF, FSW_MAX_RW > FSW_MAX_THR ? FSW_MAX_RW : FSW_MAX_THR);
#if FSW_USE_FLOAT
  EXPECT_EQ(sizeof(float), sizeof(fsw_real));
  EXPECT_STREQ("float", FSW_VERSION_REAL);
#else
  EXPECT_EQ(sizeof(double), sizeof(fsw_real));
  EXPECT_STREQ("double", FSW_VERSION_REAL);
#endif
  // A zero-initialised availability mask means "all available" (docs/fsw-conventions.md, "Frames, units and signs").
  EXPECT_EQ(0, FSW_AVAILABLE);
  EXPECT_EQ(1, FSW_UNAVAILABLE);
}

// Verifies: REQ-GEN-008
TEST(FswVersion, GeneratedHeaderIsConsistent)
{
  EXPECT_EQ(FSW_VERSION_MAJOR * 10000 + FSW_VERSION_MINOR * 100 + FSW_VERSION_PATCH,
            FSW_VERSION_NUMBER);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%d.%d.%d", FSW_VERSION_MAJOR, FSW_VERSION_MINOR,
                FSW_VERSION_PATCH);
  EXPECT_STREQ(buf, FSW_VERSION_STRING);
}

}  // namespace
