#include "mechsim/models/block.h"

#include <algorithm>
#include <stdexcept>

namespace mechsim::models {

namespace {
template <typename Ports>
int find_port(const Ports& ports, std::string_view name) {
  for (std::size_t i = 0; i < ports.size(); ++i)
    if (ports[i].name == name) return static_cast<int>(i);
  return -1;
}
}  // namespace

int Block::input_index(std::string_view name) const { return find_port(inputs_, name); }
int Block::output_index(std::string_view name) const { return find_port(outputs_, name); }
int Block::state_index(std::string_view name) const {
  auto it = std::find(state_names_.begin(), state_names_.end(), name);
  return it == state_names_.end() ? -1 : static_cast<int>(it - state_names_.begin());
}

std::vector<double> Block::default_inputs() const {
  std::vector<double> u;
  u.reserve(inputs_.size());
  for (const auto& p : inputs_) u.push_back(p.default_value);
  return u;
}

void Block::initial_state(double, std::span<double> x) const { std::fill(x.begin(), x.end(), 0.0); }

void Block::derivatives(double, std::span<const double>, std::span<const double>,
                        std::span<double> dxdt) const {
  std::fill(dxdt.begin(), dxdt.end(), 0.0);
}

int Block::declare_input(std::string name, std::string unit, double default_value) {
  if (input_index(name) >= 0) throw std::logic_error(type_name_ + ": duplicate input " + name);
  inputs_.push_back({std::move(name), std::move(unit), default_value, false});
  return num_inputs() - 1;
}

int Block::declare_required_input(std::string name, std::string unit) {
  int i = declare_input(std::move(name), std::move(unit), 0.0);
  inputs_[i].required = true;
  return i;
}

int Block::declare_output(std::string name, std::string unit, std::vector<int> feedthrough) {
  if (output_index(name) >= 0) throw std::logic_error(type_name_ + ": duplicate output " + name);
  for (int i : feedthrough)
    if (i < 0 || i >= num_inputs())
      throw std::logic_error(type_name_ + ": output " + name + " depends on an undeclared input");
  outputs_.push_back({std::move(name), std::move(unit), std::move(feedthrough)});
  return num_outputs() - 1;
}

int Block::declare_state(std::string name, std::string unit) {
  if (state_index(name) >= 0) throw std::logic_error(type_name_ + ": duplicate state " + name);
  state_names_.push_back(std::move(name));
  state_units_.push_back(std::move(unit));
  return num_states() - 1;
}

}  // namespace mechsim::models
