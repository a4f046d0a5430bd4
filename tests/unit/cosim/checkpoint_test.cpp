// Checkpoint files (checkpoint.h) and the output log's resume: what a restart with rollback
// reads back must be exactly what was written, and a damaged or half-written file is never
// taken for a checkpoint.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "mechsim/cosim/checkpoint.h"
#include "mechsim/cosim/output_log.h"

namespace mechsim::cosim {
namespace {

namespace fs = std::filesystem;

class CheckpointFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("mechsim-checkpoint-test-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  static NodeCheckpoint sample(std::uint64_t step) {
    NodeCheckpoint c;
    c.stepper.step = step;
    c.stepper.state = {1.0, -2.5e-300, 0.1 + 0.2};
    c.stepper.discrete = {1.0, 7.0};
    c.stepper.outputs = {std::nan(""), 3.0};
    c.stepper.channels = {{{step - 2, {0.5, 0.25}}, {step - 1, {0.75, 0.125}}}, {}};
    c.stepper.assumed_torque = -12.5;
    c.guard = {3.0, 400.0, 1e-12};
    c.output_rows = step + 1;
    c.events_bytes = 321;
    return c;
  }
  std::string dir() const { return dir_.string(); }
  fs::path dir_;
};

TEST_F(CheckpointFiles, ReadBackBitForBit) {
  write_checkpoint(dir(), "slide", sample(100));
  const NodeCheckpoint c = read_checkpoint(dir(), "slide", 100);
  const NodeCheckpoint e = sample(100);
  EXPECT_EQ(c.stepper.step, 100u);
  EXPECT_EQ(c.stepper.state, e.stepper.state);
  EXPECT_EQ(c.stepper.discrete, e.stepper.discrete);
  ASSERT_EQ(c.stepper.outputs.size(), 2u);
  EXPECT_TRUE(std::isnan(c.stepper.outputs[0]));
  EXPECT_EQ(c.stepper.outputs[1], 3.0);
  EXPECT_EQ(c.stepper.channels, e.stepper.channels);
  EXPECT_EQ(c.stepper.assumed_torque, e.stepper.assumed_torque);
  EXPECT_EQ(c.guard, e.guard);
  EXPECT_EQ(c.output_rows, 101u);
  EXPECT_EQ(c.events_bytes, 321);
  EXPECT_FALSE(fs::exists(checkpoint_path(dir(), "slide", 100) + ".tmp"));
}

TEST_F(CheckpointFiles, ADamagedOrForeignFileIsRefusedNamingIt) {
  write_checkpoint(dir(), "slide", sample(100));
  const std::string path = checkpoint_path(dir(), "slide", 100);
  const auto size = fs::file_size(path);
  fs::resize_file(path, size - 3);  // the end mark cut off
  try {
    read_checkpoint(dir(), "slide", 100);
    FAIL() << "a truncated checkpoint was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  write_checkpoint(dir(), "tacho", sample(100));
  fs::copy_file(checkpoint_path(dir(), "tacho", 100), checkpoint_path(dir(), "servo", 100));
  EXPECT_THROW(read_checkpoint(dir(), "servo", 100), std::runtime_error);  // names another node
  EXPECT_THROW(read_checkpoint(dir(), "servo", 200), std::runtime_error);  // none at all
}

TEST_F(CheckpointFiles, TheNewestStepEveryNodeHoldsIsCommonAndOldOnesGo) {
  for (std::uint64_t k : {100, 200, 300, 400}) write_checkpoint(dir(), "a", sample(k), 3);
  for (std::uint64_t k : {100, 200, 300}) write_checkpoint(dir(), "b", sample(k), 3);
  // b was killed while writing 400: a temporary file is no checkpoint.
  std::ofstream(checkpoint_path(dir(), "b", 400) + ".tmp") << "half";
  EXPECT_EQ(checkpoint_steps(dir(), "a"), (std::vector<std::uint64_t>{200, 300, 400}));
  EXPECT_EQ(checkpoint_steps(dir(), "b"), (std::vector<std::uint64_t>{100, 200, 300}));
  EXPECT_EQ(common_checkpoint(dir(), {"a", "b"}), 300u);
  EXPECT_EQ(common_checkpoint(dir(), {"a", "b", "c"}), std::nullopt);
  // Lock-step nodes are a few steps apart: with a short interval more are kept.
  EXPECT_EQ(checkpoints_to_keep(1000, 3), 3);
  EXPECT_GE(checkpoints_to_keep(1, 3), 10);
}

TEST_F(CheckpointFiles, AnOutputLogResumesAtTheCheckpointsRow) {
  const std::string path = dir() + "/n.outputs.bin";
  {
    OutputLogWriter w(path, {"x", "y"});
    for (int k = 0; k < 10; ++k) w.append(0.001 * k, std::vector<double>{1.0 * k, -1.0 * k});
    w.close();
  }
  {
    OutputLogWriter w(path, {"x", "y"}, OutputLogWriter::Resume{4});
    EXPECT_EQ(w.rows(), 4u);
    w.append(0.004, std::vector<double>{40.0, -40.0});
    w.close();
  }
  const OutputLog log = read_output_log(path);
  ASSERT_EQ(log.rows(), 5u);
  EXPECT_EQ(log.data[1][3], 3.0);
  EXPECT_EQ(log.data[1][4], 40.0);
  EXPECT_THROW(OutputLogWriter(path, {"x", "z"}, OutputLogWriter::Resume{2}), std::runtime_error);  // another node's columns
  EXPECT_THROW(OutputLogWriter(path, {"x", "y"}, OutputLogWriter::Resume{6}), std::runtime_error);  // fewer rows than asked
}

}  // namespace
}  // namespace mechsim::cosim
