// Small blocks shared by the solve tests.
#pragma once

#include <span>

#include "mechsim/models/block.h"

namespace mechsim::solve::test {

// x' = -a x: the reference problem with solution x0 exp(-a t).
class DecayBlock final : public models::Block {
 public:
  explicit DecayBlock(double rate) : Block("test_decay"), rate_(rate) {
    declare_state("x", "1");
    declare_output("x", "1");
  }
  void derivatives(double, std::span<const double> x, std::span<const double>,
                   std::span<double> dxdt) const override {
    dxdt[0] = -rate_ * x[0];
  }
  void calc_outputs(double, std::span<const double> x, std::span<const double>,
                    std::span<double> y) const override {
    y[0] = x[0];
  }

 private:
  double rate_;
};

}  // namespace mechsim::solve::test
