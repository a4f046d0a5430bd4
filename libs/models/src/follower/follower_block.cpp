#include "mechsim/models/follower/follower_block.h"

namespace mechsim::models::follower {

namespace {
enum Input { in_angle, in_speed, in_lift, in_lift_d1, in_lift_d2, in_pressure_angle, in_acceleration };
enum Output { out_position, out_velocity, out_acceleration, out_contact_force, out_contact,
              out_drive_torque, out_spring_force, out_load_force, out_inertia_force,
              out_drive_torque_rest, out_reflected_inertia, out_lift_off_count, out_load_power,
              out_kinetic_energy, out_spring_energy };
}  // namespace

FollowerBlock::FollowerBlock(FollowerParams params) : Block("follower"), params_(std::move(params)) {
  validate(params_);
  const int angle = declare_required_input("angle", "rad");
  const int speed = declare_required_input("speed", "rad/s");
  const int lift = declare_required_input("lift", "m");
  const int lift_d1 = declare_required_input("lift_d1", "m/rad");
  const int lift_d2 = declare_required_input("lift_d2", "m/rad^2");
  const int alpha = declare_required_input("pressure_angle", "rad");
  const int accel = declare_input("acceleration", "rad/s^2", 0.0);
  const std::vector<int> all{angle, speed, lift, lift_d1, lift_d2, alpha, accel};
  declare_output("position", "m", {lift});
  declare_output("velocity", "m/s", {speed, lift_d1});
  declare_output("acceleration", "m/s^2", {speed, lift_d1, lift_d2, accel});
  declare_output("contact_force", "N", all);
  declare_output("contact", "1", all);
  declare_output("drive_torque", "N*m", {angle, speed, lift, lift_d1, lift_d2, accel});
  declare_output("spring_force", "N", {lift});
  declare_output("load_force", "N", {angle});
  declare_output("inertia_force", "N", {speed, lift_d1, lift_d2, accel});
  declare_output("drive_torque_rest", "N*m", {angle, speed, lift, lift_d1, lift_d2});
  declare_output("reflected_inertia", "kg*m^2", {lift_d1});
  declare_output("lift_off_count", "1");
  // Energy ports (for a scene's energy_balance figure, docs/scenes.md).
  declare_output("load_power", "W", {angle, speed, lift_d1});
  declare_output("kinetic_energy", "J", {speed, lift_d1});
  declare_output("spring_energy", "J", {lift});
}

void FollowerBlock::calc_outputs(double, std::span<const double>, std::span<const double> u,
                                 std::span<double> y) const {
  const double omega = u[in_speed], omega_dot = u[in_acceleration];
  const FollowerForces f =
      kinetostatic_forces(params_, u[in_angle], u[in_lift], u[in_lift_d1], u[in_lift_d2],
                          u[in_pressure_angle], omega, omega_dot);
  y[out_position] = u[in_lift];
  y[out_velocity] = u[in_lift_d1] * omega;
  y[out_acceleration] = u[in_lift_d2] * omega * omega + u[in_lift_d1] * omega_dot;
  y[out_contact_force] = f.contact_force_n;
  y[out_contact] = f.contact_force_n >= 0.0 ? 1.0 : 0.0;
  y[out_drive_torque] = f.drive_torque_nm;
  y[out_spring_force] = f.spring_force_n;
  y[out_load_force] = f.functional_load_n;
  y[out_inertia_force] = f.inertia_force_n;
  y[out_drive_torque_rest] = f.drive_torque_rest_nm;
  y[out_reflected_inertia] = reflected_inertia(params_.mass, u[in_lift_d1]);
  y[out_lift_off_count] = 0.0;
  // The cam's power M ω splits into these: F_func v + d/dt(½ m v²) + d/dt(F0 S + ½ k S²).
  const double v = u[in_lift_d1] * omega, S = u[in_lift];
  y[out_load_power] = f.functional_load_n * v;
  y[out_kinetic_energy] = 0.5 * params_.mass * v * v;
  y[out_spring_energy] = params_.spring.preload_n * S + 0.5 * params_.spring.stiffness_n_per_m * S * S;
}

}  // namespace mechsim::models::follower
