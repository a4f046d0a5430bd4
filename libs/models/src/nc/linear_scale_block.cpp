#include "mechsim/models/nc/linear_scale_block.h"

#include <cmath>
#include <stdexcept>

namespace mechsim::models::nc {

LinearScaleBlock::LinearScaleBlock(LinearScaleParams params) : Block("linear_scale"), params_(params) {
  if (!(params_.time_constant > 0)) throw std::invalid_argument("linear_scale: time_constant must be > 0");
  if (!std::isfinite(params_.offset) || !std::isfinite(params_.initial_position))
    throw std::invalid_argument("linear_scale: offset and initial_position must be finite");
  slide_position_ = declare_required_input("slide_position", "m");
  measured_position_ = declare_output("measured_position", "m");
  measurement_error_ = declare_output("measurement_error", "m", {slide_position_});
  measured_ = declare_state("measured", "m");
}

void LinearScaleBlock::initial_state(double /*t0*/, std::span<double> x) const { x[measured_] = params_.initial_position; }

void LinearScaleBlock::derivatives(double /*t*/, std::span<const double> x, std::span<const double> u,
                                   std::span<double> dxdt) const {
  dxdt[measured_] = (u[slide_position_] - x[measured_]) / params_.time_constant;
}

void LinearScaleBlock::calc_outputs(double /*t*/, std::span<const double> x, std::span<const double> u,
                                    std::span<double> y) const {
  y[measured_position_] = x[measured_] + params_.offset;
  y[measurement_error_] = y[measured_position_] - u[slide_position_];
}

}  // namespace mechsim::models::nc
