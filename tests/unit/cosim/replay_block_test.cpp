// The replay block (`mechsim launch --replay`): a participant's recorded topic stands in for
// its block. Pure: no DDS, no files.
#include <gtest/gtest.h>

#include <cmath>

#include "mechsim/cosim/node_stepper.h"
#include "mechsim/cosim/replay_block.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

// A recorded ServoCommand-like table: field f at step k is k + f / 10, distinct everywhere.
RecordedTopic table(std::size_t steps, std::size_t fields) {
  RecordedTopic r;
  for (std::size_t k = 0; k <= steps; ++k) {
    r.rows.emplace_back();
    for (std::size_t f = 0; f < fields; ++f) r.rows.back().push_back(static_cast<double>(k) + static_cast<double>(f) / 10);
  }
  return r;
}

struct NcPlan {
  config::Scene scene = config::load_scene(testing::shipped_scene("nc_slide_loop.yaml"), {"time.end=1 ms"});  // 40 steps
  ScenePlan plan = ScenePlan::build(scene);
};

TEST(ReplayBlock, PublishesTheRecordedRowOfEachStepAndKeepsTheInputs) {
  NcPlan nc;
  PlannedNode& servo = nc.plan.node("servo");
  const std::size_t fields = servo.type->publishes->fields.size();
  const int inputs = servo.block->num_inputs();
  replace_with_replay(servo, table(40, fields), nc.plan.grid());
  EXPECT_EQ(servo.block->num_inputs(), inputs);  // the edges still map onto it
  EXPECT_EQ(servo.block->num_states(), 0);
  ASSERT_EQ(servo.published_outputs.size(), fields);

  // Through the node's own stepper: what it would publish at each step is the table row.
  NodeStepper stepper(servo, nc.plan.grid());
  std::vector<double> published;
  ASSERT_TRUE(stepper.can_initialise());  // Jacobi inputs only: initial values
  stepper.initialise(published);
  for (std::size_t f = 0; f < fields; ++f) EXPECT_EQ(published[f], static_cast<double>(f) / 10);
  for (std::uint64_t k = 0; k < 40; ++k) {
    for (std::size_t e = 0; e < servo.inputs.size(); ++e)
      stepper.channel(e).add(k, std::vector<double>(servo.inputs[e].type->fields.size(), 123.0));
    ASSERT_TRUE(stepper.can_step());
    stepper.step(published);
    for (std::size_t f = 0; f < fields; ++f) ASSERT_EQ(published[f], static_cast<double>(k + 1) + static_cast<double>(f) / 10);
  }
}

TEST(ReplayBlock, ARecordingShorterThanTheSceneIsRefused) {
  NcPlan nc;
  PlannedNode& servo = nc.plan.node("servo");
  try {
    replace_with_replay(servo, table(39, servo.type->publishes->fields.size()), nc.plan.grid());
    FAIL() << "accepted a recording of steps 0..39 for a scene of 40 steps";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("steps 0..39"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("needs steps 0..40"), std::string::npos) << e.what();
  }
}

TEST(ReplayBlock, TheTableIsReadByFieldName) {
  NcPlan nc;
  const transport::TopicType& type = *nc.plan.node("servo").type->publishes;
  OutputLog log;
  log.columns.push_back("t");
  log.data.push_back({0.0, 1.0});
  // The fields in reverse order: the reader must go by name, not position.
  for (auto f = type.fields.rbegin(); f != type.fields.rend(); ++f) {
    log.columns.push_back(f->name);
    const double v = static_cast<double>(type.field_index(f->name));
    log.data.push_back({v, v + 100});
  }
  const RecordedTopic r = recorded_topic_from_log(log, type, "servo.replay.bin");
  ASSERT_EQ(r.rows.size(), 2u);
  for (std::size_t f = 0; f < type.fields.size(); ++f) {
    EXPECT_EQ(r.rows[0][f], static_cast<double>(f));
    EXPECT_EQ(r.rows[1][f], static_cast<double>(f) + 100);
  }
  log.columns[1] = "not_a_field";
  EXPECT_THROW(recorded_topic_from_log(log, type, "servo.replay.bin"), std::runtime_error);
}

}  // namespace
}  // namespace mechsim::cosim
