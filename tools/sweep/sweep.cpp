#include "sweep.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "json_io.h"
#include "mechsim/cosim/scene_plan.h"
#include "point_row.h"
#include "provenance.h"
#include "stdout_to_dev_null.h"
#include "stop_signals.h"
#include "table.h"
#include "text_format.h"

namespace mechsim::sweep {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

std::string duration_text(double s) {
  if (!std::isfinite(s)) return "?";
  if (s < 90) return tools::fmt("%.0f s", s);
  if (s < 5400) return tools::fmt("%.0f min", s / 60);
  return tools::fmt("%.1f h", s / 3600);
}

}  // namespace

std::string point_dir(const std::string& out_dir, int index) { return out_dir + "/points/" + tools::fmt("%05d", index); }

std::optional<json> finished_row(const SweepOptions& o, const Point& point) {
  std::ifstream f(point_dir(o.out_dir, point.index) + "/summary.json");
  if (!f) return std::nullopt;
  try {
    const json summary = json::parse(f);
    if (summary.at("overrides").get<std::vector<std::string>>() != point_overrides(o.overrides, point)) return std::nullopt;
    return summary.at("row");
  } catch (const std::exception&) {
    return std::nullopt;  // half-written or foreign: run it again
  }
}

void begin_study(const SweepOptions& o, const Study& study) {
  fs::create_directories(o.out_dir);
  const std::string design_path = o.out_dir + "/design.json";
  if (o.resume && fs::exists(design_path)) {
    std::ifstream f(design_path);
    const json before = json::parse(f, nullptr, false);
    if (!before.is_object() || before.value("design", json()) != study.design)
      throw DesignError("--resume: " + o.out_dir + " holds another study (" + design_path +
                        "); give another --out or the same arguments");
  }
  tools::write_json_file(design_path, {{"schema_version", tools::schema_version}, {"design", study.design}});
}

Study plan_study(const SweepOptions& o) {
  Study study;
  for (const auto& v : o.vary) study.specs.push_back(parse_vary(v));
  study.points = make_design(study.specs, o.design);
  study.design = {{"scene_file", o.scene_path}, {"overrides", o.overrides}, {"vary", o.vary},
                  {"method", to_string(o.design.method)}, {"points", study.points.size()}};
  if (o.design.method != Method::grid) {
    study.design["samples"] = o.design.samples;
    study.design["seed"] = o.design.seed;
  }
  return study;
}

std::map<int, std::string> check_points(const SweepOptions& o, const Study& study) {
  std::map<int, std::string> refused;
  // A large design is checked on kCheckedPoints spread over it (a scene loads in about a
  // millisecond: a million points would be checked for longer than many of them run); the
  // rest are checked when they run, a refused one still a row.
  constexpr std::size_t kCheckedPoints = 2000;
  const std::size_t stride = std::max<std::size_t>(1, study.points.size() / kCheckedPoints);
  std::size_t checked = 0;
  for (std::size_t i = 0; i < study.points.size(); i += stride) {
    const Point& p = study.points[i];
    ++checked;
    try {
      const config::Scene scene = config::load_scene(o.scene_path, point_overrides(o.overrides, p));
      (void)cosim::ScenePlan::build(scene);
    } catch (const std::exception& e) {
      const std::string why = e.what();
      // A key the scene does not have refuses every point alike: bad input, not a result.
      if (why.find("unknown key") != std::string::npos) throw DesignError(why);
      refused[p.index] = why;
    }
  }
  if (checked > 0 && refused.size() == checked)
    throw DesignError("the scene refuses every point of the design; the first: " + refused.begin()->second);
  return refused;
}

json write_outputs(const SweepOptions& o, const Study& study, std::vector<json> rows, std::vector<std::string>* problems) {
  std::sort(rows.begin(), rows.end(), [](const json& a, const json& b) { return a["point"].get<int>() < b["point"].get<int>(); });
  const std::vector<std::string> columns = table_columns(study.specs, rows);
  fs::create_directories(o.out_dir);
  write_table_csv(o.out_dir + "/sweep.csv", columns, rows);
  json counts = json::object();
  for (const auto& r : rows) counts[r.value("outcome", "?")] = counts.value(r.value("outcome", "?"), 0) + 1;
  json table = {{"schema_version", tools::schema_version}, {"provenance", tools::provenance(o.scene_path)},
                {"design", study.design}, {"counts", counts}, {"columns", columns}, {"rows", rows}};
  json files = {{"csv", o.out_dir + "/sweep.csv"}, {"json", o.out_dir + "/sweep.json"}, {"plots", json::array()}};
  if (o.plots) {
    const std::string scene_name = fs::path(o.scene_path).stem().string();
    for (const auto& png : write_plots(o.out_dir + "/plots", scene_name, study.specs, columns, rows,
                                       o.design.method == Method::grid, problems))
      files["plots"].push_back(png);
  }
  table["files"] = files;
  tools::write_json_file(o.out_dir + "/sweep.json", table);
  return table;
}

int run_sweep(const SweepOptions& o, std::ostream& out) {
  Study study;
  std::map<int, std::string> refused;
  try {
    study = plan_study(o);
    refused = check_points(o, study);
    begin_study(o, study);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim sweep: %s: %s\n", o.scene_path.c_str(), e.what());
    return 2;
  }
  int told = 0;  // the first few, so that a design refused in large parts says so without a page a point
  for (const auto& [index, why] : refused)
    if (++told <= 5) std::fprintf(stderr, "mechsim sweep: point %d is refused: %s\n", index, why.c_str());
  if (told > 5) std::fprintf(stderr, "mechsim sweep: and %d more points are refused (their rows say why)\n", told - 5);

  std::vector<json> rows;
  std::vector<const Point*> to_run;
  for (const auto& p : study.points) {
    const auto row = o.resume ? finished_row(o, p) : std::nullopt;
    if (row) rows.push_back(*row);
    else to_run.push_back(&p);
  }
  const std::size_t resumed = rows.size(), total = study.points.size();
  const int jobs = std::max(1, std::min<int>(o.jobs > 0 ? o.jobs : static_cast<int>(std::thread::hardware_concurrency()),
                                             static_cast<int>(std::max<std::size_t>(1, to_run.size()))));
  std::fprintf(stderr, "mechsim sweep: %zu points (%s)%s, %zu to run on %d job%s\n", total, to_string(o.design.method),
               resumed ? tools::fmt(", %zu finished before", resumed).c_str() : "", to_run.size(), jobs, jobs == 1 ? "" : "s");

  std::mutex m;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::size_t ran = 0;
  double point_seconds = 0;  // summed over the points run here
  std::map<std::string, int> outcomes;
  std::string too_long;
  const auto t0 = Clock::now();
  auto worker = [&] {
    while (!stop && !tools::stop_requested()) {
      const std::size_t i = next++;
      if (i >= to_run.size()) return;
      const Point& p = *to_run[i];
      json row;
      try {
        row = run_point(o.scene_path, o.overrides, p, point_dir(o.out_dir, p.index));
      } catch (const std::exception& e) {  // the point's files, not its run: still a row
        SceneRun failed;
        failed.outcome = "failed";
        failed.reason = e.what();
        row = point_row(p, failed);
      }
      std::lock_guard<std::mutex> l(m);
      ++ran;
      point_seconds += row.value("wall_time_s", 0.0);
      ++outcomes[row.value("outcome", "?")];
      rows.push_back(std::move(row));
      // The estimate, once the first point of each job could have finished: a study of days is stopped.
      const double estimate = point_seconds / ran * static_cast<double>(to_run.size() - ran) / jobs;
      if (ran == static_cast<std::size_t>(jobs) && estimate > o.max_hours * 3600 && ran < to_run.size()) {
        too_long = tools::fmt("the %zu points would take about %s on %d jobs (%.3g s a point), more than --max-hours %g; "
                              "the %zu finished are kept (--resume), give --max-hours to go on",
                              to_run.size(), duration_text(estimate).c_str(), jobs, point_seconds / ran, o.max_hours, ran);
        stop = true;
      }
    }
  };
  std::optional<tools::StdoutToDevNull> quiet_nodes;
  quiet_nodes.emplace();
  std::vector<std::thread> threads;
  for (int j = 0; j < jobs; ++j) threads.emplace_back(worker);
  const bool tty = o.progress && isatty(STDERR_FILENO);
  auto last_line = Clock::now();
  auto progress = [&](bool final_line) {
    std::lock_guard<std::mutex> l(m);
    const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
    const double eta = ran ? elapsed / ran * static_cast<double>(to_run.size() - ran) : NAN;
    std::string line = tools::fmt("sweep: %zu/%zu points", resumed + ran, total);
    for (const auto& [outcome, n] : outcomes)
      if (outcome != "ok") line += tools::fmt(", %d %s", n, outcome.c_str());
    line += tools::fmt(", %s elapsed", duration_text(elapsed).c_str());
    if (!final_line) line += ", ETA " + duration_text(eta);
    std::fprintf(stderr, tty ? "\r%-90s%s" : "%s%s\n", line.c_str(), tty && final_line ? "\n" : "");
    std::fflush(stderr);
  };
  while (true) {
    bool done;
    {
      std::lock_guard<std::mutex> l(m);
      done = ran == to_run.size() || stop || tools::stop_requested();
    }
    if (done) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    // On a terminal the line is rewritten; in a log, a line every 10 s.
    if (o.progress && (tty || Clock::now() - last_line > std::chrono::seconds(10))) {
      progress(false);
      last_line = Clock::now();
    }
  }
  for (auto& t : threads) t.join();
  quiet_nodes.reset();
  if (o.progress) progress(true);

  std::vector<std::string> problems;
  json table;
  try {
    table = write_outputs(o, study, rows, &problems);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim sweep: %s\n", e.what());
    return 1;
  }
  for (const auto& p : problems) std::fprintf(stderr, "mechsim sweep: no plot: %s\n", p.c_str());
  out << "sweep of " << o.scene_path << ": " << rows.size() << " of " << total << " points";
  for (const auto& [outcome, n] : table["counts"].items()) out << ", " << n.get<int>() << " " << outcome;
  out << "\n  table: " << o.out_dir << "/sweep.csv, " << o.out_dir << "/sweep.json\n";
  for (const auto& png : table["files"]["plots"]) out << "  plot:  " << png.get<std::string>() << "\n";
  if (!too_long.empty()) {
    std::fprintf(stderr, "mechsim sweep: %s\n", too_long.c_str());
    return 3;
  }
  if (tools::stop_requested()) {
    std::fprintf(stderr, "mechsim sweep: interrupted; the %zu finished points are kept (--resume goes on)\n", rows.size());
    return 130;
  }
  return 0;
}

}  // namespace mechsim::sweep
