// NumPy arrays of what the package hands to Python: a run's compared signals against the
// reference, and the samples of an MCAP recording (read with libs/record, decoded with
// tools/record's CDR decoder).
#pragma once

#include <string>

#include <pybind11/pybind11.h>

#include "scene_run.h"

namespace mechsim::python {

// {"t": array, "signals": {name: {"unit", "cosim", "reference", "error"}}} of a compared run.
pybind11::dict comparison_arrays(const assess::ReferenceComparison& comparison);

// {topic: {"t", "step", "run_id", field...: array}}, one entry per sample in recording order;
// booleans and integers as float64, string members left out. A damaged chunk is skipped.
// Throws record::McapError for a file that is not MCAP.
pybind11::dict read_mcap(const std::string& path);

}  // namespace mechsim::python
