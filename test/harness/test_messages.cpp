// Messages and the data-flow map.
#include <gtest/gtest.h>

#include "harness/core/messages.h"

namespace {
struct Att {
  double sigma[3];
};
struct Cmd {
  double u[4];
};
}  // namespace

TEST(Messages, WriteReadThroughHarness)
{
  harness::DataFlow f;
  auto& att = f.add_message<Att>("att");
  auto w = f.writer("nav", att);
  auto r = f.reader("ctrl", att);
  EXPECT_EQ(r.write_count(), 0u);
  EXPECT_EQ(r.read().sigma[0], 0.0);  // value-initialised before the first write
  w.write(Att{{0.1, 0.2, 0.3}}, 500);
  EXPECT_EQ(r.read().sigma[2], 0.3);
  EXPECT_EQ(r.t_ns(), 500u);
  EXPECT_EQ(r.write_count(), 1u);
}

TEST(Messages, OneWriterPerMessage)
{
  harness::DataFlow f;
  auto& att = f.add_message<Att>("att");
  f.writer("nav", att);
  EXPECT_NO_THROW(f.writer("nav", att));  // same component again is fine
  EXPECT_THROW(f.writer("other", att), std::invalid_argument);
  EXPECT_THROW(f.add_message<Cmd>("att"), std::invalid_argument);
  EXPECT_THROW(f.add_message<Cmd>(""), std::invalid_argument);
}

TEST(DataFlow, DotListsComponentsMessagesAndEdges)
{
  harness::DataFlow f;
  f.add_component("mrp_fb", "fsw_c");
  auto& att = f.add_message<Att>("att_guid");
  auto& cmd = f.add_message<Cmd>("rw_cmd");
  f.writer("att_track", att);
  f.reader("mrp_fb", att);
  f.writer("mrp_fb", cmd);
  f.reader("plant", cmd);
  EXPECT_EQ(f.writer_of("rw_cmd"), "mrp_fb");
  EXPECT_EQ(f.readers_of("att_guid"), std::vector<std::string>{"mrp_fb"});
  const std::string dot = f.to_dot("t");
  EXPECT_EQ(dot.rfind("digraph \"t\" {", 0), 0u);
  EXPECT_NE(dot.find("\"c:att_track\" -> \"m:att_guid\";"), std::string::npos);
  EXPECT_NE(dot.find("\"m:att_guid\" -> \"c:mrp_fb\";"), std::string::npos);
  EXPECT_NE(dot.find("\"c:mrp_fb\" -> \"m:rw_cmd\";"), std::string::npos);
  EXPECT_NE(dot.find("\"m:rw_cmd\" -> \"c:plant\";"), std::string::npos);
  EXPECT_NE(dot.find("label=\"mrp_fb (fsw_c)\""), std::string::npos);
  EXPECT_EQ(dot.back(), '\n');
  EXPECT_EQ(dot.substr(dot.size() - 2), "}\n");
  // 4 edges exactly
  size_t arrows = 0;
  for (size_t p = dot.find("->"); p != std::string::npos; p = dot.find("->", p + 1)) ++arrows;
  EXPECT_EQ(arrows, 4u);
}
