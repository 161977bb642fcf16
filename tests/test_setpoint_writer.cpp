// Setpoint sinks: CSV header and rows, the binary layout, byte-for-byte reproducibility.
#include <gtest/gtest.h>
#include <kontur/io/setpoint_writer.hpp>
#include <kontur/geometry/line_segment.hpp>

#include "support/planner_run.hpp"

#include <cstring>
#include <sstream>

namespace kontur {
namespace {

std::string run(SetpointFormat f) {
  const auto setpoints = testing::plan_and_sample(
      default_machine(), {program::move_along(std::make_shared<LineSegment>(Vec3(0, 0, 0), Vec3(10, 5, -2)), 50.0, false, 12)});
  std::ostringstream out;
  SetpointWriter w(out, f, 1e-3);
  for (const auto& s : setpoints) w.write(s);
  return out.str();
}

TEST(SetpointWriter, CsvHasHeaderRowsAndExactEnds) {
  const std::string csv = run(SetpointFormat::csv);
  EXPECT_EQ(csv.rfind("t,x,y,z,v,block\n0.000000000,0,0,0,0.000000,12\n", 0), 0u);
  EXPECT_NE(csv.find(",10,5,-2,0.000000,12\n"), std::string::npos);
  EXPECT_EQ(csv.find("nan"), std::string::npos);
  EXPECT_EQ(csv, run(SetpointFormat::csv));  // reproducible byte for byte
}

TEST(SetpointWriter, BinaryLayout) {
  const std::string bin = run(SetpointFormat::binary);
  ASSERT_GE(bin.size(), 24u);
  EXPECT_EQ(bin.substr(0, 8), "KONTURSP");
  std::uint32_t version = 0, record = 0;
  double period = 0;
  std::memcpy(&version, bin.data() + 8, 4);
  std::memcpy(&record, bin.data() + 12, 4);
  std::memcpy(&period, bin.data() + 16, 8);
  EXPECT_EQ(version, 1u);
  EXPECT_EQ(record, 48u);
  EXPECT_EQ(period, 1e-3);
  EXPECT_EQ((bin.size() - 24) % 48, 0u);
  // The last record is the end point at rest.
  double last[5];
  std::int64_t line = 0;
  std::memcpy(last, bin.data() + bin.size() - 48, 40);
  std::memcpy(&line, bin.data() + bin.size() - 8, 8);
  EXPECT_EQ(last[1], 10.0);
  EXPECT_EQ(last[2], 5.0);
  EXPECT_EQ(last[3], -2.0);
  EXPECT_EQ(last[4], 0.0);
  EXPECT_EQ(line, 12);
  EXPECT_EQ(bin, run(SetpointFormat::binary));
}

}  // namespace
}  // namespace kontur
