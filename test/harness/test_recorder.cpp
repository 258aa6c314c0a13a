// Recorder: preallocated storage, no reallocation, overflow never silent.
#include <gtest/gtest.h>

#include "harness/recorder.h"

namespace {
struct Msg {
  double a, b;
};
}  // namespace

TEST(Recorder, RecordsAnyMessageIntoPreallocatedRows)
{
  harness::DataFlow f;
  auto& ch = f.add_message<Msg>("m");
  auto w = f.writer("src", ch);
  harness::Recorder rec("r");
  int k = 0;
  rec.add_source({{"k", "-"}}, [&k](double* o) { o[0] = k; });
  rec.record<Msg>(ch, {{"a", "m"}, {"b2", "m^2"}}, [](const Msg& m, double* o) {
    o[0] = m.a;
    o[1] = m.b * m.b;
  });
  rec.allocate(5);
  const double* storage = rec.storage_address();
  for (k = 0; k < 5; ++k) {
    w.write(Msg{1.0 * k, 3.0}, 0);
    ASSERT_TRUE(rec.sample());
    EXPECT_EQ(rec.storage_address(), storage);  // never reallocated
  }
  EXPECT_EQ(rec.rows(), 5u);
  EXPECT_EQ(rec.capacity(), 5u);
  EXPECT_EQ(rec.at(3, 0), 3.0);
  EXPECT_EQ(rec.at(3, 1), 3.0);
  EXPECT_EQ(rec.at(4, 2), 9.0);
  EXPECT_EQ(rec.column("a"), (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(rec.columns()[2].unit, "m^2");
  EXPECT_EQ(rec.recorded_messages(), std::vector<std::string>{"m"});
  // full: refused and counted, the stored rows are untouched
  EXPECT_FALSE(rec.sample());
  EXPECT_EQ(rec.overflow(), 1u);
  EXPECT_EQ(rec.rows(), 5u);
  EXPECT_EQ(rec.storage_address(), storage);
}

TEST(Recorder, SetupErrors)
{
  harness::Recorder rec("r");
  rec.add_source({{"x", "-"}}, [](double* o) { o[0] = 1; });
  EXPECT_THROW(rec.add_source({{"x", "-"}}, [](double* o) { o[0] = 1; }), std::invalid_argument);
  EXPECT_THROW(rec.add_source({{"", "-"}}, [](double* o) { o[0] = 1; }), std::invalid_argument);
  rec.allocate(2);
  EXPECT_THROW(rec.add_source({{"y", "-"}}, [](double* o) { o[0] = 1; }), std::logic_error);
  EXPECT_THROW(rec.allocate(3), std::logic_error);
  EXPECT_THROW(rec.column_index("nope"), std::out_of_range);
}
