#include "realtime_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "mechsim/cosim/process_realtime.h"
#include "plot.h"

namespace mechsim::launch {

using nlohmann::json;

namespace {

json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) return json();
  json j = json::parse(in, nullptr, false);
  return j.is_discarded() ? json() : j;
}

}  // namespace

std::vector<std::string> realtime_rights_problems(const config::Scene& scene) {
  std::vector<std::string> problems;
  if (scene.mode != config::RunMode::realtime) return problems;  // the nodes apply them in real-time mode only
  const cosim::ProcessRights rights = cosim::current_process_rights();
  std::set<std::string> seen;  // a scene-wide setting refused once, not once per participant
  for (const auto& p : scene.participants) {
    if (!p.process_realtime.any()) continue;
    const std::string why = cosim::realtime_refusal(p.process_realtime, rights);
    if (!why.empty() && seen.insert(why).second) problems.push_back(why);
  }
  return problems;
}

json realtime_summary(const config::Scene& scene, const cosim::StepGrid& grid, const std::vector<std::string>& nodes,
                      const std::string& run_dir,
                      const std::vector<std::string>& warnings) {
  json per_node = json::object();
  long long missed = 0;
  double p99 = 0, worst = 0, paced = 0, jitter_std = 0, jitter_max = 0;
  double rtf = std::numeric_limits<double>::infinity();
  for (const std::string& name : nodes) {
    json f = read_json(run_dir + "/" + name + ".realtime.json");
    if (!f.is_object()) continue;
    missed += f.value("missed_deadlines", 0LL);
    p99 = std::max(p99, f.value("lateness_p99_s", 0.0));
    worst = std::max(worst, f.value("lateness_max_s", 0.0));
    rtf = std::min(rtf, f.value("rtf_achieved", 0.0));
    paced = std::max(paced, f.value("paced_wall_time_s", 0.0));
    jitter_std = std::max(jitter_std, f.value("period_jitter_std_s", 0.0));
    jitter_max = std::max(jitter_max, f.value("period_jitter_max_s", 0.0));
    if (f.contains("worst"))
      for (auto& w : f["worst"]) w["t_s"] = grid.time(std::min<std::uint64_t>(w.value("step", std::uint64_t{0}), grid.steps()));
    per_node[name] = std::move(f);
  }
  return {{"rtf_requested", scene.rtf},
          {"warnings", warnings},
          {"on_overrun", config::to_string(scene.realtime.on_overrun)},
          {"wait", scene.realtime.spin_wait ? "spin" : "blocking"},
          {"missed_deadlines", missed},
          {"lateness_p99_s", p99},
          {"lateness_max_s", worst},
          {"period_jitter_std_s", jitter_std},
          {"period_jitter_max_s", jitter_max},
          {"rtf_achieved", std::isfinite(rtf) ? rtf : 0.0},
          {"paced_wall_time_s", paced},
          {"nodes", per_node}};
}

json process_settings_summary(const std::vector<std::string>& nodes, const std::string& run_dir) {
  json out = json::object();
  for (const std::string& name : nodes) {
    json applied = read_json(run_dir + "/" + name + ".process.json");
    if (applied.is_object()) out[name] = std::move(applied);
  }
  return out;
}

std::vector<std::string> write_lateness_plots(const json& realtime, double step_wall_s, const std::string& run_dir,
                                              std::string* why) {
  std::vector<std::string> written;
  if (!realtime.contains("nodes")) return written;
  for (const auto& [name, f] : realtime["nodes"].items()) {
    if (!f.contains("lateness_histogram")) continue;
    const json& h = f["lateness_histogram"];
    const double bin = h.value("bin_s", 1e-6);
    // Outline of the histogram in microseconds, coarsened to at most ~400 bars so a
    // 20 000-bin record stays readable: bars of `width` bins.
    long last_bin = 0;
    for (const auto& b : h["bins"]) last_bin = std::max(last_bin, b[0].get<long>());
    const long width = std::max<long>(1, (last_bin + 1 + 399) / 400);
    std::vector<double> counts(static_cast<std::size_t>(last_bin / width + 1), 0.0);
    for (const auto& b : h["bins"]) counts[static_cast<std::size_t>(b[0].get<long>() / width)] += b[1].get<double>();
    plot::Series bars{.label = name + ": publications per " + std::to_string(width) + " us"};
    for (std::size_t i = 0; i < counts.size(); ++i) {
      const double x0 = static_cast<double>(i) * width * bin * 1e6, x1 = static_cast<double>(i + 1) * width * bin * 1e6;
      const double y = counts[i] > 0 ? counts[i] : std::nan("");
      bars.x.insert(bars.x.end(), {x0, x1});
      bars.y.insert(bars.y.end(), {y, y});
    }
    const double p99_us = f.value("lateness_p99_s", 0.0) * 1e6, max_us = f.value("lateness_max_s", 0.0) * 1e6;
    auto marker = [](const std::string& label, double x, const char* style) {
      return plot::Series{.label = label, .x = {x, x}, .y = {0.8, 1e9}, .style = style};
    };
    char p99_label[64], max_label[64];
    std::snprintf(p99_label, sizeof p99_label, "p99 %.1f us", p99_us);
    std::snprintf(max_label, sizeof max_label, "max %.1f us", max_us);
    plot::Panel panel{.title = name, .xlabel = "lateness of a publication against its deadline [us]", .ylabel = "publications",
                      .series = {bars, marker(p99_label, p99_us, "dashed"), marker(max_label, max_us, "dashed")}, .logy = true};
    panel.yrange = std::make_pair(0.8, std::max(10.0, 2.0 * f.value("publications", 1.0)));
    if (max_us > step_wall_s * 1e6 * 0.5) panel.series.push_back(marker("deadline missed beyond (one step)", step_wall_s * 1e6, "lines"));
    if (h.value("overflow", 0L) > 0)
      panel.title += " (" + std::to_string(h.value("overflow", 0L)) + " publications later than 20 ms, beyond the axis)";
    char title[160];
    std::snprintf(title, sizeof title, "%s: %ld publications, %ld missed deadlines, period jitter %.1f us (std), %.1f us (max)",
                  name.c_str(), f.value("publications", 0L), f.value("missed_deadlines", 0L), f.value("period_jitter_std_s", 0.0) * 1e6,
                  f.value("period_jitter_max_s", 0.0) * 1e6);
    plot::Figure figure{.title = title, .panels = {panel}};
    const std::string png = run_dir + "/" + name + ".lateness.png";
    if (plot::write_png(figure, png, why)) written.push_back(png);
  }
  return written;
}

void print_realtime_summary(const json& summary) {
  if (summary.contains("realtime")) {
    const json& r = summary["realtime"];
    std::printf("  real time (rtf %g, %s wait): %lld missed deadlines, lateness p99 %.3f ms, max %.3f ms, achieved rtf %.3f\n",
                r["rtf_requested"].get<double>(), r["wait"].get<std::string>().c_str(), r["missed_deadlines"].get<long long>(),
                1e3 * r["lateness_p99_s"].get<double>(), 1e3 * r["lateness_max_s"].get<double>(), r["rtf_achieved"].get<double>());
    for (const auto& [name, f] : r["nodes"].items())
      std::printf("    %-12s %ld missed, lateness median %.3f / p99 %.3f / max %.3f ms, period jitter %.3f ms std, %.3f ms max\n",
                  name.c_str(), f.value("missed_deadlines", 0L), 1e3 * f.value("lateness_median_s", 0.0),
                  1e3 * f.value("lateness_p99_s", 0.0), 1e3 * f.value("lateness_max_s", 0.0), 1e3 * f.value("period_jitter_std_s", 0.0),
                  1e3 * f.value("period_jitter_max_s", 0.0));
    // The worst publications of the run (several nodes late at the same step: a stall that
    // travelled around the lock-step ring from the node that was late first).
    std::map<std::uint64_t, std::pair<double, std::string>> worst;
    for (const auto& [name, f] : r["nodes"].items())
      if (f.contains("worst"))
        for (const auto& w : f["worst"]) {
          auto& entry = worst[w["step"].get<std::uint64_t>()];
          entry.first = std::max(entry.first, w["lateness_s"].get<double>());
          entry.second += (entry.second.empty() ? "" : ",") + name;
        }
    std::vector<std::pair<double, std::uint64_t>> ranked;
    for (const auto& [step, e] : worst) ranked.push_back({e.first, step});
    std::sort(ranked.rbegin(), ranked.rend());
    std::string line;
    for (std::size_t i = 0; i < ranked.size() && i < 4; ++i) {
      if (ranked[i].first < 1e-3 * 0.25) break;  // only what matters against the target
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s%.2f ms at step %llu (%s)", line.empty() ? "" : "; ", 1e3 * ranked[i].first,
                    static_cast<unsigned long long>(ranked[i].second), worst[ranked[i].second].second.c_str());
      line += buf;
    }
    if (!line.empty()) std::printf("    worst: %s\n", line.c_str());
  }
  if (summary.contains("process_realtime") && !summary["process_realtime"].empty())
    for (const auto& [name, a] : summary["process_realtime"].items()) {
      std::string cpus;
      for (const auto& c : a["cpus"]) cpus += (cpus.empty() ? "" : ",") + std::to_string(c.get<int>());
      std::printf("  process %-12s %s%s, memory %s, cpus %s\n", name.c_str(), a["policy"].get<std::string>().c_str(),
                  a["priority"].get<int>() > 0 ? (" " + std::to_string(a["priority"].get<int>())).c_str() : "",
                  a["memory_locked"].get<bool>() ? "locked" : "not locked", cpus.empty() ? "any" : cpus.c_str());
    }
}

}  // namespace mechsim::launch
