#include "mechsim/cosim/fmu_unpacking.h"

#include <filesystem>
#include <system_error>

#include "mechsim/fmi/archive.h"

namespace mechsim::cosim {

std::string fmu_unpack_folder(const std::string& run_dir) { return run_dir + "/fmu"; }

void unpack_fmus_in_run_folder(const std::string& run_dir) { fmi::set_unpack_root(fmu_unpack_folder(run_dir)); }

std::string remove_fmu_unpack_folder(const std::string& run_dir) {
  std::error_code ec;
  std::filesystem::remove_all(fmu_unpack_folder(run_dir), ec);
  return ec ? "cannot remove " + fmu_unpack_folder(run_dir) + ": " + ec.message() : "";
}

}  // namespace mechsim::cosim
