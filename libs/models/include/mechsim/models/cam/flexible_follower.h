// The report's linear vibration model of a flexible follower (spec cam.md §5, model (a)):
// one mass on a follower stiffness k_f with damping ratio ζ (damper to the frame), driven by
// the normalised lift θ(τ), τ = t/t_event:
//   γ'' + 2ζ(2πλ) γ' + (2πλ)² γ = (2πλ)² θ(τ)
// λ = number of natural periods in the event. Integrated with fixed-step RK4 (the step is
// a whole fraction of a natural period; see the tests for its convergence check).
#pragma once

#include <cstddef>
#include <vector>

#include "mechsim/models/cam/motion_law.h"

namespace mechsim::models::cam {

// A rest-to-rest motion: consecutive moving pieces of the law joined with S' ≠ 0 (a C1
// followed by its C2 is one event; a rise that ends at rest is its own event).
struct RestToRestEvent {
  std::size_t first_piece, last_piece;  // into law.pieces()
  double start_rad, span_rad;
  double start_lift_m, end_lift_m;
};

// The events of a law in angle order. An event running through 360° is kept whole: it
// starts before 360° and its span reaches past it (first_piece > last_piece then).
std::vector<RestToRestEvent> rest_to_rest_events(const MotionLaw& law);

// The critical event: the shortest one (the stiffest follower for a given λ); among equal
// spans the largest |lift|.
std::size_t critical_event_index(const std::vector<RestToRestEvent>& events);

// k_f = (2πλ/t_event)² m (574.19 N/mm for the press cam's fall at 30 rpm, λ = 9.38).
double follower_stiffness_for_lambda(double lambda, double mass_kg, double event_duration_s);

// λ' = λ · T/t_event = λ · 2π/β_event (48.24 for the press cam).
double multi_rise_lambda(double lambda, double event_span_rad);

// Normalised excitation of an event: θ(τ) = (S − S_end)/(S_start − S_end), 1 → 0.
double event_excitation(const MotionLaw& law, const RestToRestEvent& event, double tau);

struct VibrationSample {
  double tau, gamma, excitation;
};

struct SingleRiseResult {
  double lambda, damping_ratio;
  double max_error;         // max |γ − θ| for τ in [0, 1]
  double tau_max_error;
  double residual_amplitude;  // envelope of the free vibration at τ = 1: √(γ² + ((γ' + ζωγ)/ω_d)²)
  double max_residual;        // max |γ| sampled over the free vibration after the event
  // Approximation of the residual amplitude (Koster): Ã1 = Q/(2πλ)^N, N the order of the
  // first derivative of θ(τ) that jumps at the end of the event and Q its jump
  // (cycloid: N = 3, Q = (2π)²). NaN when no derivative up to the third jumps.
  int approx_order;
  double approx_q;
  double approx_residual_amplitude;
  std::vector<VibrationSample> samples;  // for the follower-error plot
};

// Integrates the event with γ(0) = 1, γ'(0) = 0, then the free vibration for free_tau
// after it. steps_per_period: RK4 steps per natural period (the event is split into a
// whole number of steps so that τ = 1 is a step boundary).
SingleRiseResult single_rise(const MotionLaw& law, const RestToRestEvent& event, double lambda,
                             double damping_ratio, int steps_per_period = 200,
                             double free_tau = 1.0, int plot_samples = 400);

struct MultiRiseResult {
  double lambda_prime, damping_ratio;
  int cycles;                  // the evaluated cycle is the last one
  double max_error;            // max |γ − θ| over the last cycle
  double theta_max_error_rad;  // cam angle of that maximum
  double max_dwell_error;      // max |γ − θ| over the dwells of the last cycle (residual vibration)
  double periodicity_error;    // max |γ_last − γ_previous| at equal phase: steady-state check
  std::vector<VibrationSample> samples;  // last cycle, τ in [0, 1) of the cycle
};

// The whole 360° law as excitation, θ(τ) = (S(2πτ) − S_min)/(S_max − S_min) with τ = t/T,
// starting from rest at γ = θ(0), γ' = 0; the last of `cycles` cycles is evaluated.
MultiRiseResult multi_rise(const MotionLaw& law, double lambda_prime, double damping_ratio,
                           int cycles = 20, int steps_per_period = 200, int plot_samples = 720);

}  // namespace mechsim::models::cam
