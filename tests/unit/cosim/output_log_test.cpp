// The node's output log: what is written is read back bit for bit, in both modes; the
// background mode keeps every row and their order when the ring wraps several times.
#include "mechsim/cosim/output_log.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

namespace mechsim::cosim {
namespace {

namespace fs = std::filesystem;

class OutputLogTest : public ::testing::TestWithParam<OutputLogWriter::Mode> {};

TEST_P(OutputLogTest, RowsComeBackBitForBitAndInOrder) {
  const fs::path file = fs::temp_directory_path() / ("mechsim_output_log_" + std::to_string(::getpid()) + ".bin");
  // 50 000 rows: three wraps of the 16 384-row ring in background mode.
  constexpr int kRows = 50000;
  {
    OutputLogWriter log(file.string(), {"a", "b"}, GetParam());
    for (int k = 0; k < kRows; ++k) {
      const double values[2] = {std::sin(k * 0.001), 1.0 / (k + 1)};
      log.append(k * 1e-3, values);
    }
    log.close();
  }
  const OutputLog back = read_output_log(file.string());
  ASSERT_EQ(back.columns, (std::vector<std::string>{"t", "a", "b"}));
  ASSERT_EQ(back.data[0].size(), static_cast<std::size_t>(kRows));
  for (int k = 0; k < kRows; ++k) {
    ASSERT_EQ(back.data[0][k], k * 1e-3) << k;
    ASSERT_EQ(back.data[1][k], std::sin(k * 0.001)) << k;
    ASSERT_EQ(back.data[2][k], 1.0 / (k + 1)) << k;
  }
  fs::remove(file);
}

INSTANTIATE_TEST_SUITE_P(BothModes, OutputLogTest,
                         ::testing::Values(OutputLogWriter::Mode::direct, OutputLogWriter::Mode::background));

}  // namespace
}  // namespace mechsim::cosim
