// Recorder: rows streamed to sinks in fixed chunks (the only storage is one
// chunk), quantities grouped per message, overflow never silent, and the
// in-memory sink preallocated once.
#include <gtest/gtest.h>

#include <stdexcept>

#include "harness/core/recorder.h"

namespace {
struct Msg {
  double a, b;
};

// Counts what reaches it and checks the chunk protocol.
struct CountingSink : harness::RecordSink {
  uint64_t expected = 0, rows = 0;
  size_t begins = 0, ends = 0, max_chunk = 0, writes = 0;
  bool complete = false;
  std::vector<double> first_col;
  size_t nc = 0;
  void begin(const harness::RecordLayout& l, uint64_t e) override
  {
    ++begins;
    expected = e;
    nc = l.columns.size();
  }
  void write(const double* r, size_t n) override
  {
    ++writes;
    max_chunk = std::max(max_chunk, n);
    for (size_t i = 0; i < n; ++i) first_col.push_back(r[i * nc]);
    rows += n;
  }
  void end(bool c) override
  {
    ++ends;
    complete = c;
  }
};
}  // namespace

TEST(Recorder, RecordsAnyMessageIntoTheMemorySink)
{
  harness::DataFlow f;
  auto& ch = f.add_message<Msg>("m");
  auto w = f.writer("src", ch);
  harness::Recorder rec("r");
  int k = 0;
  rec.add_source({{"k", "-"}}, [&k](double* o) { o[0] = k; });
  rec.record<Msg>(ch, {{"a", "m", "", {"a"}}, {"b2", "m^2", "", {"b2"}}}, [](const Msg& m, double* o) {
    o[0] = m.a;
    o[1] = m.b * m.b;
  });
  rec.allocate(5, 2);  // chunks of 2 rows
  harness::MemorySink mem;
  rec.add_sink(mem);
  const double* storage = mem.storage_address();
  const double* chunk = rec.chunk_address();
  for (k = 0; k < 5; ++k) {
    w.write(Msg{1.0 * k, 3.0}, 0);
    ASSERT_TRUE(rec.sample());
    EXPECT_EQ(rec.last_row()[0], k);  // the row just written, whether flushed or not
    EXPECT_EQ(mem.storage_address(), storage);  // never reallocated
    EXPECT_EQ(rec.chunk_address(), chunk);
  }
  EXPECT_EQ(mem.rows(), 4u);  // two full chunks handed over, the fifth row pending
  rec.finish(true);
  EXPECT_EQ(mem.rows(), 5u);
  EXPECT_TRUE(mem.complete());
  EXPECT_EQ(rec.rows(), 5u);
  EXPECT_EQ(rec.capacity(), 5u);
  EXPECT_EQ(mem.at(3, 0), 3.0);
  EXPECT_EQ(mem.at(3, 1), 3.0);
  EXPECT_EQ(mem.at(4, 2), 9.0);
  EXPECT_EQ(mem.column("a"), (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(rec.columns()[2].unit, "m^2");
  EXPECT_EQ(rec.columns()[2].group, "m");
  EXPECT_EQ(rec.recorded_messages(), std::vector<std::string>{"m"});
  // full: refused and counted, the stored rows are untouched
  EXPECT_FALSE(rec.sample());
  EXPECT_EQ(rec.overflow(), 1u);
  EXPECT_EQ(mem.rows(), 5u);
}

TEST(Recorder, QuantitiesKeepTheirComponentsTogether)
{
  harness::DataFlow f;
  auto& ch = f.add_message<Msg>("truth");
  harness::Recorder rec("r");
  rec.add_source("", {{"t", "s", "", {"t"}}}, [](double* o) { o[0] = 0; });
  rec.record<Msg>(ch, {{"v", "m/s", "N", {"v_x", "v_y", "v_z"}}, {"s", "-", "", {"s"}}},
                  [](const Msg&, double* o) { o[0] = o[1] = o[2] = o[3] = 0; });
  rec.allocate(1);
  const harness::RecordLayout& l = rec.layout();
  ASSERT_EQ(l.quantities.size(), 3u);
  EXPECT_EQ(l.quantities[1].group, "truth");
  EXPECT_EQ(l.quantities[1].name, "v");
  EXPECT_EQ(l.quantities[1].frame, "N");
  EXPECT_EQ(l.quantities[1].first_col, 1u);
  EXPECT_EQ(l.quantities[1].num_cols, 3u);
  EXPECT_EQ(l.quantities[2].first_col, 4u);
  EXPECT_EQ(l.columns[3].name, "v_z");
  EXPECT_EQ(l.columns[3].quantity, "v");
  EXPECT_EQ(l.columns[3].component, 2);
}

// A long run through a small chunk: every row reaches the sink once, in
// order, in chunks of at most chunk_rows, while the recorder holds one chunk.
TEST(Recorder, StreamsAnyNumberOfRowsThroughOneChunk)
{
  harness::Recorder rec("r");
  uint64_t i = 0;
  rec.add_source({{"i", "-"}, {"twice", "-"}}, [&i](double* o) {
    o[0] = static_cast<double>(i);
    o[1] = 2.0 * static_cast<double>(i);
  });
  const uint64_t n = 100003;  // not a multiple of the chunk
  rec.allocate(n, 64);
  CountingSink s;
  rec.add_sink(s);
  EXPECT_EQ(s.begins, 1u);
  EXPECT_EQ(s.expected, n);
  for (i = 0; i < n; ++i) ASSERT_TRUE(rec.sample());
  EXPECT_EQ(s.rows, n - n % 64);
  rec.finish(true);
  rec.finish(false);  // once only
  EXPECT_EQ(s.ends, 1u);
  EXPECT_TRUE(s.complete);
  EXPECT_EQ(s.rows, n);
  EXPECT_EQ(s.max_chunk, 64u);
  EXPECT_EQ(s.writes, (n + 63) / 64);
  for (uint64_t r = 0; r < n; ++r) ASSERT_EQ(s.first_col[r], static_cast<double>(r));
  EXPECT_FALSE(rec.sample());  // finished: nothing more is taken
}

TEST(Recorder, AnIncompleteRunEndsItsSinksIncomplete)
{
  harness::Recorder rec("r");
  rec.add_source({{"x", "-"}}, [](double* o) { o[0] = 1; });
  rec.allocate(10, 4);
  CountingSink s;
  rec.add_sink(s);
  for (int i = 0; i < 6; ++i) rec.sample();
  rec.finish(false);
  EXPECT_FALSE(s.complete);
  EXPECT_EQ(s.rows, 6u);
}

TEST(Recorder, SetupErrors)
{
  harness::Recorder rec("r");
  CountingSink s;
  EXPECT_THROW(rec.add_sink(s), std::logic_error);  // before allocate
  rec.add_source({{"x", "-"}}, [](double* o) { o[0] = 1; });
  EXPECT_THROW(rec.add_source({{"x", "-"}}, [](double* o) { o[0] = 1; }), std::invalid_argument);
  EXPECT_THROW(rec.add_source({{"", "-"}}, [](double* o) { o[0] = 1; }), std::invalid_argument);
  EXPECT_THROW(rec.add_source("g", {{"q", "-", "", {}}}, [](double* o) { o[0] = 1; }), std::invalid_argument);
  rec.allocate(2);
  EXPECT_THROW(rec.add_source({{"y", "-"}}, [](double* o) { o[0] = 1; }), std::logic_error);
  EXPECT_THROW(rec.allocate(3), std::logic_error);
  EXPECT_THROW(rec.column_index("nope"), std::out_of_range);
  rec.sample();
  EXPECT_THROW(rec.add_sink(s), std::logic_error);  // after the first sample
}
