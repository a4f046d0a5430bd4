#include "mechsim/cosim/composer.h"

#include "mechsim/cosim/output_log.h"

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace mechsim::cosim {

CompositeBlock::CompositeBlock(ScenePlan& plan) : Block("composite"), plan_(plan) {
  auto& nodes = plan.nodes();
  const std::size_t n = nodes.size();
  state_base_.assign(1, 0);
  output_base_.assign(1, 0);
  event_base_.assign(1, 0);
  for (auto& node : nodes) {
    for (const auto& s : node.block->state_names()) declare_state(node.name() + "." + s, "");
    for (const auto& o : node.block->outputs()) declare_output(node.name() + "." + o.name, o.unit);
    state_base_.push_back(state_base_.back() + node.block->num_states());
    output_base_.push_back(output_base_.back() + node.block->num_outputs());
    event_base_.push_back(event_base_.back() + node.block->num_event_functions());
    u_.push_back(node.block->default_inputs());
    y_.emplace_back(node.block->num_outputs(), 0.0);
  }
  auto index_of = [&](const std::string& name) {
    for (std::size_t i = 0; i < n; ++i)
      if (nodes[i].name() == name) return static_cast<int>(i);
    throw std::logic_error("unknown participant " + name);
  };
  wires_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    for (const auto& edge : nodes[i].inputs) {
      int src = index_of(edge.from);
      for (const auto& [field, input] : edge.field_to_input)
        wires_[i].push_back({input, src, nodes[src].published_outputs[field]});  // >= 0: the plan checked it
    }

  for (std::size_t i = 0; i < n; ++i)
    if (nodes[i].cut && nodes[i].cut->twist_sign > 0) {
      const int partner = index_of(nodes[i].cut->partner);
      cuts_.push_back({static_cast<int>(i), partner, &*nodes[i].cut, &*nodes[partner].cut});
    }

  for (const auto& node : nodes) {
    const double ts = node.block->sample_time();
    if (ts > 0 && (sample_time_ == 0 || ts < sample_time_)) sample_time_ = ts;
  }
  for (const auto& node : nodes) {
    const double ts = node.block->sample_time();
    long ratio = 0;
    if (ts > 0) {
      ratio = std::lround(ts / sample_time_);
      if (std::abs(ratio * sample_time_ - ts) > 1e-9 * ts)
        throw std::runtime_error("sample time of " + node.name() + " (" + std::to_string(ts) +
                                 " s) is not a whole multiple of the shortest one in the scene (" +
                                 std::to_string(sample_time_) + " s)");
    }
    sample_ratio_.push_back(ratio);
  }

  // Sweeps needed: the longest chain of outputs linked by feedthrough (the plan refused
  // cycles), counted in blocks visited; each sweep evaluates every block once in order.
  std::vector<std::vector<int>> feeds(output_base_.back());  // composite output -> dependent outputs
  for (std::size_t i = 0; i < n; ++i)
    for (const auto& w : wires_[i])
      for (int o = 0; o < nodes[i].block->num_outputs(); ++o)
        for (int ft : nodes[i].block->outputs()[o].feedthrough)
          if (ft == w.input) feeds[output_base_[w.source_block] + w.source_output].push_back(output_base_[i] + o);
  std::vector<int> depth(feeds.size(), 0);
  std::function<int(int)> longest = [&](int v) {
    if (depth[v]) return depth[v];
    int d = 1;
    for (int w : feeds[v]) d = std::max(d, 1 + longest(w));
    return depth[v] = d;
  };
  for (std::size_t v = 0; v < feeds.size(); ++v) passes_ = std::max(passes_, longest(static_cast<int>(v)));
  // A cut's torque needs both sides' angle and speed (no feedthrough: right after one pass).
  if (!cuts_.empty()) passes_ += 1;
}

std::span<const double> CompositeBlock::block_state(std::span<const double> x, std::size_t i) const {
  return x.subspan(state_base_[i], state_base_[i + 1] - state_base_[i]);
}

void CompositeBlock::evaluate(double t, std::span<const double> x) const {
  auto& nodes = plan_.nodes();
  for (int pass = 0; pass < passes_; ++pass)
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      for (const auto& w : wires_[i]) u_[i][w.input] = y_[w.source_block][w.source_output];
      for (const auto& c : cuts_) {
        if (c.plus_block != static_cast<int>(i) && c.minus_block != static_cast<int>(i)) continue;
        const auto& yp = y_[c.plus_block];
        const auto& ym = y_[c.minus_block];
        const double torque = c.plus->stiffness * (yp[c.plus->angle_output] - ym[c.minus->angle_output]) +
                              c.plus->damping * (yp[c.plus->speed_output] - ym[c.minus->speed_output]);
        u_[i][c.plus_block == static_cast<int>(i) ? c.plus->torque_input : c.minus->torque_input] = torque;
      }
      nodes[i].block->calc_outputs(t, block_state(x, i), u_[i], y_[i]);
    }
}

void CompositeBlock::initial_state(double t0, std::span<double> x) const {
  auto& nodes = plan_.nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    nodes[i].block->initial_state(t0, x.subspan(state_base_[i], state_base_[i + 1] - state_base_[i]));
}

void CompositeBlock::derivatives(double t, std::span<const double> x, std::span<const double>,
                                 std::span<double> dxdt) const {
  evaluate(t, x);
  auto& nodes = plan_.nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    nodes[i].block->derivatives(t, block_state(x, i), u_[i],
                                dxdt.subspan(state_base_[i], state_base_[i + 1] - state_base_[i]));
}

void CompositeBlock::calc_outputs(double t, std::span<const double> x, std::span<const double>,
                                  std::span<double> y) const {
  evaluate(t, x);
  for (std::size_t i = 0; i < y_.size(); ++i) std::copy(y_[i].begin(), y_[i].end(), y.begin() + output_base_[i]);
}

void CompositeBlock::discrete_update(double t, std::span<double> x, std::span<const double>) {
  // The integrator calls this at t0 + j * sample_time_, j = 0, 1, ...: block i updates
  // when j is a multiple of its ratio, with the inputs its partners give at that instant.
  auto& nodes = plan_.nodes();
  evaluate(t, x);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (sample_ratio_[i] > 0 && samples_taken_ % sample_ratio_[i] == 0) {
      nodes[i].block->discrete_update(t, x.subspan(state_base_[i], state_base_[i + 1] - state_base_[i]), u_[i]);
      evaluate(t, x);  // held outputs changed: later blocks see the new values
    }
  ++samples_taken_;
}

models::Crossing CompositeBlock::event_direction(int index) const {
  std::size_t i = 0;
  while (event_base_[i + 1] <= index) ++i;
  return plan_.nodes()[i].block->event_direction(index - event_base_[i]);
}

void CompositeBlock::event_functions(double t, std::span<const double> x, std::span<const double>,
                                     std::span<double> g) const {
  evaluate(t, x);
  auto& nodes = plan_.nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    nodes[i].block->event_functions(t, block_state(x, i), u_[i],
                                    g.subspan(event_base_[i], event_base_[i + 1] - event_base_[i]));
}

bool CompositeBlock::handle_events(double t, std::span<double> x, std::span<const double>,
                                   std::span<const int> crossed) {
  evaluate(t, x);
  bool changed = false;
  auto& nodes = plan_.nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    auto c = crossed.subspan(event_base_[i], event_base_[i + 1] - event_base_[i]);
    bool any = false;
    for (int v : c) any = any || v != 0;
    if (any)
      changed = nodes[i].block->handle_events(t, x.subspan(state_base_[i], state_base_[i + 1] - state_base_[i]),
                                              u_[i], c) || changed;
  }
  return changed;
}

std::vector<models::BlockEvent> CompositeBlock::take_event_log() {
  std::vector<models::BlockEvent> all;
  for (auto& node : plan_.nodes())
    for (auto& e : node.block->take_event_log()) {
      e.kind = node.name() + "." + e.kind;
      all.push_back(std::move(e));
    }
  return all;
}

std::vector<double> CompositeBlock::save_discrete_state() const {
  std::vector<double> all;
  for (const auto& node : plan_.nodes()) {
    auto s = node.block->save_discrete_state();
    all.push_back(static_cast<double>(s.size()));
    all.insert(all.end(), s.begin(), s.end());
  }
  return all;
}

void CompositeBlock::restore_discrete_state(std::span<const double> saved) {
  std::size_t pos = 0;
  for (auto& node : plan_.nodes()) {
    auto len = static_cast<std::size_t>(saved[pos++]);
    node.block->restore_discrete_state(saved.subspan(pos, len));
    pos += len;
  }
}

ReferenceRun run_reference(ScenePlan& plan, double rtol, double atol) {
  if (plan.grid()->is_adaptive())
    throw std::invalid_argument("the reference of a scene with an adaptive step is sampled at the instants its run took");
  return run_reference_at(plan, run_instants(plan, ""), rtol, atol);  // sampled where the nodes publish
}

std::vector<double> run_instants(const ScenePlan& plan, const std::string& run_dir) {
  const StepGrid& grid = *plan.grid();
  if (grid.is_adaptive()) return read_output_log(run_dir + "/" + plan.nodes().front().name() + ".outputs.bin").data.at(0);
  std::vector<double> instants(grid.steps() + 1);
  for (std::uint64_t k = 0; k < instants.size(); ++k) instants[k] = grid.time(k);
  return instants;
}

ReferenceRun run_reference_at(ScenePlan& plan, std::span<const double> instants, double rtol, double atol) {
  const auto started = std::chrono::steady_clock::now();
  if (instants.empty() || instants.front() != plan.scene().time.start)
    throw std::invalid_argument("reference: the instants must start at the scene's start");
  const config::TimeSpec& time = plan.scene().time;
  CompositeBlock composite(plan);
  std::vector<double> x(composite.num_states()), y(composite.num_outputs());
  composite.initial_state(time.start, x);
  solve::SolverOptions options;
  options.rtol = rtol;
  options.atol = atol;
  solve::BlockIntegrator integrator(composite, options, time.start, x);

  ReferenceRun run;
  run.rtol = rtol;
  run.atol = atol;
  run.log.columns.push_back("t");
  for (const auto& o : composite.outputs()) run.log.columns.push_back(o.name);
  run.log.data.resize(run.log.columns.size());
  const auto n = static_cast<long>(instants.size()) - 1;
  for (auto& column : run.log.data) column.reserve(n + 1);
  auto sample = [&](double t) {
    composite.calc_outputs(t, integrator.state(), {}, y);
    run.log.data[0].push_back(t);
    for (std::size_t j = 0; j < y.size(); ++j) run.log.data[j + 1].push_back(y[j]);
  };
  const solve::InputFunction no_inputs = [](double, std::span<double>) {};
  integrator.advance_to(time.start, no_inputs);  // sampled blocks: the t0 sample before the t0 outputs
  sample(time.start);
  for (long k = 1; k <= n; ++k) {
    const double t = instants[static_cast<std::size_t>(k)];
    integrator.advance_to(t, no_inputs);
    for (auto& e : composite.take_event_log()) run.events.push_back(std::move(e));
    sample(t);
  }
  run.stats = integrator.stats();
  run.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return run;
}

double ReferenceAccuracy::max_abs_of(const std::string& column) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == column) return max_abs[i];
  return std::numeric_limits<double>::quiet_NaN();
}

double ReferenceAccuracy::rms_abs_of(const std::string& column) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == column) return rms_abs[i];
  return std::numeric_limits<double>::quiet_NaN();
}

ReferenceAccuracy estimate_reference_error(const config::Scene& scene, const ReferenceRun& ref, double factor) {
  ScenePlan plan = ScenePlan::build(scene);
  ReferenceAccuracy acc;
  acc.rtol = ref.rtol / factor;
  acc.atol = ref.atol / factor;
  const ReferenceRun tight = run_reference_at(plan, ref.log.data.at(0), acc.rtol, acc.atol);  // the same instants
  acc.wall_time_s = tight.wall_time_s;
  acc.stats = tight.stats;
  if (tight.log.columns != ref.log.columns || tight.log.rows() != ref.log.rows())
    throw std::logic_error("reference check: the tighter run has other columns or rows than the reference");
  for (std::size_t c = 1; c < ref.log.columns.size(); ++c) {
    double worst = 0.0, sum_sq = 0.0;
    const auto& a = ref.log.data[c];
    const auto& b = tight.log.data[c];
    for (std::size_t k = 0; k < a.size(); ++k) {
      const double d = std::abs(a[k] - b[k]);
      // NaN columns (fields a configuration does not compute) agree when both are NaN.
      if (std::isnan(a[k]) && std::isnan(b[k])) continue;
      worst = std::isfinite(d) ? std::max(worst, d) : std::numeric_limits<double>::infinity();
      sum_sq += d * d;
    }
    acc.columns.push_back(ref.log.columns[c]);
    acc.max_abs.push_back(worst);
    acc.rms_abs.push_back(a.empty() ? 0.0 : std::sqrt(sum_sq / static_cast<double>(a.size())));
  }
  return acc;
}

}  // namespace mechsim::cosim
