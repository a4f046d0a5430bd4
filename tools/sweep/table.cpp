#include "table.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include "figure_files.h"

namespace mechsim::sweep {

using nlohmann::json;

namespace {

std::string csv_cell(const json& v) {
  if (v.is_null()) return "";
  std::string s = v.is_string() ? v.get<std::string>() : v.dump();
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

double number_of(const json& row, const std::string& column) {
  const auto it = row.find(column);
  return it != row.end() && it->is_number() ? it->get<double>() : NAN;
}

bool is_figure_column(const std::string& c) {
  return c.find('(') != std::string::npos && c.find(".max_rel_error") == std::string::npos &&
         c.find(".rms_rel_error") == std::string::npos;
}

}  // namespace

std::vector<std::string> table_columns(const std::vector<VarySpec>& specs, const std::vector<json>& rows) {
  std::vector<std::string> columns{"point"};
  for (const auto& s : specs) {
    columns.push_back(s.key);
    columns.push_back(s.key + ".text");
  }
  for (const char* c : {"outcome", "reason", "steps", "wall_time_s", "worst_max_rel_error", "worst_max_rel_signal",
                        "worst_rms_rel_error", "worst_rms_rel_signal"})
    columns.push_back(c);
  std::set<std::string> seen(columns.begin(), columns.end());
  // Signals' errors before the figures, each group in the rows' order.
  for (const bool figures : {false, true})
    for (const auto& row : rows)
      for (const auto& [k, v] : row.items())
        if (is_figure_column(k) == figures && !seen.count(k)) {
          seen.insert(k);
          columns.push_back(k);
        }
  return columns;
}

void write_table_csv(const std::string& path, const std::vector<std::string>& columns, const std::vector<json>& rows) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot write");
  for (std::size_t i = 0; i < columns.size(); ++i) f << (i ? "," : "") << csv_cell(columns[i]);
  f << "\n";
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const auto it = row.find(columns[i]);
      f << (i ? "," : "") << (it == row.end() ? "" : csv_cell(*it));
    }
    f << "\n";
  }
  if (!f) throw std::runtime_error(path + ": write failed");
}

std::vector<std::string> write_plots(const std::string& dir, const std::string& scene_name, const std::vector<VarySpec>& specs,
                                     const std::vector<std::string>& columns, const std::vector<json>& rows, bool grid,
                                     std::vector<std::string>* problems) {
  std::vector<json> done;
  for (const auto& r : rows)
    if (r.value("outcome", "") == "ok") done.push_back(r);
  std::vector<std::string> plotted{"worst_max_rel_error"};
  for (const auto& c : columns) {
    if (!is_figure_column(c)) continue;
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& r : done)
      if (const double v = number_of(r, c); std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (hi > lo) plotted.push_back(c);  // a figure the sweep does not move says nothing here
  }
  std::vector<plot::NamedFigure> figures;
  for (std::size_t k = 0; k < specs.size(); ++k) {
    const VarySpec& spec = specs[k];
    if (std::none_of(done.begin(), done.end(), [&](const json& r) { return std::isfinite(number_of(r, spec.key)); })) continue;
    // Two keys in a grid: a line per value of the other; else the points as they fell.
    const bool lines = grid && specs.size() == 2;
    const std::string other = lines ? specs[1 - k].key + ".text" : "";
    plot::Figure figure;
    figure.title = scene_name + ": against " + spec.key;
    for (const auto& c : plotted) {
      plot::Panel panel;
      panel.title = c;
      panel.xlabel = spec.key + (spec.unit.empty() ? "" : " [" + spec.unit + "]");
      // The title names the figure; the axis its quantity ("rise_time_s", or the stat's value).
      const std::string quantity = c.substr(c.rfind(')') + 1);
      panel.ylabel = c == "worst_max_rel_error" ? "worst max error / range"
                     : quantity.empty()        ? c.substr(0, c.find('('))
                                               : quantity.substr(1);
      panel.logx = spec.log;
      panel.logy = c == "worst_max_rel_error";
      std::map<std::string, plot::Series> by_other;
      std::vector<std::string> order;
      for (const auto& r : done) {
        const double x = number_of(r, spec.key), y = number_of(r, c);
        if (!std::isfinite(x) || !std::isfinite(y) || (panel.logy && y <= 0)) continue;
        const std::string label = lines ? specs[1 - k].key + " = " + r.value(other, "") : grid ? "grid" : "samples";
        if (!by_other.count(label)) order.push_back(label);
        auto& s = by_other[label];
        s.label = label;
        // A line through a grid's values of one key; samples (or a grid of more keys) as a cloud.
        s.style = grid && (lines || specs.size() == 1) ? "linespoints" : "points";
        s.x.push_back(x);
        s.y.push_back(y);
      }
      for (const auto& label : order) {
        auto s = by_other[label];
        std::vector<std::size_t> idx(s.x.size());
        for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
        std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return s.x[a] < s.x[b]; });
        plot::Series sorted{s.label, {}, {}, s.style};
        for (auto i : idx) sorted.x.push_back(s.x[i]), sorted.y.push_back(s.y[i]);
        panel.series.push_back(std::move(sorted));
      }
      if (!panel.series.empty()) figure.panels.push_back(std::move(panel));
    }
    if (figure.panels.empty()) continue;
    std::string file = spec.key;
    for (char& ch : file)
      if (ch == '/' || ch == ' ') ch = '_';
    figures.push_back({file + ".png", std::move(figure)});
  }
  if (figures.empty()) return {};
  const plot::PlotOutcome outcome = plot::write_figures(dir, figures);
  if (problems) problems->insert(problems->end(), outcome.problems.begin(), outcome.problems.end());
  return outcome.files;
}

}  // namespace mechsim::sweep
