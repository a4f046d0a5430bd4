// mechsim._core: the C++ side of the Python package (python/mechsim/__init__.py wraps it).
// Structured results cross as JSON text (the layouts the command writes) and time series as
// NumPy arrays; long calls release the GIL, so that threads of one interpreter run points
// side by side.
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"
#include "point_row.h"
#include "scene_override.h"
#include "stdout_to_dev_null.h"
#include "sweep.h"

namespace py = pybind11;
using nlohmann::json;

namespace mechsim::python {
namespace {

// The nodes' "done: ..." lines kept off a notebook's stdout while any run of this process
// goes on: one redirection for all threads (each its own would restore another's /dev/null).
class QuietNodes {
 public:
  QuietNodes() {
    std::lock_guard<std::mutex> l(mutex());
    if (count()++ == 0) silence().emplace();
  }
  ~QuietNodes() {
    std::lock_guard<std::mutex> l(mutex());
    if (--count() == 0) silence().reset();
  }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static int& count() {
    static int n = 0;
    return n;
  }
  static std::optional<tools::StdoutToDevNull>& silence() {
    static std::optional<tools::StdoutToDevNull> s;
    return s;
  }
};

std::vector<std::string> overrides_of(const std::vector<std::string>& sets) {
  std::vector<std::string> out;
  for (const auto& s : sets) out.push_back(tools::scene_override(s));
  return out;
}

// The sweep's options from the package's JSON (the command's flags by name).
sweep::SweepOptions sweep_options(const std::string& text) {
  const json j = json::parse(text);
  sweep::SweepOptions o;
  o.scene_path = j.at("scene").get<std::string>();
  o.overrides = overrides_of(j.value("set", std::vector<std::string>{}));
  o.vary = j.at("vary").get<std::vector<std::string>>();
  o.design.method = sweep::parse_method(j.value("method", "grid"));
  o.design.samples = j.value("samples", 0);
  o.design.seed = j.value("seed", std::uint64_t{1});
  o.jobs = j.value("jobs", 0);
  o.out_dir = j.value("out", "sweep");
  o.resume = j.value("resume", false);
  o.progress = j.value("progress", true);
  o.plots = j.value("plots", true);
  o.max_hours = j.value("max_hours", 24.0);
  return o;
}

// A scene loaded and planned, as `mechsim check` does: its YAML after the overrides.
std::string check(const std::string& path, const std::vector<std::string>& sets) {
  const config::Scene scene = config::load_scene(path, overrides_of(sets));
  (void)cosim::ScenePlan::build(scene);
  return config::scene_to_yaml(scene);
}

py::dict run(const std::string& path, const std::vector<std::string>& sets, const std::string& run_dir) {
  const std::vector<std::string> overrides = overrides_of(sets);
  sweep::SceneRun r;
  {
    py::gil_scoped_release release;
    const QuietNodes quiet;
    r = sweep::run_scene(path, overrides, run_dir);
  }
  const json row = sweep::point_row(sweep::Point{}, r);
  py::dict out;
  out["summary"] = sweep::point_summary(overrides, row, r).dump();
  out["arrays"] = r.comparison ? comparison_arrays(*r.comparison) : py::dict();
  return out;
}

// The study's points after every check the command makes before running any: the design,
// the points, the reasons of refused ones. Throws ValueError for bad input.
std::string prepare(const std::string& options) {
  const sweep::SweepOptions o = sweep_options(options);
  const sweep::Study study = sweep::plan_study(o);
  const auto refused = sweep::check_points(o, study);
  sweep::begin_study(o, study);
  json points = json::array(), finished = json::array(), why = json::object();
  for (const auto& p : study.points) {
    points.push_back(sweep::point_json(p));
    finished.push_back(o.resume ? sweep::finished_row(o, p).value_or(json()) : json());
  }
  for (const auto& [index, reason] : refused) why[std::to_string(index)] = reason;
  return json{{"design", study.design}, {"points", points}, {"finished", finished}, {"refused", why},
              {"scene", o.scene_path}, {"overrides", o.overrides}, {"out", o.out_dir}}
      .dump();
}

std::string run_point(const std::string& scene, const std::vector<std::string>& overrides, const std::string& point,
                      const std::string& point_dir) {
  const sweep::Point p = sweep::point_from_json(json::parse(point));
  py::gil_scoped_release release;
  const QuietNodes quiet;
  return sweep::run_point(scene, overrides, p, point_dir).dump();
}

std::string write_outputs(const std::string& options, const std::string& rows) {
  const sweep::SweepOptions o = sweep_options(options);
  const sweep::Study study = sweep::plan_study(o);
  std::vector<std::string> problems;
  const json table = sweep::write_outputs(o, study, json::parse(rows).get<std::vector<json>>(), &problems);
  for (const auto& p : problems) std::cerr << "mechsim.sweep: no plot: " << p << "\n";
  return table.dump();
}

int run_sweep(const std::string& options) {
  const sweep::SweepOptions o = sweep_options(options);
  std::ostringstream out;
  int code;
  {
    py::gil_scoped_release release;
    code = sweep::run_sweep(o, out);
  }
  return code;
}

}  // namespace
}  // namespace mechsim::python

PYBIND11_MODULE(_core, m) {
  using namespace mechsim::python;
  m.doc() = "mechsim's C++ side; use the package `mechsim` (docs/python.md)";
  // Scene, design and MCAP errors reach Python as ValueError, with the command's message.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const std::runtime_error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.def("overrides", &overrides_of, "--set texts as the scene loader's dotted overrides");
  m.def("check", &check, "load and plan a scene with --set texts; its YAML", py::arg("path"), py::arg("sets"));
  m.def("run", &run, "one run in process, compared with the reference", py::arg("path"), py::arg("sets"), py::arg("run_dir"));
  m.def("read_mcap", &read_mcap, "an MCAP recording's samples as arrays per topic", py::arg("path"));
  m.def("prepare", &prepare, "a study's points after the checks (JSON)", py::arg("options"));
  m.def("run_point", &run_point, "one point of a study; its row (JSON)", py::arg("scene"), py::arg("overrides"), py::arg("point"),
        py::arg("point_dir"));
  m.def("write_outputs", &write_outputs, "the table and plots of a study's rows (JSON)", py::arg("options"), py::arg("rows"));
  m.def("run_sweep", &run_sweep, "the whole study as `mechsim sweep` runs it; the exit code", py::arg("options"));
}
