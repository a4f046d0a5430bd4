// Node type `cvt`: the HCVT push-belt CVT with its drive motor, shaft inertias and ratio
// actuator (models/cvt/cvt_block.h), publishing <name>/state (CvtState). Reads the load of a
// shaft it drives: a cam shaft with a gear drive hands over its torque and inertia reflected
// through the gear (docs/press-line.md). The belt keys are those of `mechsim cvt-map`
// (parse_cvt_config, docs/cvt.md); the time-run keys are parsed here.
#include <memory>
#include <string>

#include "mechsim/catalog/catalog.h"
#include "mechsim/catalog/cvt_params.h"
#include "mechsim/models/cvt/cvt_block.h"

namespace mechsim::cosim {

namespace cvt = models::cvt;
using config::ConfigNode;
namespace dim = config::dim;

const std::vector<std::string>& cvt_time_run_keys() {
  static const std::vector<std::string> keys{"drive",         "input_inertia",  "output_inertia", "initial_speed",
                                             "ratio_setting", "ratio_actuator", "shape_table",    "belt_map",
                                             "clamping_actuator"};
  return keys;
}

cvt::CvtBlockParams parse_cvt_block_params(const ConfigNode& p) {
  const CvtConfig c = parse_cvt_config(p, cvt_time_run_keys());
  cvt::CvtBlockParams b;
  b.cvt = c.params;
  b.clamp = c.clamp;
  b.v_K = c.safety_factor;
  b.F_K = c.clamping_force;
  b.level = c.level;
  // The drive motor: a torque-speed line on the input (intermediate-body) shaft.
  const ConfigNode drive = p.child("drive");
  if (!drive.is_map()) drive.fail("expected a map {type: motor_line, stall_torque, no_load_speed}");
  drive.allow_only({"type", "stall_torque", "no_load_speed"});
  drive.choice_or("type", {"motor_line"}, "motor_line");
  b.stall_torque = drive.positive_quantity("stall_torque", dim::torque);
  b.no_load_speed = drive.positive_quantity("no_load_speed", dim::angular_velocity);
  b.J_C = p.positive_quantity("input_inertia", dim::inertia);
  b.J_D = p.non_negative_quantity_or("output_inertia", dim::inertia, 0.0);
  b.omega0 = p.non_negative_quantity_or("initial_speed", dim::angular_velocity, 0.0);
  if (b.omega0 > b.no_load_speed) p.child("initial_speed").fail("expected an initial speed at most the motor's no-load speed");
  // The shape table: the belt shape is searched at these points at start-up and interpolated.
  if (auto t = p.optional_child("shape_table")) {
    t->allow_only({"from", "to", "points"});
    b.s_table_min = t->positive_quantity_or("from", dim::length, b.s_table_min);
    b.s_table_max = t->positive_quantity_or("to", dim::length, b.s_table_max);
    b.s_table_points = static_cast<int>(t->integer_or("points", b.s_table_points));
    if (!(b.s_table_max > b.s_table_min)) t->fail("expected from < to");
    if (b.s_table_points < 2 || b.s_table_points > 10001) t->child("points").fail("expected 2 to 10001 points");
  }
  // The belt map: tabulated at start-up over s x T_C x speed (default), or the model at every
  // evaluation (`direct`: exact, ~0.7 ms per L1 evaluation; needed for clamping: {mode: force}).
  if (auto m = p.optional_child("belt_map")) {
    if (m->is_map()) {
      m->allow_only({"evaluation", "s_points", "torque_points", "speed_points"});
      b.belt_table = m->choice_or("evaluation", {"table", "direct"}, "table") == "table";
      b.table_s_points = static_cast<int>(m->integer_or("s_points", b.table_s_points));
      b.table_torque_points = static_cast<int>(m->integer_or("torque_points", b.table_torque_points));
      b.table_speed_points = static_cast<int>(m->integer_or("speed_points", b.table_speed_points));
      for (const char* k : {"s_points", "torque_points", "speed_points"})
        if (m->has(k) && (m->integer_or(k, 0) < 2 || m->integer_or(k, 0) > 201)) m->child(k).fail("expected 2 to 201 points");
    } else {
      b.belt_table = m->as_choice({"table", "direct"}) == "table";
    }
  } else {
    b.belt_table = b.clamp == cvt::ClampMode::safety_factor;
  }
  if (b.belt_table && b.clamp != cvt::ClampMode::safety_factor)
    p.child("belt_map").fail("expected belt_map: direct with clamping: {mode: force} (the table is built at the safety factor)");
  // `clamping_actuator: {time_constant, initial_force}`: the clamping force lags its setpoint.
  if (auto a = p.optional_child("clamping_actuator")) {
    a->allow_only({"time_constant", "initial_force"});
    if (!b.belt_table) a->fail("expected no clamping actuator lag with belt_map: direct (it runs on the tabulated map)");
    b.clamp_time_constant = a->positive_quantity("time_constant", dim::time);
    b.F_K0 = a->non_negative_quantity_or("initial_force", dim::force, -1.0);
  }
  b.s0 = p.positive_quantity_or("ratio_setting", dim::length, b.s0);
  if (!(b.s0 >= b.s_table_min && b.s0 <= b.s_table_max))
    p.child("ratio_setting").fail("expected a ratio setting s inside the shape table (" +
                                  std::to_string(b.s_table_min * 1e3) + " .. " + std::to_string(b.s_table_max * 1e3) +
                                  " mm)");
  if (auto a = p.optional_child("ratio_actuator")) {
    a->allow_only({"time_constant", "schedule"});
    b.ratio_time_constant = a->positive_quantity_or("time_constant", dim::time, b.ratio_time_constant);
    if (auto sch = a->optional_child("schedule")) {
      if (!sch->is_sequence() || sch->size() == 0)
        sch->fail("expected a list of setpoints {t, s}, e.g. [{t: 0 s, s: 30 mm}, {t: 1 s, s: 30 mm}, {t: 1 s, s: 20 mm}]");
      for (std::size_t k = 0; k < sch->size(); ++k) {
        ConfigNode pt = sch->at(k);
        pt.allow_only({"t", "s"});
        const double t = pt.quantity("t", dim::time), s = pt.positive_quantity("s", dim::length);
        if (!b.ratio_schedule.empty() && t < b.ratio_schedule.back().first)
          pt.child("t").fail("expected times in non-decreasing order");
        if (!(s >= b.s_table_min && s <= b.s_table_max)) pt.child("s").fail("expected s inside the shape table");
        b.ratio_schedule.emplace_back(t, s);
      }
    }
  }
  return b;
}

namespace {

std::unique_ptr<models::Block> make_cvt(const ConfigNode& p, const ConfigNode*) {
  cvt::CvtBlockParams b = parse_cvt_block_params(p);
  try {
    return std::make_unique<cvt::CvtBlock>(std::move(b));
  } catch (const cvt::CvtInputError& e) {
    p.fail(std::string("expected parameters the CVT model accepts: ") + e.what());
  }
}

}  // namespace

NodeType cvt_node_type() {
  return {"cvt",
          "push-belt CVT (HCVT) with its drive motor line, shaft inertias and ratio actuator; drives a cam shaft "
          "through a gear; publishes CvtState",
          transport::find_topic_type("CvtState"),
          "state",
          make_cvt,
          // A cam shaft with a gear drive: its torque without the inertia part and its
          // inertia, both reflected onto the disc shaft (no algebraic loop across the gear).
          {{transport::find_topic_type("CamState"),
            {{"drive_load_torque", "load_torque"}, {"drive_load_inertia", "load_inertia"}}}}};
}

}  // namespace mechsim::cosim
