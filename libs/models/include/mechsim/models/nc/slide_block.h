// Time-domain block of what lies beyond the coupling (spec nc_slide.md §2–§3): spindle,
// nut and slide. The coupling C_kopp, d_k belongs to the connection; this block receives it
// either as a torque at the spindle's drive end (CouplingInput::torque) or as the motor's
// angle and speed with the spring-damper evaluated here (CouplingInput::compliant).
//
// Variants, all written as  M q'' + D q' + K q = b T − n T_guide(n·q'):
//   rigid     one inertia I_a + I_b                                  q = [φ]
//   two_mass  I_a —C_sp, d_sp— I_b  (I_a = I_kopp + I_sp/2 at the drive end,
//             I_b = I_slide + I_sp/2 at the slide; as in §3)         q = [φ_a, φ_b]
//   modal     the spindle as a continuous free–free shaft (length l) with I_kopp lumped at
//             the drive end and I_slide at the nut, Rayleigh–Ritz with N cosines cos(nπs/l),
//             n = 0..N−1 (N = 1 is the rigid variant); q = Ritz amplitudes. Damping is
//             stiffness-proportional, D = (d_sp/C_sp) K: exactly the two-mass variant's law
//             for the first mode; higher modes get more (ζ_n = d_sp ω_n / 2C_sp).
// b is the shape at the drive end, n the shape at the nut (slide).
//
// Guide friction, reduced to the spindle with r = lead/2π (v = r ω_slide):
//   T_guide = r (c_v v + F_c tanh(v / v_s))
// The Coulomb part is regularised with tanh over the velocity scale v_s (default 0.1 mm/s):
// below v_s it acts as a steep viscous law, so the slide creeps instead of sticking. Keep
// F_c = 0 (default) unless the Coulomb extreme is wanted; it makes the block stiff.
//
// Ports                       unit    feedthrough
//   in  drive_torque          N m     default 0                (torque coupling)
//   in  motor_angle           rad     default 0                (compliant coupling)
//   in  motor_speed           rad/s   default 0                (compliant coupling)
//   out spindle_angle         rad     —   drive end
//   out spindle_speed         rad/s   —
//   out slide_position        m       —   φ_slide · lead/2π
//   out slide_speed           m/s     —
//   out coupling_torque       N m     drive_torque | motor_angle, motor_speed
// States start at zero (at rest).
#pragma once

#include <Eigen/Dense>
#include <optional>

#include "mechsim/models/block.h"
#include "mechsim/models/nc/coupling.h"
#include "mechsim/models/nc/slide_drive_data.h"

namespace mechsim::models::nc {

enum class SlideVariant { rigid, two_mass, modal };

struct SlideBlockOptions {
  SlideDriveData drive;                        // default: I_slide = m s²/4π² (5 mm lead)
  SlideVariant variant = SlideVariant::two_mass;
  int modal_shapes = 4;                        // N, modal variant only (N >= 1)
  // Modal variant: the nut along the spindle from its drive end [m]. Empty: the far end,
  // where the two-mass variant puts the slide.
  std::optional<double> nut_position;
  double spindle_damping = 0.08;               // d_sp [N m s/rad]
  double guide_viscous_friction = 2000.0;      // c_v [N s/m]
  double guide_coulomb_friction = 0.0;         // F_c [N]
  double coulomb_velocity_scale = 1e-4;        // v_s [m/s]
  CouplingInput coupling_input = CouplingInput::torque;
  CouplingParams coupling;                     // used with CouplingInput::compliant
};

class SlideBlock final : public Block {
 public:
  explicit SlideBlock(SlideBlockOptions options = {});

  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;

  const SlideBlockOptions& options() const { return options_; }
  // The variant's matrices (for analyses and tests): q has num_coordinates() entries and
  // the state is [q, q'].
  int num_coordinates() const { return static_cast<int>(drive_shape_.size()); }
  const Eigen::MatrixXd& mass_matrix() const { return mass_; }
  const Eigen::MatrixXd& stiffness_matrix() const { return stiffness_; }
  const Eigen::MatrixXd& damping_matrix() const { return damping_; }
  const Eigen::VectorXd& drive_end_shape() const { return drive_shape_; }
  const Eigen::VectorXd& nut_shape() const { return nut_shape_; }
  // Guide friction torque on the spindle for a slide speed [m/s] -> [N m].
  double guide_friction_torque(double slide_speed) const;

 private:
  double drive_torque(std::span<const double> x, std::span<const double> u) const;
  double shape_dot(const Eigen::VectorXd& shape, std::span<const double> values) const;

  SlideBlockOptions options_;
  Eigen::MatrixXd mass_, inverse_mass_, stiffness_, damping_;
  Eigen::VectorXd drive_shape_, nut_shape_;
  double metres_per_radian_;
  struct Inputs {
    int drive_torque = -1, motor_angle = -1, motor_speed = -1;
  } in_;
  struct Outputs {
    int spindle_angle, spindle_speed, slide_position, slide_speed, coupling_torque;
  } out_;
};

}  // namespace mechsim::models::nc
