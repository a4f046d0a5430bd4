// An FMU block's instance (co_simulation_block.h, model_exchange_block.h), made at once or
// at its first use as this process asks (instantiation.h): `make` instantiates and
// initializes, `after` reads what the block keeps from the initialized FMU.
#pragma once

#include <functional>
#include <memory>

#include "mechsim/fmi/instance.h"
#include "mechsim/fmi/instantiation.h"

namespace mechsim::fmi {

class LazyInstance {
 public:
  using Make = std::function<std::unique_ptr<FmuInstance>()>;
  using After = std::function<void(FmuInstance&)>;
  LazyInstance(Make make, After after) : make_(std::move(make)), after_(std::move(after)) {}
  // Made now unless this process defers instantiation (a block's constructor calls it).
  void make_unless_deferred() const {
    if (block_instantiation() == Instantiation::when_made) get();
  }
  FmuInstance& get() const {
    if (!instance_) {
      auto made = make_();
      after_(*made);
      instance_ = std::move(made);
    }
    return *instance_;
  }

 private:
  Make make_;
  After after_;
  mutable std::unique_ptr<FmuInstance> instance_;
};

}  // namespace mechsim::fmi
