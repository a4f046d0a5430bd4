// The HCVT push-belt CVT as a stationary map (spec cvt.md §3–§5, §8): for a ratio setting s,
// an input speed and a torque it gives the ratio, the clamping force, the link forces, the
// four Hertz stresses, the belt and bearing losses and the efficiencies.
//
//   L1 (reference): the thesis's program step by step (belt shape, link-by-link equilibrium
//       with the transition packet, the clamping-force search of §3.8); reproduces §6.2.
//   L0 (screening): closed form, F_K = cos β_D·(T/r)/(λ μ_D), η_PB from the mean slip.
//
// SI at the interface. The thesis's model is stationary and valid for positive torque in its
// rig's range; states outside it are flagged (CvtFlag), bad inputs throw CvtInputError.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "mechsim/models/cvt/belt_geometry.h"
#include "mechsim/models/cvt/cvt_params.h"
#include "mechsim/models/cvt/hertz.h"

namespace mechsim::models::cvt {

// A bad input (NaN, s outside the geometric range, negative clamping force, ...).
class CvtInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

enum class ClampMode {
  safety_factor,   // v_K given: F_K = v_K·F_K,min results (thesis mode)
  clamping_force,  // F_K given: v_K follows; v_K < 1 is gross slip (flagged, not modelled)
};

enum class TorqueInput {
  intermediate_body,  // T_C on the intermediate body (the thesis's variable)
  input_shaft,        // T_1 = T_C + T_Lprim (input torque meter)
  output_load,        // T_2 on the disc shaft (the load)
};

enum class Level { L1, L0 };

struct CvtOperatingPoint {
  double s = 15e-3;          // ratio setting [m]
  double omega_C = 0.0;      // speed of the intermediate-body (input) shaft [rad/s], >= 0
  double torque = 0.0;       // [Nm], meaning given by torque_input
  TorqueInput torque_input = TorqueInput::intermediate_body;
  ClampMode clamp = ClampMode::safety_factor;
  double v_K = 1.0;          // clamping reserve factor (safety_factor mode), > 0
  double F_K_applied = 0.0;  // [N] (clamping_force mode), >= 0
  Level level = Level::L1;
};

// Flags of a result: states outside the thesis's model. Bit set.
enum CvtFlag : unsigned {
  kOutsideValidatedRange = 1u << 0,  // s, T_C or speed outside the rig's 5–55 mm, 20–120 Nm, 1000–5000 rpm
  kGrossSlip = 1u << 1,              // applied F_K below F_K,min (v_K < 1): the belt slips, not modelled
  kStressExceeded = 1u << 2,         // a contact stress above σ̄_HZ
  kLinkShift = 1u << 3,              // q_D or q_C clipped to μ_E: links shift at the transition ends
  kZeroTorque = 1u << 4,             // T_C = 0: unloaded belt (η_PB = 1, F_K = 0)
  kTorqueReversal = 1u << 5,         // T_C < 0, or T_C so small that the slip loss exceeds T_C ω_C:
                                     // power from the disc side, outside the model
  kZeroSpeed = 1u << 6,              // ω_C = 0: no slip power, η_PB := 1
  kNoSolution = 1u << 7,             // the §3.8 search found no push force (F_P0 > 1000·T/r)
  kBadInput = 1u << 8,               // set by CvtBlock: an input the model refuses (NaN, s or the
                                     // ratio command outside the tabulated range); the block
                                     // carries on with a lossless belt at the clamped s
};
// "gross_slip,link_shift" etc., empty for none.
std::string flag_names(unsigned flags);
// True when the belt numbers are the model's (no gross slip, reversal, no solution).
inline bool belt_state_modelled(unsigned flags) {
  return (flags & (kGrossSlip | kTorqueReversal | kNoSolution | kBadInput)) == 0;
}

struct BearingLoads {
  double F_rA = 0.0, F_rB = 0.0, F_aA = 0.0, F_aB = 0.0;  // [N]
  double T_L0A = 0.0, T_L0B = 0.0, T_L1A = 0.0, T_L1B = 0.0;  // [Nm]
  double loss_torque() const { return T_L0A + T_L0B + T_L1A + T_L1B; }
};

// Per-link forces of the L1 model [N]; F_P has n+1 entries (F_P(j), j = 1..n+1).
struct ArcForces {
  std::vector<double> F_P, F_N, F_A, F_W, F_WST, F_WSR;
};

struct CvtResult {
  Level level = Level::L1;
  unsigned flags = 0;
  // kinematics
  double s = 0.0, z_max = 0.0, r_D = 0.0, r_F = 0.0;  // [m]
  double ratio = 0.0;                                 // i_TH = ω_D/ω_C
  double gamma_D = 0.0, gamma_C = 0.0, gamma_F = 0.0;  // [rad]
  int n_D = 0, n_C = 0;
  double omega_C = 0.0, omega_D = 0.0;  // [rad/s]
  double T_over_r = 0.0;                // belt force T/r [N]
  double v_PB = 0.0;                    // belt speed [m/s]
  // torques and efficiencies
  double T_C = 0.0, T_D = 0.0, T_1 = 0.0, T_2 = 0.0;  // [Nm]
  double P_loss_belt = 0.0;                           // [W]
  double T_L_prim = 0.0, T_L_sec = 0.0;               // [Nm]
  double eta_PB = 1.0, eta_L_prim = 1.0, eta_L_sec = 1.0, eta_SYS = 1.0;
  // clamping and slip margin
  double F_K = 0.0;          // clamping force acting [N] (L1: rounded ΣF_AD as coded)
  double F_K_applied = 0.0;  // clamping_force mode: the command [N]
  double v_K = 1.0;          // reserve factor the search ran with
  double v_KD = 0.0, v_KC = 0.0;  // achieved slip margins of the disc and C contact
  double mu_D_required = 0.0;     // μ_D that would just carry the torque, = cos β_D (T/r)/(λ F_K)
  double T_C_capacity = 0.0;      // torque the applied F_K can carry at v_KD = 1 [Nm]
  double q_D = 0.0, q_C = 0.0, n_alpha_D = 0.0, n_alpha_C = 0.0;
  double F_P0 = 0.0, F_P_min = 0.0, F_P_max = 0.0;  // [N]
  double F_C_D = 0.0, F_C_C = 0.0, F_C_packet = 0.0;  // centrifugal forces [N]
  std::array<double, 4> F_N_peak{};  // forces used for σ1..σ4 [N]
  std::array<double, 4> sigma{};     // σ1 link–disc, σ2 link–C, σ3 link–link (equivalent), σ4 support [Pa]
  double v_slip_max = 0.0;           // max support-surface slip speed [m/s]
  BearingLoads bearings_prim, bearings_sec;
  ArcForces disc, ring;              // per-link forces (L1 only)
  std::vector<double> slip;          // v_SLIP/v_PB per disc link

  double sigma_utilisation(int i, double admissible) const { return sigma[i] / admissible; }
};

class CvtModel {
 public:
  explicit CvtModel(CvtParams params = {});
  const CvtParams& params() const { return p_; }
  const LinkCurvatures& curvatures() const { return curv_; }

  // Precomputes the belt shape over [s_lo, s_hi] (points searches); later evaluations inside
  // interpolate z_max and r_F (no search). Without it every new s is searched once.
  void tabulate_shapes(double s_lo, double s_hi, int points);
  // The belt shape at s [m] (cached). Throws CvtInputError outside the geometric range.
  BeltShape shape(double s);
  // The same without the per-link fields (allocation-free where tabulated): ratio, link
  // counts and angles, for a time step.
  BeltShape shape_scalars(double s);

  // The operating point. Throws CvtInputError on bad input; states outside the model are
  // flagged in the result.
  CvtResult evaluate(const CvtOperatingPoint& op);

  // Bearing model of appendix B2 for one shaft (spec §3.9, §5): r [m] = r_C (primary) or r_D.
  BearingLoads bearing_losses(bool primary, double r, double omega, double F_K, double T_over_r) const;

 private:
  BeltShape checked_shape(double s, bool scalars_only);
  CvtResult evaluate_tc(const CvtOperatingPoint& op, double T_C, double v_K);
  // The results of evaluate_tc where no force balance is solved: an unloaded or reversed
  // belt (T_C <= 0), gross slip under a clamping force too low for T_C.
  void unloaded(CvtResult& r, const CvtOperatingPoint& op, double T_C) const;
  void gross_slip(CvtResult& r, const CvtOperatingPoint& op, double T_C, double v_K) const;
  // Centrifugal forces into r, and the least push force F_Pmin that keeps the transition
  // packet's deviation within bounds (0: none does).
  double min_push_force(CvtResult& r, const BeltShape& b, const LinkGeometry& g) const;
  void solve_l1(CvtResult& r, const BeltShape& b, double v_K);
  void solve_l0(CvtResult& r, const BeltShape& b, double v_K);
  void finish(CvtResult& r, const BeltShape& b);

  CvtParams p_;
  LinkCurvatures curv_;
  BeltShapeCache shapes_;
};

}  // namespace mechsim::models::cvt
