// The flexible follower for time simulation (spec cam.md §5, model (b)): the follower mass m
// sits behind a follower stiffness k_f (and damper c_f) that touches the cam, with the
// return spring, the functional loads and an optional damper c to the frame on the mass:
//
//   m ÿ = F − F_func(θ) − (F0 + k y) − c ẏ,   F = k_f (S − y) + c_f (Ṡ − ẏ) ≥ 0
//
// F is the contact force along the follower axis (the N cos α of §3; the normal force is
// F/cos α). The contact is unilateral: it holds while the follower stiffness is compressed
// (S − y > 0) and F > 0, i.e. while h = min(k_f (S − y), F) > 0. In contact vs flying is a
// mode switched by zero crossings of h that the integrator locates (SUNDIALS root
// finding), never by the step size:
//   lift-off: h crosses zero downward in contact (there h = F: the contact force vanishes)
//   landing:  h crosses zero upward while flying (from a real flight h = k_f (S − y): the
//             gap closes; after a lift-off with S − y > 0, which the damper c_f allows,
//             h = F: the compressed contact pushes again)
// With c_f = 0 both reduce to S − y crossing zero.
// Each switch is reported through take_event_log() ("lift_off", "landing").
//
// The states are the deflection δ = S − y and ẏ, not y: the contact force k_f δ is then a
// state the solver's error control sees, however stiff the follower. With y as the state
// the error allowed on y (rtol·|y|, ~25 nm at rtol 1e-6 on a 25 mm lift) exceeds the whole
// deflection of a stiff contact (~50 nm at 1e4× the report's k_f), and the force becomes
// noise. δ̇ = Ṡ − ẏ with Ṡ = S' ω from the cam.
//
// Unlike the rigid follower this one reflects no inertia onto the shaft: its drive torque
// F S' follows from its own state, so a dynamic cam shaft sees no algebraic loop.
#pragma once

#include <vector>

#include "mechsim/models/block.h"
#include "mechsim/models/follower/kinetostatics.h"

namespace mechsim::models::follower {

struct FollowerContact {
  double stiffness_n_per_m = 0.0;          // k_f > 0, between the cam contact and the mass
  double contact_damping_n_s_per_m = 0.0;  // c_f ≥ 0, on the deflection rate Ṡ − ẏ
  double frame_damping_n_s_per_m = 0.0;    // c ≥ 0, mass to frame (the report's model)
};

struct FlexibleFollowerParams {
  FollowerParams follower;  // mass, return spring, functional loads
  FollowerContact contact;
  // Lift S at t0: the follower starts at rest in static equilibrium on the cam there
  // (functional loads left out: scenes start in a dwell without load).
  double initial_lift_m = 0.0;
};

// Damping coefficient for a damping ratio ζ on stiffness k and mass m: c = 2ζ√(k m).
double damping_for_ratio(double damping_ratio, double stiffness_n_per_m, double mass_kg);

// Static equilibrium in contact at lift S: k_f (S − y) = F0 + k y.
double static_position(const FlexibleFollowerParams& params, double lift_m);

// Throws std::invalid_argument for invalid follower data (kinetostatics.h validate), a
// non-positive mass or contact stiffness, or negative damping.
void validate(const FlexibleFollowerParams& params);

// States: deflection δ = S − y (m), velocity ẏ (m/s). Inputs as the rigid FollowerBlock (angle,
// speed, lift, lift_d1, pressure_angle required; lift_d2 and acceleration accepted and
// unused). Outputs: position, velocity, acceleration (ÿ), contact_force (F/cos α, 0 while
// flying), contact (1 in contact), drive_torque (F S'), spring_force, load_force,
// inertia_force (m ÿ), drive_torque_rest (= drive_torque: nothing depends on ω̇),
// reflected_inertia (0), lift_off_count, deflection (S − y; < 0 is the flight gap).
class FlexibleFollowerBlock : public Block {
 public:
  explicit FlexibleFollowerBlock(FlexibleFollowerParams params);

  // Also resets the mode to "in contact" and the event counters, so that the block can be
  // run again from the start.
  void initial_state(double t0, std::span<double> x) const override;
  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;

  int num_event_functions() const override { return 2; }
  Crossing event_direction(int index) const override;
  void event_functions(double t, std::span<const double> x, std::span<const double> u,
                       std::span<double> g) const override;
  bool handle_events(double t, std::span<double> x, std::span<const double> u,
                     std::span<const int> crossed) override;
  std::vector<BlockEvent> take_event_log() override;
  // The load intervals' ends, on the side functional_load() takes as after them.
  std::vector<double> angle_events() const override { return load_boundaries(params_.follower.loads); }
  bool angle_event_reached(double theta, double event) const override { return angle_at_or_past(theta, event); }

  std::vector<double> save_discrete_state() const override;
  void restore_discrete_state(std::span<const double> saved) override;

  const FlexibleFollowerParams& params() const { return params_; }
  bool in_contact() const { return mode_.in_contact; }
  long lift_off_count() const { return mode_.lift_offs; }

 private:
  struct Mode {
    bool in_contact = true;
    long lift_offs = 0;
    double lift_off_time = 0.0;  // of the current (or last) flight
  };
  // Axial contact force F of the current mode (0 while flying).
  double contact_force(std::span<const double> x, std::span<const double> u) const;
  // > 0 exactly where the contact holds: min(k_f (S − y), k_f (S − y) + c_f (Ṡ − ẏ)).
  double contact_function(std::span<const double> x, std::span<const double> u) const;
  double acceleration(std::span<const double> x, std::span<const double> u) const;

  FlexibleFollowerParams params_;
  // Mutable: initial_state() (const in Block) starts a fresh run.
  mutable Mode mode_;
  mutable std::vector<BlockEvent> log_;
};

}  // namespace mechsim::models::follower
