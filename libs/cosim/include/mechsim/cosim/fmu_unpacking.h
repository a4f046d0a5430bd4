// Where a run's FMUs are unpacked (docs/fmi.md, "Unpacking"): <run folder>/fmu, one folder
// per FMU participant, shared by the processes of the run on one host (fmi/archive.h). The
// nodes unpack there; the launcher removes it when the run ends, also after a crash.
#pragma once

#include <string>

namespace mechsim::cosim {

std::string fmu_unpack_folder(const std::string& run_dir);
// This process's FMU archives unpack into fmu_unpack_folder(run_dir) from now on.
void unpack_fmus_in_run_folder(const std::string& run_dir);
// Removes fmu_unpack_folder(run_dir) with everything in it; "" on success, else why not.
std::string remove_fmu_unpack_folder(const std::string& run_dir);

}  // namespace mechsim::cosim
