// Node type `linear_scale`: a direct measuring system on the slide, publishing
// <name>/reading (ScaleReading). Reads the slide's position from SlideState. The worked
// example of docs/new-participant.md: its params, its block and what it reads, in one file.
#include "mechsim/catalog/catalog.h"
#include "mechsim/models/nc/linear_scale_block.h"

namespace mechsim::cosim {

namespace {
std::unique_ptr<models::Block> make_linear_scale(const config::ConfigNode& p, const config::ConfigNode* coupling) {
  if (coupling) coupling->fail("expected no coupling element: a linear_scale only measures, it is no side of a mechanical cut");
  p.allow_only({"time_constant", "offset", "initial_position"});
  models::nc::LinearScaleParams params;
  params.time_constant = p.positive_quantity_or("time_constant", config::dim::time, params.time_constant);
  params.offset = p.quantity_or("offset", config::dim::length, params.offset);
  params.initial_position = p.quantity_or("initial_position", config::dim::length, params.initial_position);
  return std::make_unique<models::nc::LinearScaleBlock>(params);
}
}  // namespace

NodeType linear_scale_node_type() {
  return {"linear_scale",
          "direct measuring system on the slide (first-order lag of the slide position); publishes ScaleReading",
          transport::find_topic_type("ScaleReading"),
          "reading",
          make_linear_scale,
          {{transport::find_topic_type("SlideState"), {{"slide_position", "slide_position"}}}}};
}

}  // namespace mechsim::cosim
