#include "mechsim/models/cam/flexible_follower.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "mechsim/models/constants.h"

namespace mechsim::models::cam {

namespace {

bool moving(const MotionLaw::Piece& p) { return p.segment.type != SegmentType::dwell && p.segment.lift_m != 0.0; }

// Fixed-step RK4 for γ'' + 2ζω γ' + ω² γ = ω² θ(τ), state (γ, γ').
struct Oscillator {
  double omega, zeta;
  template <typename Excitation>
  void step(double tau, double h, std::array<double, 2>& y, Excitation&& theta) const {
    auto f = [&](double t, const std::array<double, 2>& s) {
      return std::array<double, 2>{s[1], omega * omega * (theta(t) - s[0]) - 2.0 * zeta * omega * s[1]};
    };
    const auto k1 = f(tau, y);
    const auto k2 = f(tau + h / 2, {y[0] + h / 2 * k1[0], y[1] + h / 2 * k1[1]});
    const auto k3 = f(tau + h / 2, {y[0] + h / 2 * k2[0], y[1] + h / 2 * k2[1]});
    const auto k4 = f(tau + h, {y[0] + h * k3[0], y[1] + h * k3[1]});
    y[0] += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]);
    y[1] += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]);
  }
};

void check_vibration_inputs(double lambda, double zeta, int steps_per_period) {
  if (!(lambda > 0.0)) throw std::invalid_argument("flexible follower: lambda must be > 0");
  if (!(zeta >= 0.0 && zeta < 1.0))
    throw std::invalid_argument("flexible follower: damping ratio must be in [0, 1)");
  if (steps_per_period < 20)
    throw std::invalid_argument("flexible follower: need at least 20 RK4 steps per natural period");
}

}  // namespace

std::vector<RestToRestEvent> rest_to_rest_events(const MotionLaw& law) {
  const auto& pieces = law.pieces();
  const std::size_t n = pieces.size();
  // A joint "continues" an event when both sides move and the follower does not stop there.
  const double speed_scale = law.max_lift();
  auto continues = [&](std::size_t i) {  // joint between piece i and i + 1 (mod n)
    const std::size_t j = (i + 1) % n;
    if (!moving(pieces[i]) || !moving(pieces[j])) return false;
    const double end = pieces[i].segment.start_rad + pieces[i].segment.span_rad;
    return std::abs(law.evaluate_piece(i, end).s_d1) > 1e-9 * speed_scale;
  };
  // Start the scan just after a joint that does not continue an event.
  std::size_t first = 0;
  bool found = false;
  for (std::size_t i = 0; i < n && !found; ++i)
    if (!continues((i + n - 1) % n)) first = i, found = true;
  if (!found) throw std::invalid_argument("rest_to_rest_events: the follower never stops");
  std::vector<RestToRestEvent> events;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (first + k) % n;
    if (!moving(pieces[i])) continue;
    const bool starts = !continues((i + n - 1) % n);
    if (starts) {
      events.push_back({i, i, pieces[i].segment.start_rad, 0.0, pieces[i].start_lift_m, 0.0});
    }
    RestToRestEvent& e = events.back();
    e.last_piece = i;
    double end = pieces[i].segment.start_rad + pieces[i].segment.span_rad;
    if (end < e.start_rad) end += two_pi;  // the event runs through 360°
    e.span_rad = end - e.start_rad;
    e.end_lift_m = pieces[i].start_lift_m + pieces[i].segment.lift_m;
  }
  std::sort(events.begin(), events.end(),
            [](const RestToRestEvent& a, const RestToRestEvent& b) { return a.start_rad < b.start_rad; });
  return events;
}

std::size_t critical_event_index(const std::vector<RestToRestEvent>& events) {
  if (events.empty()) throw std::invalid_argument("critical_event_index: the law has no motion");
  std::size_t best = 0;
  for (std::size_t i = 1; i < events.size(); ++i) {
    const auto& e = events[i];
    const auto& b = events[best];
    const double de = std::abs(e.end_lift_m - e.start_lift_m), db = std::abs(b.end_lift_m - b.start_lift_m);
    if (e.span_rad < b.span_rad - 1e-12 || (std::abs(e.span_rad - b.span_rad) <= 1e-12 && de > db)) best = i;
  }
  return best;
}

double follower_stiffness_for_lambda(double lambda, double mass_kg, double event_duration_s) {
  if (!(event_duration_s > 0.0)) throw std::invalid_argument("follower stiffness: event duration must be > 0");
  const double wn = two_pi * lambda / event_duration_s;
  return wn * wn * mass_kg;
}

double multi_rise_lambda(double lambda, double event_span_rad) { return lambda * two_pi / event_span_rad; }

double event_excitation(const MotionLaw& law, const RestToRestEvent& e, double tau) {
  const double range = e.start_lift_m - e.end_lift_m;
  if (std::abs(range) < 1e-15) throw std::invalid_argument("event_excitation: the event has no net lift");
  if (tau <= 0.0) return 1.0;
  if (tau >= 1.0) return 0.0;
  return (law.evaluate(e.start_rad + tau * e.span_rad).s - e.end_lift_m) / range;
}

SingleRiseResult single_rise(const MotionLaw& law, const RestToRestEvent& event, double lambda,
                             double zeta, int steps_per_period, double free_tau, int plot_samples) {
  check_vibration_inputs(lambda, zeta, steps_per_period);
  const double omega = two_pi * lambda;
  const Oscillator osc{omega, zeta};
  const int n_event = static_cast<int>(std::ceil(lambda * steps_per_period));
  const double h = 1.0 / n_event;
  const int n_free = static_cast<int>(std::ceil(free_tau / h));
  const int n_total = n_event + n_free;
  const int plot_every = std::max(1, n_total / std::max(plot_samples, 1));
  auto theta = [&](double tau) { return event_excitation(law, event, tau); };

  SingleRiseResult out{};
  out.lambda = lambda, out.damping_ratio = zeta;
  std::array<double, 2> y{1.0, 0.0};
  out.samples.push_back({0.0, y[0], 1.0});
  for (int i = 0; i < n_total; ++i) {
    const double tau = i * h;
    osc.step(tau, h, y, theta);
    const double t1 = (i + 1) * h;
    const double th = theta(t1);
    if (i + 1 <= n_event) {
      const double err = std::abs(y[0] - th);
      if (err > out.max_error) out.max_error = err, out.tau_max_error = t1;
    } else {
      out.max_residual = std::max(out.max_residual, std::abs(y[0]));
    }
    if (i + 1 == n_event) {
      const double wd = omega * std::sqrt(1.0 - zeta * zeta);
      out.residual_amplitude = std::hypot(y[0], (y[1] + zeta * omega * y[0]) / wd);
    }
    if ((i + 1) % plot_every == 0 || i + 1 == n_event) out.samples.push_back({t1, y[0], th});
  }

  // The first derivative of θ(τ) = (S − S_end)/(S_start − S_end) that jumps at τ = 1⁻.
  const double range = event.start_lift_m - event.end_lift_m;
  const auto& last = law.pieces()[event.last_piece].segment;
  const LawPoint p = law.evaluate_piece(event.last_piece, last.start_rad + last.span_rad);
  const double derivs[3] = {p.s_d1 * event.span_rad / range,
                            p.s_d2 * std::pow(event.span_rad, 2) / range,
                            p.s_d3 * std::pow(event.span_rad, 3) / range};
  out.approx_order = 0, out.approx_q = nan, out.approx_residual_amplitude = nan;
  for (int k = 0; k < 3; ++k)
    if (std::abs(derivs[k]) > 1e-9) {
      out.approx_order = k + 1;
      out.approx_q = std::abs(derivs[k]);
      out.approx_residual_amplitude = out.approx_q / std::pow(omega, k + 1);
      break;
    }
  return out;
}

MultiRiseResult multi_rise(const MotionLaw& law, double lambda_prime, double zeta, int cycles,
                           int steps_per_period, int plot_samples) {
  check_vibration_inputs(lambda_prime, zeta, steps_per_period);
  if (cycles < 2) throw std::invalid_argument("multi_rise: need at least 2 cycles");
  // Every piece is monotone, so the lift extremes sit at piece ends.
  double s_min = 0.0, s_max = 0.0;
  for (const auto& p : law.pieces()) {
    s_min = std::min(s_min, p.start_lift_m);
    s_max = std::max(s_max, p.start_lift_m);
  }
  if (!(s_max > s_min)) throw std::invalid_argument("multi_rise: the law has no lift");
  auto theta = [&](double tau) { return (law.evaluate(two_pi * tau).s - s_min) / (s_max - s_min); };

  const double omega = two_pi * lambda_prime;
  const Oscillator osc{omega, zeta};
  const int n = static_cast<int>(std::ceil(lambda_prime * steps_per_period));
  const double h = 1.0 / n;
  const int plot_every = std::max(1, n / std::max(plot_samples, 1));
  std::vector<double> previous(n), current(n);
  std::array<double, 2> y{theta(0.0), 0.0};
  MultiRiseResult out{};
  out.lambda_prime = lambda_prime, out.damping_ratio = zeta, out.cycles = cycles;
  for (int c = 0; c < cycles; ++c) {
    for (int i = 0; i < n; ++i) {
      const double tau = i * h;  // phase within the cycle; θ is periodic
      current[i] = y[0];
      if (c == cycles - 1) {
        const double th = theta(tau);
        const double err = std::abs(y[0] - th);
        if (err > out.max_error) out.max_error = err, out.theta_max_error_rad = two_pi * tau;
        const LawPoint p = law.evaluate(two_pi * tau);
        if (p.s_d1 == 0.0 && p.s_d2 == 0.0) out.max_dwell_error = std::max(out.max_dwell_error, err);
        if (i % plot_every == 0) out.samples.push_back({tau, y[0], th});
      }
      osc.step(tau, h, y, theta);
    }
    if (c == cycles - 1)
      for (int i = 0; i < n; ++i) out.periodicity_error = std::max(out.periodicity_error, std::abs(current[i] - previous[i]));
    std::swap(previous, current);
  }
  return out;
}

}  // namespace mechsim::models::cam
