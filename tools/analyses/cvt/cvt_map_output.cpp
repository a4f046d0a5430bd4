// Presentation of the CVT operating maps: printed tables, JSON, PNG plots (docs/cvt.md).
#include <cmath>
#include <filesystem>
#include <functional>

#include "cvt_map.h"
#include "json_io.h"
#include "mechsim/models/constants.h"
#include "plot.h"
#include "provenance.h"
#include "text_format.h"

namespace mechsim::tools::cvt_map {

namespace cvt = models::cvt;
using nlohmann::json;

namespace {

using models::rpm;

using Getter = std::function<double(const cvt::CvtResult&)>;

// A field as nested arrays [s][torque][speed].
json field(const CvtMapResult& r, const std::vector<cvt::CvtResult>& grid, const Getter& get) {
  json out = json::array();
  for (std::size_t is = 0; is < r.s.size(); ++is) {
    json plane = json::array();
    for (std::size_t it = 0; it < r.torque.size(); ++it) {
      json row = json::array();
      for (std::size_t in = 0; in < r.speed.size(); ++in) row.push_back(finite_or_null(get(grid[r.index(is, it, in)])));
      plane.push_back(row);
    }
    out.push_back(plane);
  }
  return out;
}

struct FieldSpec {
  const char* key;
  const char* unit;
  const char* meaning;
  Getter get;
};

const std::vector<FieldSpec>& l1_fields() {
  static const std::vector<FieldSpec> f{
      {"ratio", "-", "i_TH = n_D/n_C (2.8)", [](const cvt::CvtResult& x) { return x.ratio; }},
      {"T_1", "Nm", "input-shaft torque T_C + T_Lprim (6.5)", [](const cvt::CvtResult& x) { return x.T_1; }},
      {"T_2", "Nm", "output-shaft torque T_D - T_Lsec (6.6)", [](const cvt::CvtResult& x) { return x.T_2; }},
      {"F_K", "N", "clamping force (4.67)", [](const cvt::CvtResult& x) { return x.F_K; }},
      {"eta_PB", "-", "belt efficiency (6.2)", [](const cvt::CvtResult& x) { return x.eta_PB; }},
      {"eta_SYS", "-", "system efficiency incl. bearings (6.10)", [](const cvt::CvtResult& x) { return x.eta_SYS; }},
      {"eta_L_prim", "-", "primary bearings (6.8)", [](const cvt::CvtResult& x) { return x.eta_L_prim; }},
      {"eta_L_sec", "-", "secondary bearings (6.9)", [](const cvt::CvtResult& x) { return x.eta_L_sec; }},
      {"P_loss_belt", "W", "support-surface slip loss (6.1)", [](const cvt::CvtResult& x) { return x.P_loss_belt; }},
      {"sigma_link_disc", "N/mm^2", "contact 1, link-disc (Hertz, elliptic)",
       [](const cvt::CvtResult& x) { return x.sigma[0] / 1e6; }},
      {"sigma_link_ring", "N/mm^2", "contact 2, link-C cone (Hertz, line)",
       [](const cvt::CvtResult& x) { return x.sigma[1] / 1e6; }},
      {"sigma_link_link", "N/mm^2", "contact 3, rocking edge, equivalent stress (5.49)",
       [](const cvt::CvtResult& x) { return x.sigma[2] / 1e6; }},
      {"sigma_support", "N/mm^2", "contact 4, support surface (5.53)",
       [](const cvt::CvtResult& x) { return x.sigma[3] / 1e6; }},
      {"slip_margin", "-", "v_KD: friction available / needed in the disc contact (4.64); < 1 is gross slip",
       [](const cvt::CvtResult& x) { return x.v_KD; }},
      {"slip_margin_ring", "-", "v_KC: the same for the C contact (4.66)", [](const cvt::CvtResult& x) { return x.v_KC; }},
      {"F_P_max", "N", "largest push force", [](const cvt::CvtResult& x) { return x.F_P_max; }},
      {"v_slip_max", "m/s", "largest support-surface slip speed", [](const cvt::CvtResult& x) { return x.v_slip_max; }},
  };
  return f;
}

// A table cell or label: "-" for a value the model could not compute.
std::string number_text(const char* format, double v) { return std::isfinite(v) ? fmt(format, v) : "-"; }

struct Range {
  double lo = INFINITY, hi = -INFINITY;
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

// The L0-vs-L1 deviation over the grid.
struct Deviation {
  Range F_K_rel, eta_PB, eta_SYS;
};
Deviation deviation(const CvtMapResult& r) {
  Deviation d;
  for (std::size_t k = 0; k < r.l1.size(); ++k) {
    const auto &a = r.l1[k], &b = r.l0[k];
    if (!cvt::belt_state_modelled(a.flags) || !cvt::belt_state_modelled(b.flags)) continue;
    if (a.F_K > 0) d.F_K_rel.add(b.F_K / a.F_K - 1.0);
    d.eta_PB.add(b.eta_PB - a.eta_PB);
    d.eta_SYS.add(b.eta_SYS - a.eta_SYS);
  }
  return d;
}

const char* clamp_name(cvt::ClampMode m) { return m == cvt::ClampMode::clamping_force ? "force" : "safety_factor"; }

}  // namespace

std::vector<std::string> summary_lines(const CvtMapResult& r) {
  std::vector<std::string> out;
  const auto& p = r.config.params;
  out.push_back("CVT operating map of " + r.scene_name + " (" + r.source + ")");
  for (const auto& n : r.notes) out.push_back("  note: " + n);
  out.push_back("  belt " + std::string(p.lambda == 1 ? "split" : "Lambda") + ", r_C " + number_text("%.1f", p.r_C * 1e3) +
                " mm, " + (p.disc_driving ? "disc" : "intermediate body") + " driving; clamping " +
                (r.config.clamp == cvt::ClampMode::clamping_force ? "force " + number_text("%.0f N", r.config.clamping_force)
                                                                   : "safety factor v_K = " + number_text("%.3g", r.config.safety_factor)));
  out.push_back("  grid: " + std::to_string(r.s.size()) + " ratio settings x " + std::to_string(r.torque.size()) +
                " torques x " + std::to_string(r.speed.size()) + " speeds");
  Range kr, epb, esys, s3, margin;
  unsigned flags = 0;
  for (const auto& x : r.l1) {
    flags |= x.flags;
    if (!cvt::belt_state_modelled(x.flags)) continue;
    if (x.T_over_r > 0) kr.add(x.F_K / x.T_over_r);
    epb.add(x.eta_PB);
    esys.add(x.eta_SYS);
    s3.add(x.sigma[2] / 1e6);
    margin.add(x.v_KD);
  }
  out.push_back("  F_K/(T/r) " + number_text("%.3f", kr.lo) + " .. " + number_text("%.3f", kr.hi) + ", eta_PB " + number_text("%.4f", epb.lo) +
                " .. " + number_text("%.4f", epb.hi) + ", eta_SYS " + number_text("%.4f", esys.lo) + " .. " + number_text("%.4f", esys.hi));
  out.push_back("  link-link stress " + number_text("%.0f", s3.lo) + " .. " + number_text("%.0f", s3.hi) + " N/mm^2 (admissible " +
                number_text("%.0f", p.sigma_admissible / 1e6) + "), slip margin v_KD " + number_text("%.3f", margin.lo) + " .. " +
                number_text("%.3f", margin.hi));
  if (flags) out.push_back("  flags on the grid: " + cvt::flag_names(flags));
  const Deviation d = deviation(r);
  out.push_back("  L0 vs L1: F_K " + number_text("%+.1f", 100 * d.F_K_rel.lo) + " .. " + number_text("%+.1f", 100 * d.F_K_rel.hi) +
                " %, eta_PB " + number_text("%+.4f", d.eta_PB.lo) + " .. " + number_text("%+.4f", d.eta_PB.hi) + ", eta_SYS " +
                number_text("%+.4f", d.eta_SYS.lo) + " .. " + number_text("%+.4f", d.eta_SYS.hi));
  struct Table {
    const char* title;
    const char* format;
    Getter get;
  };
  const Table tables[] = {{"T_1 [Nm]", "%9.3f", [](const cvt::CvtResult& x) { return x.T_1; }},
                          {"F_K [N]", "%9.0f", [](const cvt::CvtResult& x) { return x.F_K; }},
                          {"eta_PB", "%9.4f", [](const cvt::CvtResult& x) { return x.eta_PB; }},
                          {"eta_SYS", "%9.4f", [](const cvt::CvtResult& x) { return x.eta_SYS; }}};
  for (std::size_t is = 0; is < r.s.size(); ++is) {
    out.push_back("");
    out.push_back("s = " + number_text("%g", r.s[is] * 1e3) + " mm (i_TH = " + number_text("%.4f", r.l1[r.index(is, 0, 0)].ratio) + ")");
    for (const Table& t : tables) {
      std::string head = "  " + std::string(t.title);
      head.resize(14, ' ');
      head += "T_C \\ n_C";
      for (double w : r.speed) head += number_text("%9.0f", w / rpm);
      out.push_back(head + "  rpm");
      for (std::size_t it = 0; it < r.torque.size(); ++it) {
        std::string line = "  " + number_text("%19.1f", r.torque[it]) + " Nm";
        line.resize(25, ' ');
        for (std::size_t in = 0; in < r.speed.size(); ++in) {
          std::string cell = number_text(t.format, t.get(r.l1[r.index(is, it, in)]));
          if (cell == "-") cell = "        -";
          line += cell;
        }
        out.push_back(line);
      }
    }
  }
  return out;
}

json report_json(const CvtMapResult& r) {
  const auto& p = r.config.params;
  json j{{"schema_version", schema_version},
         {"command", "cvt-map"},
         {"provenance", provenance(r.scene_file)},
         {"scene", {{"name", r.scene_name}, {"file", r.scene_file}}},
         {"overrides", r.overrides},
         {"source", r.source},
         {"notes", r.notes}};
  j["parameters"] = {{"belt", p.lambda == 1 ? "split" : "lambda"},
                     {"driving", p.disc_driving ? "disc" : "intermediate_body"},
                     {"r_C_mm", p.r_C * 1e3},
                     {"clamping", {{"mode", clamp_name(r.config.clamp)},
                                   {"safety_factor", finite_or_null(r.config.clamp == cvt::ClampMode::safety_factor ? r.config.safety_factor : NAN)},
                                   {"force_n", finite_or_null(r.config.clamp == cvt::ClampMode::clamping_force ? r.config.clamping_force : NAN)}}},
                     {"admissible_stress_n_mm2", p.sigma_admissible / 1e6},
                     {"link_curvatures_mm", {{"r11", r.curvatures.r11 * 1e3}, {"r12", r.curvatures.r12 * 1e3},
                                             {"r22", r.curvatures.r22 * 1e3}}}};
  json s_mm = json::array(), t_nm = json::array(), n_rpm = json::array();
  for (double v : r.s) s_mm.push_back(v * 1e3);
  for (double v : r.torque) t_nm.push_back(v);
  for (double v : r.speed) n_rpm.push_back(v / rpm);
  j["axes"] = {{"order", {"s", "T_C", "n_C"}},
               {"s", {{"unit", "mm"}, {"meaning", "ratio setting (disc-axis offset)"}, {"values", s_mm}}},
               {"T_C", {{"unit", "Nm"}, {"meaning", "intermediate-body (input) torque"}, {"values", t_nm}}},
               {"n_C", {{"unit", "rpm"}, {"meaning", "input speed"}, {"values", n_rpm}}}};
  json fields = json::object();
  for (const FieldSpec& f : l1_fields())
    fields[f.key] = {{"unit", f.unit}, {"meaning", f.meaning}, {"values", field(r, r.l1, f.get)}};
  json flags = json::array();
  for (std::size_t is = 0; is < r.s.size(); ++is) {
    json plane = json::array();
    for (std::size_t it = 0; it < r.torque.size(); ++it) {
      json row = json::array();
      for (std::size_t in = 0; in < r.speed.size(); ++in) row.push_back(cvt::flag_names(r.l1[r.index(is, it, in)].flags));
      plane.push_back(row);
    }
    flags.push_back(plane);
  }
  fields["flags"] = {{"unit", ""}, {"meaning", "states outside the model (docs/cvt.md), comma-separated"}, {"values", flags}};
  j["fields"] = fields;
  j["level"] = r.config.level == cvt::Level::L0 ? "L0" : "L1";
  json l0 = json::object();
  l0["F_K"] = {{"unit", "N"}, {"values", field(r, r.l0, [](const cvt::CvtResult& x) { return x.F_K; })}};
  l0["eta_PB"] = {{"unit", "-"}, {"values", field(r, r.l0, [](const cvt::CvtResult& x) { return x.eta_PB; })}};
  l0["eta_SYS"] = {{"unit", "-"}, {"values", field(r, r.l0, [](const cvt::CvtResult& x) { return x.eta_SYS; })}};
  const Deviation d = deviation(r);
  l0["deviation_from_L1"] = {{"F_K_relative", {finite_or_null(d.F_K_rel.lo), finite_or_null(d.F_K_rel.hi)}},
                             {"eta_PB_absolute", {finite_or_null(d.eta_PB.lo), finite_or_null(d.eta_PB.hi)}},
                             {"eta_SYS_absolute", {finite_or_null(d.eta_SYS.lo), finite_or_null(d.eta_SYS.hi)}}};
  j["L0"] = l0;
  return j;
}

PlotOutcome write_plots(const std::string& dir, const CvtMapResult& r) {
  std::filesystem::create_directories(dir);
  // tools/plot draws curves, so a "map" is a family: x = T_C, one curve per ratio setting,
  // one panel per speed (the first, middle and last of the grid).
  std::vector<std::size_t> speeds{0};
  if (r.speed.size() > 2) speeds.push_back(r.speed.size() / 2);
  if (r.speed.size() > 1) speeds.push_back(r.speed.size() - 1);
  auto family = [&](const std::string& ylabel, const Getter& get, std::size_t in) {
    plot::Panel panel;
    panel.title = "n_C = " + number_text("%.0f", r.speed[in] / rpm) + " rpm";
    panel.xlabel = "input torque T_C [Nm]";
    panel.ylabel = ylabel;
    for (std::size_t is = 0; is < r.s.size(); ++is) {
      plot::Series s;
      s.label = "s = " + number_text("%g", r.s[is] * 1e3) + " mm (i = " + number_text("%.3f", r.l1[r.index(is, 0, in)].ratio) + ")";
      s.style = "linespoints";
      for (std::size_t it = 0; it < r.torque.size(); ++it) {
        s.x.push_back(r.torque[it]);
        const double v = get(r.l1[r.index(is, it, in)]);
        s.y.push_back(std::isfinite(v) ? v : NAN);
      }
      panel.series.push_back(std::move(s));
    }
    return panel;
  };
  struct Map {
    std::string file, title, ylabel;
    Getter get;
    bool fatigue_line;
  };
  const Map maps[] = {
      {"efficiency.png", "CVT system efficiency eta_SYS (belt and bearings)", "eta_SYS [-]",
       [](const cvt::CvtResult& x) { return x.eta_SYS; }, false},
      {"belt_efficiency.png", "Belt efficiency eta_PB (support-surface slip)", "eta_PB [-]",
       [](const cvt::CvtResult& x) { return x.eta_PB; }, false},
      {"clamping_force.png", "Required clamping force F_K", "F_K [kN]", [](const cvt::CvtResult& x) { return x.F_K / 1e3; },
       false},
      {"link_link_stress.png", "Link-link (rocking edge) equivalent Hertz stress", "sigma_3 [N/mm^2]",
       [](const cvt::CvtResult& x) { return x.sigma[2] / 1e6; }, true},
  };
  PlotOutcome out;
  for (const Map& m : maps) {
    plot::Figure f;
    f.title = m.title + " - " + r.scene_name;
    for (std::size_t in : speeds) {
      plot::Panel panel = family(m.ylabel, m.get, in);
      Range y;
      for (const auto& s : panel.series)
        for (double v : s.y) y.add(v);
      if (m.fatigue_line) {
        const double adm = r.config.params.sigma_admissible / 1e6;
        panel.hlines.push_back({adm, "admissible (fatigue) " + number_text("%.0f", adm) + " N/mm^2"});
        y.add(adm);
      }
      // Headroom above the curves for the key (gnuplot draws it top right, opaque).
      if (y.hi > y.lo) panel.yrange = std::make_pair(y.lo - 0.05 * (y.hi - y.lo), y.hi + 1.1 * (y.hi - y.lo));
      f.panels.push_back(std::move(panel));
    }
    const std::string path = (std::filesystem::path(dir) / m.file).string();
    std::string why;
    if (plot::write_png(f, path, &why)) {
      out.files.push_back(path);
    } else {
      out.problems.push_back(m.file + ": " + why);
    }
  }
  return out;
}

}  // namespace mechsim::tools::cvt_map
