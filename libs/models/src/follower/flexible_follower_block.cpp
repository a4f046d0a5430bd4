#include "mechsim/models/follower/flexible_follower_block.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace mechsim::models::follower {

namespace {
enum Input { in_angle, in_speed, in_lift, in_lift_d1, in_lift_d2, in_pressure_angle, in_acceleration };
enum Output { out_position, out_velocity, out_acceleration, out_contact_force, out_contact,
              out_drive_torque, out_spring_force, out_load_force, out_inertia_force,
              out_drive_torque_rest, out_reflected_inertia, out_lift_off_count, out_deflection,
              out_load_power, out_kinetic_energy, out_spring_energy };
enum State { x_deflection, x_velocity };
enum Event { ev_lift_off, ev_landing };

double wrapped_degrees(double theta_rad) {
  double deg = std::fmod(theta_rad * 180.0 / std::numbers::pi, 360.0);
  return deg < 0.0 ? deg + 360.0 : deg;
}
}  // namespace

double damping_for_ratio(double damping_ratio, double stiffness_n_per_m, double mass_kg) {
  return 2.0 * damping_ratio * std::sqrt(stiffness_n_per_m * mass_kg);
}

double static_position(const FlexibleFollowerParams& p, double lift_m) {
  const double kf = p.contact.stiffness_n_per_m, k = p.follower.spring.stiffness_n_per_m;
  return (kf * lift_m - p.follower.spring.preload_n) / (kf + k);
}

void validate(const FlexibleFollowerParams& p) {
  validate(p.follower);
  if (!(p.follower.mass > 0.0)) throw std::invalid_argument("flexible follower: mass must be > 0");
  if (!(p.contact.stiffness_n_per_m > 0.0 && std::isfinite(p.contact.stiffness_n_per_m)))
    throw std::invalid_argument("flexible follower: the follower stiffness k_f must be > 0");
  if (!(p.contact.contact_damping_n_s_per_m >= 0.0) || !(p.contact.frame_damping_n_s_per_m >= 0.0))
    throw std::invalid_argument("flexible follower: damping must be >= 0");
  if (!std::isfinite(p.initial_lift_m)) throw std::invalid_argument("flexible follower: initial lift must be finite");
}

FlexibleFollowerBlock::FlexibleFollowerBlock(FlexibleFollowerParams params)
    : Block("follower"), params_(std::move(params)) {
  validate(params_);
  const int angle = declare_required_input("angle", "rad");
  const int speed = declare_required_input("speed", "rad/s");
  const int lift = declare_required_input("lift", "m");
  const int lift_d1 = declare_required_input("lift_d1", "m/rad");
  declare_input("lift_d2", "m/rad^2", 0.0);       // accepted from CamState, not needed
  const int alpha = declare_required_input("pressure_angle", "rad");
  declare_input("acceleration", "rad/s^2", 0.0);  // accepted from CamState, not needed
  const std::vector<int> force{speed, lift, lift_d1};  // F through S and Ṡ = S' ω
  std::vector<int> accel = force;
  accel.push_back(angle);  // F_func(θ)
  std::vector<int> normal = force;
  normal.push_back(alpha);
  declare_output("position", "m", {lift});  // y = S − δ
  declare_output("velocity", "m/s");
  declare_output("acceleration", "m/s^2", accel);
  declare_output("contact_force", "N", normal);
  declare_output("contact", "1");
  declare_output("drive_torque", "N*m", force);
  declare_output("spring_force", "N", {lift});
  declare_output("load_force", "N", {angle});
  declare_output("inertia_force", "N", accel);
  declare_output("drive_torque_rest", "N*m", force);
  declare_output("reflected_inertia", "kg*m^2");
  declare_output("lift_off_count", "1");
  declare_output("deflection", "m");  // the state itself
  declare_output("load_power", "W", {angle});
  declare_output("kinetic_energy", "J");
  declare_output("spring_energy", "J", {lift});
  declare_state("deflection", "m");
  declare_state("velocity", "m/s");
}

void FlexibleFollowerBlock::initial_state(double, std::span<double> x) const {
  mode_ = Mode{};
  log_.clear();
  x[x_deflection] = params_.initial_lift_m - static_position(params_, params_.initial_lift_m);
  x[x_velocity] = 0.0;
}

double FlexibleFollowerBlock::contact_force(std::span<const double> x, std::span<const double> u) const {
  if (!mode_.in_contact) return 0.0;
  const FollowerContact& c = params_.contact;
  const double deflection_rate = u[in_lift_d1] * u[in_speed] - x[x_velocity];
  const double f = c.stiffness_n_per_m * x[x_deflection] + c.contact_damping_n_s_per_m * deflection_rate;
  // Within the root-finding tolerance of a lift-off F may be a hair below zero: the
  // contact cannot pull.
  return std::max(0.0, f);
}

double FlexibleFollowerBlock::acceleration(std::span<const double> x, std::span<const double> u) const {
  const FollowerParams& f = params_.follower;
  const double spring = f.spring.preload_n + f.spring.stiffness_n_per_m * (u[in_lift] - x[x_deflection]);
  return (contact_force(x, u) - functional_load(f.loads, u[in_angle]) - spring -
          params_.contact.frame_damping_n_s_per_m * x[x_velocity]) /
         f.mass;
}

void FlexibleFollowerBlock::derivatives(double, std::span<const double> x, std::span<const double> u,
                                        std::span<double> dxdt) const {
  dxdt[x_deflection] = u[in_lift_d1] * u[in_speed] - x[x_velocity];  // Ṡ − ẏ
  dxdt[x_velocity] = acceleration(x, u);
}

void FlexibleFollowerBlock::calc_outputs(double, std::span<const double> x, std::span<const double> u,
                                         std::span<double> y) const {
  const FollowerParams& f = params_.follower;
  const double force = contact_force(x, u);
  const double a = acceleration(x, u);
  y[out_position] = u[in_lift] - x[x_deflection];
  y[out_velocity] = x[x_velocity];
  y[out_acceleration] = a;
  y[out_contact_force] = force / std::cos(u[in_pressure_angle]);
  y[out_contact] = mode_.in_contact ? 1.0 : 0.0;
  y[out_drive_torque] = force * u[in_lift_d1];
  y[out_spring_force] = f.spring.preload_n + f.spring.stiffness_n_per_m * y[out_position];
  y[out_load_force] = functional_load(f.loads, u[in_angle]);
  y[out_inertia_force] = f.mass * a;
  y[out_drive_torque_rest] = y[out_drive_torque];
  y[out_reflected_inertia] = 0.0;
  y[out_lift_off_count] = static_cast<double>(mode_.lift_offs);
  y[out_deflection] = x[x_deflection];
  // Energy ports as the rigid follower's; the spring energy includes the compressed contact
  // stiffness. The dampers' losses (c_f, c) are not among them.
  const double yy = y[out_position], v = x[x_velocity];
  y[out_load_power] = y[out_load_force] * v;
  y[out_kinetic_energy] = 0.5 * f.mass * v * v;
  y[out_spring_energy] = f.spring.preload_n * yy + 0.5 * f.spring.stiffness_n_per_m * yy * yy +
                         (x[x_deflection] > 0 ? 0.5 * params_.contact.stiffness_n_per_m * x[x_deflection] * x[x_deflection] : 0.0);
}

Crossing FlexibleFollowerBlock::event_direction(int index) const {
  return index == ev_lift_off ? Crossing::falling : Crossing::rising;
}

double FlexibleFollowerBlock::contact_function(std::span<const double> x, std::span<const double> u) const {
  const FollowerContact& c = params_.contact;
  const double spring = c.stiffness_n_per_m * x[x_deflection];  // k_f (S − y)
  const double force = spring + c.contact_damping_n_s_per_m * (u[in_lift_d1] * u[in_speed] - x[x_velocity]);
  return std::min(spring, force);
}

void FlexibleFollowerBlock::event_functions(double, std::span<const double> x, std::span<const double> u,
                                            std::span<double> g) const {
  // The function of the other mode is held at a constant of the sign it has when that mode
  // is entered, so it cannot cross; the solver restarts at every mode switch anyway.
  const double h = contact_function(x, u);
  g[ev_lift_off] = mode_.in_contact ? h : 1.0;
  g[ev_landing] = mode_.in_contact ? -1.0 : h;
}

bool FlexibleFollowerBlock::handle_events(double t, std::span<double> x, std::span<const double> u,
                                          std::span<const int> crossed) {
  if (mode_.in_contact && crossed[ev_lift_off] != 0) {
    mode_.in_contact = false;
    ++mode_.lift_offs;
    mode_.lift_off_time = t;
    log_.push_back({"lift_off", t, {{"angle_deg", wrapped_degrees(u[in_angle])}}});
    return true;
  }
  if (!mode_.in_contact && crossed[ev_landing] != 0) {
    mode_.in_contact = true;
    const double impact_velocity = u[in_lift_d1] * u[in_speed] - x[x_velocity];  // closing speed Ṡ − ẏ
    log_.push_back({"landing",
                    t,
                    {{"angle_deg", wrapped_degrees(u[in_angle])},
                     {"flight_duration_s", t - mode_.lift_off_time},
                     {"impact_velocity_m_per_s", impact_velocity}}});
    return true;
  }
  return false;
}

std::vector<BlockEvent> FlexibleFollowerBlock::take_event_log() {
  std::vector<BlockEvent> taken;
  taken.swap(log_);
  return taken;
}

std::vector<double> FlexibleFollowerBlock::save_discrete_state() const {
  return {mode_.in_contact ? 1.0 : 0.0, static_cast<double>(mode_.lift_offs), mode_.lift_off_time};
}

void FlexibleFollowerBlock::restore_discrete_state(std::span<const double> saved) {
  if (saved.size() != 3) throw std::invalid_argument("flexible follower: saved discrete state has the wrong size");
  mode_.in_contact = saved[0] != 0.0;
  mode_.lift_offs = static_cast<long>(saved[1]);
  mode_.lift_off_time = saved[2];
}

}  // namespace mechsim::models::follower
