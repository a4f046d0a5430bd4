// One in-process run of a scene for the FMU tests (node threads over the in-process
// transport, cosim::run_inproc) with its node logs in `folder`: the FMU-played and the
// native scene are each run so and their logs compared.
#pragma once

#include <filesystem>

#include <gtest/gtest.h>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/inproc_run.h"

namespace mechsim::fmi::test {

inline ::testing::AssertionResult runs_in_process(const config::Scene& scene, const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  cosim::InprocRunOptions options;
  options.run_dir = folder.string();
  const auto run = cosim::run_inproc(scene, options);
  if (run.ok) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << run.reason;
}

}  // namespace mechsim::fmi::test
