#include "mechsim/models/nc/slide_block.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "mechsim/models/nc/torsion_shaft.h"

namespace mechsim::models::nc {

namespace {
constexpr int max_coordinates = 64;  // bounds the stack buffer in derivatives()
}

SlideBlock::SlideBlock(SlideBlockOptions options)
    : Block("slide"), options_(std::move(options)), metres_per_radian_(options_.drive.metres_per_radian()) {
  const SlideDriveData& d = options_.drive;
  if (options_.spindle_damping < 0 || options_.guide_viscous_friction < 0 ||
      options_.guide_coulomb_friction < 0 || !(options_.coulomb_velocity_scale > 0))
    throw std::invalid_argument("slide: damping and friction must be >= 0, Coulomb velocity scale > 0");
  const double i_a = d.coupling_inertia + d.spindle_inertia() / 2;
  const double i_b = d.slide_inertia() + d.spindle_inertia() / 2;
  const double c_sp = d.spindle_stiffness();

  std::vector<std::string> angle_names, speed_names;
  switch (options_.variant) {
    case SlideVariant::rigid:
      mass_ = Eigen::MatrixXd::Constant(1, 1, i_a + i_b);
      stiffness_ = damping_ = Eigen::MatrixXd::Zero(1, 1);
      drive_shape_ = nut_shape_ = Eigen::VectorXd::Ones(1);
      angle_names = {"angle"};
      speed_names = {"speed"};
      break;
    case SlideVariant::two_mass: {
      Eigen::Matrix2d spring;
      spring << 1, -1, -1, 1;
      mass_ = Eigen::Vector2d(i_a, i_b).asDiagonal();
      stiffness_ = c_sp * spring;
      damping_ = options_.spindle_damping * spring;
      drive_shape_ = Eigen::Vector2d(1, 0);
      nut_shape_ = Eigen::Vector2d(0, 1);
      angle_names = {"drive_end_angle", "slide_end_angle"};
      speed_names = {"drive_end_speed", "slide_end_speed"};
      break;
    }
    case SlideVariant::modal: {
      const int n = options_.modal_shapes;
      if (n < 1 || n > max_coordinates)
        throw std::invalid_argument("slide: modal_shapes must be in 1..64");
      const double nut = options_.nut_position.value_or(d.spindle_length);
      if (nut < 0 || nut > d.spindle_length)
        throw std::invalid_argument("slide: nut_position must lie on the spindle");
      const UniformShaft spindle{d.spindle_length, d.shear_modulus * d.polar_moment(),
                                 d.density * d.polar_moment()};
      const RitzMatrices ritz =
          cosine_ritz_matrices(spindle, {{0.0, d.coupling_inertia}, {nut, d.slide_inertia()}}, n);
      mass_ = ritz.mass;
      stiffness_ = ritz.stiffness;
      damping_ = (options_.spindle_damping / c_sp) * ritz.stiffness;
      drive_shape_.resize(n);
      nut_shape_.resize(n);
      for (int k = 0; k < n; ++k) {
        drive_shape_(k) = cosine_shape(k, 0.0, d.spindle_length);
        nut_shape_(k) = cosine_shape(k, nut, d.spindle_length);
        angle_names.push_back("ritz_angle_" + std::to_string(k));
        speed_names.push_back("ritz_speed_" + std::to_string(k));
      }
      break;
    }
  }
  inverse_mass_ = mass_.inverse();

  std::vector<int> coupling_feedthrough;
  if (options_.coupling_input == CouplingInput::torque) {
    in_.drive_torque = declare_input("drive_torque", "N m", 0.0);
    coupling_feedthrough = {in_.drive_torque};
  } else {
    in_.motor_angle = declare_input("motor_angle", "rad", 0.0);
    in_.motor_speed = declare_input("motor_speed", "rad/s", 0.0);
    coupling_feedthrough = {in_.motor_angle, in_.motor_speed};
  }
  out_.spindle_angle = declare_output("spindle_angle", "rad");
  out_.spindle_speed = declare_output("spindle_speed", "rad/s");
  out_.slide_position = declare_output("slide_position", "m");
  out_.slide_speed = declare_output("slide_speed", "m/s");
  out_.coupling_torque = declare_output("coupling_torque", "N m", coupling_feedthrough);
  for (const auto& name : angle_names) declare_state(name, "rad");
  for (const auto& name : speed_names) declare_state(name, "rad/s");
}

double SlideBlock::guide_friction_torque(double slide_speed) const {
  const double force = options_.guide_viscous_friction * slide_speed +
                       options_.guide_coulomb_friction * std::tanh(slide_speed / options_.coulomb_velocity_scale);
  return metres_per_radian_ * force;
}

double SlideBlock::shape_dot(const Eigen::VectorXd& shape, std::span<const double> values) const {
  double sum = 0;
  for (int k = 0; k < shape.size(); ++k) sum += shape(k) * values[k];
  return sum;
}

double SlideBlock::drive_torque(std::span<const double> x, std::span<const double> u) const {
  if (options_.coupling_input == CouplingInput::torque) return u[in_.drive_torque];
  const int n = num_coordinates();
  return coupling_torque(options_.coupling, u[in_.motor_angle], u[in_.motor_speed],
                         shape_dot(drive_shape_, x.first(n)), shape_dot(drive_shape_, x.subspan(n, n)));
}

void SlideBlock::derivatives(double, std::span<const double> x, std::span<const double> u,
                             std::span<double> dxdt) const {
  const int n = num_coordinates();
  const auto q = x.first(n), q_dot = x.subspan(n, n);
  const double torque = drive_torque(x, u);
  const double friction = guide_friction_torque(metres_per_radian_ * shape_dot(nut_shape_, q_dot));
  // Small n (<= a few tens): plain loops, no allocation in the right-hand side.
  for (int i = 0; i < n; ++i) {
    double force = drive_shape_(i) * torque - nut_shape_(i) * friction;
    for (int j = 0; j < n; ++j) force -= stiffness_(i, j) * q[j] + damping_(i, j) * q_dot[j];
    dxdt[n + i] = force;  // generalised force, multiplied by M⁻¹ below
    dxdt[i] = q_dot[i];
  }
  double acceleration[max_coordinates];
  for (int i = 0; i < n; ++i) {
    acceleration[i] = 0;
    for (int j = 0; j < n; ++j) acceleration[i] += inverse_mass_(i, j) * dxdt[n + j];
  }
  for (int i = 0; i < n; ++i) dxdt[n + i] = acceleration[i];
}

void SlideBlock::calc_outputs(double, std::span<const double> x, std::span<const double> u,
                              std::span<double> y) const {
  const int n = num_coordinates();
  const auto q = x.first(n), q_dot = x.subspan(n, n);
  y[out_.spindle_angle] = shape_dot(drive_shape_, q);
  y[out_.spindle_speed] = shape_dot(drive_shape_, q_dot);
  y[out_.slide_position] = metres_per_radian_ * shape_dot(nut_shape_, q);
  y[out_.slide_speed] = metres_per_radian_ * shape_dot(nut_shape_, q_dot);
  y[out_.coupling_torque] = drive_torque(x, u);
}

}  // namespace mechsim::models::nc
