// What the FMU blocks share: the exchanged inputs/outputs of a description, the parameter
// check against it, and typed set/get of a variable as a double.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "mechsim/fmi/instance.h"

namespace mechsim::fmi {

struct ExchangedVariables {
  std::vector<const Variable*> inputs, outputs;  // Real/Integer/Boolean, causality input/output
};
ExchangedVariables exchanged_variables(const ModelDescription& md);

// The inputs (indices into `inputs`) that output `output` depends on directly, as the
// description's <ModelStructure> dependencies say; every input where it does not say.
std::vector<int> feedthrough(const ModelDescription& md, const Variable& output,
                             const std::vector<const Variable*>& inputs);

// The port unit of a variable ("1" when it has none) and an input's default (its start).
std::string port_unit(const Variable& v);
double start_value(const Variable& v, const FmuLabel& label);

// Refuses a parameter name the FMU lacks, or that is not a settable parameter.
void check_parameters(const ModelDescription& md, const std::map<std::string, double>& parameters,
                      const FmuLabel& label);

// Instantiates `kind`, sets the parameters in initialization mode and exits it at t0.
std::unique_ptr<FmuInstance> initialize(const FmuArchive& archive, InterfaceKind kind,
                                        const std::map<std::string, double>& parameters, double t0, double t_stop);

void set_value(FmuInstance& fmu, const Variable& v, double value);
double get_value(FmuInstance& fmu, const Variable& v);  // outputs: NaN/inf refused

}  // namespace mechsim::fmi
