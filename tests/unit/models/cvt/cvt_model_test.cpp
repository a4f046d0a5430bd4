// The CVT operating point (L1 and L0) against spec cvt.md §6.2 and check cases CC3, CC5, CC7,
// the sanity checks of §9, the input modes and guards of §8, and invariants over the thesis
// grid. Tolerances are the spec's "ref" tolerances; [D] values without a stated tolerance are
// checked to half a unit of their last printed digit.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mechsim/models/cvt/cvt_model.h"

namespace cvt = mechsim::models::cvt;

namespace {
constexpr double kMPa = 1e6;
constexpr double kRpm = std::numbers::pi / 30.0;

cvt::CvtOperatingPoint point(double s_mm, double T_C, double rpm) {
  cvt::CvtOperatingPoint op;
  op.s = s_mm * 1e-3;
  op.torque = T_C;
  op.omega_C = rpm * kRpm;
  return op;
}

class CvtModelTest : public ::testing::Test {
 protected:
  cvt::CvtModel model_;
};
}  // namespace

// CC3 — belt operating point: T/r ±0.01 N, v_PB ±0.005 m/s; centrifugal forces ±0.1 %.
TEST_F(CvtModelTest, CC3BeltOperatingPoint) {
  const cvt::CvtResult r = model_.evaluate(point(15, 35, 3000));
  EXPECT_NEAR(r.T_over_r, 843.37, 0.01);
  EXPECT_NEAR(r.v_PB, 13.04, 0.005);
  EXPECT_NEAR(r.F_C_D, 4.311, 4.311e-3);
  EXPECT_NEAR(r.F_C_C, 5.734, 5.734e-3);
  EXPECT_NEAR(r.F_C_packet, 30.35, 30.35e-3);
}

// CC5 — the complete operating point of §6.2 (s = 15 mm, T_C = 35 Nm, 3000 rpm, v_K = 1).
TEST_F(CvtModelTest, CC5CompleteOperatingPoint) {
  const cvt::CvtResult r = model_.evaluate(point(15, 35, 3000));
  ASSERT_TRUE(cvt::belt_state_modelled(r.flags)) << cvt::flag_names(r.flags);
  // [T] with the CC5 table's tolerances.
  EXPECT_NEAR(r.P_loss_belt, 394.2, 0.1);
  EXPECT_NEAR(r.eta_PB, 0.9641, 0.0001);
  EXPECT_NEAR(r.T_L_prim, 1.05, 0.005);
  EXPECT_NEAR(r.T_L_sec, 1.158, 0.001);
  EXPECT_NEAR(r.eta_L_prim, 0.9709, 0.0001);
  EXPECT_NEAR(r.eta_L_sec, 0.9742, 0.0001);
  EXPECT_NEAR(r.eta_SYS, 0.9119, 0.0001);
  // [D] "ref" column.
  EXPECT_NEAR(r.F_K, 7088.0, 1.0);
  EXPECT_NEAR(r.F_P0, 506.0, 0.1);
  EXPECT_NEAR(r.F_P0 / r.T_over_r, 0.60, 1e-9);  // an integer multiple of duwproc·T/r
  EXPECT_NEAR(r.F_P_max, 1549.2, 0.1);
  EXPECT_NEAR(r.disc.F_P.back() - r.disc.F_P.front(), 1035.6, 0.1);
  EXPECT_GT(r.disc.F_P.back() - r.disc.F_P.front(), r.T_over_r);  // [T] ≈ 1000 N > T/r: C drives
  EXPECT_NEAR(r.sigma[0] / kMPa, 1170.0, 11.70);
  EXPECT_NEAR(r.sigma[1] / kMPa, 589.0, 5.89);
  EXPECT_NEAR(r.sigma[2] / kMPa, 1572.0, 15.72);
  EXPECT_NEAR(r.sigma[3] / kMPa, 135.0, 1.35);
  EXPECT_NEAR(r.T_D, 44.887, 0.01);
  EXPECT_NEAR(r.T_2, 43.730, 0.01);
  EXPECT_NEAR(r.omega_D, 236.18, 0.005);
  EXPECT_NEAR(r.T_1, 36.050, 0.0005);
  // Intermediate values [D] of §3.8, printed to 0.1 N / 3 decimals.
  EXPECT_NEAR(r.F_P_min, 42.17, 0.005);
  EXPECT_NEAR(r.n_alpha_D, 0.097, 0.0005);
  EXPECT_NEAR(r.n_alpha_C, 68.94, 0.005);
  EXPECT_NEAR(r.q_D, 0.12, 1e-12);  // clipped at μ_E
  EXPECT_NEAR(r.q_C, 0.12, 1e-12);
  EXPECT_NEAR(r.v_KD, 1.031, 0.0005);
  EXPECT_NEAR(r.v_KC, 3.587, 0.0005);
  const double FP[] = {506.0, 563.1, 591.3, 622.3, 657.2, 697.8, 747.2, 809.2, 883.4, 965.7, 1053.7, 1146.4, 1244.0, 1541.6};
  const double FN[] = {471.3, 206.4, 217.9, 232.3, 252.7, 286.5, 346.5, 430.1, 512.6, 585.1, 651.2, 714.8, 2339.0};
  const double FA[] = {461.0, 201.9, 213.1, 227.2, 247.2, 280.3, 339.0, 420.7, 501.4, 572.4, 637.0, 699.2, 2287.9};
  ASSERT_EQ(r.disc.F_P.size(), 14u);
  for (int j = 0; j < 14; ++j) EXPECT_NEAR(r.disc.F_P[j], FP[j], 0.05) << "F_P link " << j + 1;
  for (int j = 0; j < 13; ++j) {
    EXPECT_NEAR(r.disc.F_N[j], FN[j], 0.05) << "F_N link " << j + 1;
    EXPECT_NEAR(r.disc.F_A[j], FA[j], 0.05) << "F_A link " << j + 1;
  }
  EXPECT_NEAR(*std::max_element(r.ring.F_N.begin(), r.ring.F_N.end()), 831.4, 0.05);
  double sum_FNC = 0.0;
  for (double f : r.ring.F_N) sum_FNC += f;
  EXPECT_NEAR(sum_FNC, 14522.0, 0.5);
  // Bearing loads at the §6.2 point [D], whole newtons.
  EXPECT_NEAR(r.bearings_prim.F_rA, 2607.0, 0.5);
  EXPECT_NEAR(r.bearings_prim.F_rB, 1693.0, 0.5);
  EXPECT_NEAR(r.bearings_prim.F_aA, 1003.0, 0.5);
  EXPECT_NEAR(r.bearings_prim.F_aB, 8091.0, 0.5);
  EXPECT_NEAR(r.bearings_sec.F_rA, 5701.0, 0.5);
  EXPECT_NEAR(r.bearings_sec.F_rB, 7322.0, 0.5);
  EXPECT_NEAR(r.bearings_sec.F_aA, 1781.0, 0.5);
  EXPECT_NEAR(r.bearings_sec.F_aB, 8869.0, 0.5);
}

// CC5's warning: the text's half-angle convention gives P_verlies = 406.5 W, η_PB = 0.9630,
// F_P0 = 1139 N [D] — proof that the convention switch does what it says.
TEST(CvtModelOptions, HalfAngleConventionGivesTheTextNumbers) {
  cvt::CvtParams p;
  p.full_angle = false;
  cvt::CvtModel m(p);
  const cvt::CvtResult r = m.evaluate(point(15, 35, 3000));
  EXPECT_NEAR(r.P_loss_belt, 406.5, 0.05);
  EXPECT_NEAR(r.eta_PB, 0.9630, 0.00005);
  EXPECT_NEAR(r.F_P0, 1139.0, 0.5);
}

// Sanity: F_K grows with v_K; the §6.2 point with v_K = 1.3 [D] (F_K ±1 N as CC5, η ±0.0001,
// σ ±1 %).
TEST_F(CvtModelTest, ClampingReserveFactor13) {
  cvt::CvtOperatingPoint op = point(15, 35, 3000);
  op.v_K = 1.3;
  const cvt::CvtResult r = model_.evaluate(op);
  EXPECT_NEAR(r.F_K, 8946.0, 1.0);
  EXPECT_NEAR(r.P_loss_belt, 491.7, 0.05);
  EXPECT_NEAR(r.eta_PB, 0.9553, 0.0001);
  EXPECT_NEAR(r.eta_SYS, 0.8945, 0.0001);
  EXPECT_NEAR(r.sigma[0] / kMPa, 1233.0, 12.33);
  EXPECT_NEAR(r.sigma[1] / kMPa, 630.0, 6.30);
  EXPECT_NEAR(r.sigma[2] / kMPa, 1691.0, 16.91);
  EXPECT_NEAR(r.sigma[3] / kMPa, 157.0, 1.57);
  EXPECT_GE(r.v_KD, 1.3);
  EXPECT_GT(r.F_K, model_.evaluate(point(15, 35, 3000)).F_K);
}

// CC7 — bearing-loss model: T_Lprim = 0.5613 Nm ±0.00005 with its intermediate values [D]
// (0.1 N, 5 decimals in Nm) and the secondary side T_Lsec = 0.6327 Nm.
TEST_F(CvtModelTest, CC7BearingLosses) {
  const double Tr = 20.0 / 0.0415;
  const cvt::BearingLoads b = model_.bearing_losses(true, 41.5e-3, 104.720, 3994.0, Tr);
  EXPECT_NEAR(b.loss_torque(), 0.5613, 0.00005);
  EXPECT_NEAR(b.F_rA, 1469.5, 0.05);
  EXPECT_NEAR(b.F_rB, 962.3, 0.05);
  EXPECT_NEAR(b.F_aA, 565.2, 0.05);
  EXPECT_NEAR(b.F_aB, 4559.2, 0.05);
  EXPECT_NEAR(b.T_L0A, 0.06609, 0.000005);
  EXPECT_NEAR(b.T_L0B, 0.11013, 0.000005);
  EXPECT_NEAR(b.T_L1A, 0.02851, 0.000005);
  EXPECT_NEAR(b.T_L1B, 0.35653, 0.000005);
  const cvt::BearingLoads s = model_.bearing_losses(false, 69.9596e-3, 0.59320 * 104.720, 3994.0, Tr);
  EXPECT_NEAR(s.loss_torque(), 0.6327, 0.00005);
  // Below ν·n = 2000 the speed-independent T_L0 branch applies (standstill included).
  const cvt::BearingLoads still = model_.bearing_losses(true, 41.5e-3, 0.0, 3994.0, Tr);
  EXPECT_NEAR(still.T_L0A, 1e-10 * 160.0 * 6.0 * std::pow(48.5, 3.0), 1e-12);
}

// The thesis grid (5 × 5 × 5): F_K/(T/r) spans 8.15 … 10.24 [D] (2 decimals printed, ±0.005);
// invariants η ≤ 1, F_K grows
// with torque, η_PB falls as s grows; the thesis's range η_PB ≈ 94–98 % [T §2.1.2].
TEST_F(CvtModelTest, ThesisGridInvariants) {
  const double S[] = {5, 17.5, 30, 42.5, 55}, T[] = {20, 45, 70, 95, 120};
  double kmin = 1e9, kmax = 0.0, eta_min = 1.0, eta_max = 0.0, k3min = 1e9, k3max = 0.0;
  double kmax_s = 0.0, kmax_T = 0.0;
  int kmax_rpm = 0;
  for (int rpm = 1000; rpm <= 5000; rpm += 1000) {
    for (double tc : T) {
      double previous_eta = 2.0;
      for (double s : S) {
        const cvt::CvtResult r = model_.evaluate(point(s, tc, rpm));
        ASSERT_TRUE(cvt::belt_state_modelled(r.flags));
        EXPECT_EQ(r.flags & cvt::kOutsideValidatedRange, 0u);
        EXPECT_LE(r.eta_PB, 1.0);
        EXPECT_LE(r.eta_SYS, r.eta_PB);
        EXPECT_GT(r.eta_SYS, 0.0);
        EXPECT_LT(r.eta_PB, previous_eta) << "s " << s << " T " << tc << " rpm " << rpm;
        previous_eta = r.eta_PB;
        const double k = r.F_K / r.T_over_r;
        kmin = std::min(kmin, k);
        if (k > kmax) {
          kmax = k;
          kmax_s = s;
          kmax_T = tc;
          kmax_rpm = rpm;
        }
        if (rpm == 3000) {
          k3min = std::min(k3min, k);
          k3max = std::max(k3max, k);
        }
        eta_min = std::min(eta_min, r.eta_PB);
        eta_max = std::max(eta_max, r.eta_PB);
        EXPECT_GE(r.v_KD, 1.0);
        EXPECT_GE(r.v_KC, 1.0);
      }
    }
  }
  EXPECT_NEAR(kmin, 8.15, 0.005);
  EXPECT_NEAR(kmax, 10.24, 0.005);
  // [D]: 8.18 … 9.34 at ω_C = 314 rad/s; the highest at s = 5 mm, T_C = 20 Nm, 5000 rpm.
  EXPECT_NEAR(k3min, 8.18, 0.005);
  EXPECT_NEAR(k3max, 9.34, 0.005);
  EXPECT_EQ(kmax_s, 5.0);
  EXPECT_EQ(kmax_T, 20.0);
  EXPECT_EQ(kmax_rpm, 5000);
  EXPECT_GT(eta_min, 0.93);
  EXPECT_LT(eta_max, 0.985);
}

TEST_F(CvtModelTest, ClampingForceGrowsWithTorque) {
  for (double s : {5.0, 30.0, 55.0}) {
    for (int rpm : {1000, 3000, 5000}) {
      double previous = 0.0;
      for (double tc = 20.0; tc <= 120.0; tc += 5.0) {
        const cvt::CvtResult r = model_.evaluate(point(s, tc, rpm));
        EXPECT_GT(r.F_K, previous) << "s " << s << " rpm " << rpm << " T " << tc;
        previous = r.F_K;
      }
    }
  }
}

// L0 (closed form) against L1: F_K = cos β_D (T/r)/(λ μ_D) = 8.151 T/r, η_PB from the mean slip
// (0.970 at s = 15 mm [A/D]); over the grid L0 underestimates F_K by 0 … 21 % (8.15 vs up to
// 10.24 T/r) and overestimates η_PB by less than 1.5 points (the spec: "good to about ±1 %").
TEST_F(CvtModelTest, L0AgainstL1) {
  cvt::CvtOperatingPoint op = point(15, 35, 3000);
  op.level = cvt::Level::L0;
  const cvt::CvtResult l0 = model_.evaluate(op);
  EXPECT_NEAR(l0.F_K / l0.T_over_r, std::cos(12.0 * std::numbers::pi / 180.0) / 0.12, 1e-12);
  EXPECT_NEAR(l0.eta_PB, 0.970, 0.0005);
  EXPECT_TRUE(std::isnan(l0.sigma[0]));  // no link forces in L0
  for (double s : {5.0, 30.0, 55.0}) {
    for (double tc : {20.0, 70.0, 120.0}) {
      cvt::CvtOperatingPoint q = point(s, tc, 3000);
      const cvt::CvtResult l1 = model_.evaluate(q);
      q.level = cvt::Level::L0;
      const cvt::CvtResult l = model_.evaluate(q);
      const double dF = l.F_K / l1.F_K - 1.0;
      EXPECT_LE(dF, 0.0);
      EXPECT_GT(dF, -0.21);
      EXPECT_GT(l.eta_PB - l1.eta_PB, 0.0);
      EXPECT_LT(l.eta_PB - l1.eta_PB, 0.015);
      EXPECT_DOUBLE_EQ(l.ratio, l1.ratio);
    }
  }
}

// §8.3 clamping-force mode: v_K follows from the applied F_K; the model's F_K is at least the
// applied one and at most one F_P0 step above (≈ 3 %).
TEST_F(CvtModelTest, ClampingForceGivenAboveTheSlipLimit) {
  cvt::CvtOperatingPoint op = point(15, 35, 3000);
  op.clamp = cvt::ClampMode::clamping_force;
  op.F_K_applied = 8000.0;
  const cvt::CvtResult r = model_.evaluate(op);
  EXPECT_EQ(r.flags & cvt::kGrossSlip, 0u);
  EXPECT_GE(r.F_K, 8000.0 - 0.5);  // F_K is rounded to whole newtons as coded
  EXPECT_LT(r.F_K, 8000.0 * 1.03);
  EXPECT_NEAR(r.v_K, 0.12 * 8000.0 / (std::cos(12.0 * std::numbers::pi / 180.0) * r.T_over_r), 1e-12);
  EXPECT_GT(r.eta_PB, 0.95);
}

// Below F_K,min the belt slips grossly: flagged, belt numbers NaN (never a silent number), the
// torque capacity at v_KD = 1 is given.
TEST_F(CvtModelTest, ClampingForceGivenBelowTheSlipLimitIsGrossSlip) {
  cvt::CvtOperatingPoint op = point(15, 35, 3000);
  op.clamp = cvt::ClampMode::clamping_force;
  op.F_K_applied = 5000.0;
  const cvt::CvtResult r = model_.evaluate(op);
  EXPECT_NE(r.flags & cvt::kGrossSlip, 0u);
  EXPECT_FALSE(cvt::belt_state_modelled(r.flags));
  EXPECT_TRUE(std::isnan(r.eta_PB));
  EXPECT_TRUE(std::isnan(r.T_2));
  EXPECT_LT(r.v_K, 1.0);
  const double capacity = 0.0415 * 0.12 * 5000.0 / std::cos(12.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(r.T_C_capacity, capacity, 1e-9);
  EXPECT_LT(r.T_C_capacity, 35.0);
  EXPECT_EQ(cvt::flag_names(r.flags).find("gross_slip") != std::string::npos, true);
}

// Torque causalities: the input-shaft torque T_1 and the output load T_2 of the §6.2 point give
// back T_C = 35 Nm. T_1 = 36.050 Nm and T_2 = 43.730 Nm are printed to 0.001 Nm, so T_C comes
// back to within that (times dT_C/dT_1 ≈ 1 and dT_C/dT_2 ≈ i_TH/η_PB ≈ 0.78).
TEST_F(CvtModelTest, TorqueCausalities) {
  cvt::CvtOperatingPoint op = point(15, 36.050, 3000);
  op.torque_input = cvt::TorqueInput::input_shaft;
  EXPECT_NEAR(model_.evaluate(op).T_C, 35.0, 0.001);
  op.torque = 43.730;
  op.torque_input = cvt::TorqueInput::output_load;
  const cvt::CvtResult r = model_.evaluate(op);
  EXPECT_NEAR(r.T_C, 35.0, 0.001);
  EXPECT_NEAR(r.T_2, 43.730, 1e-6);  // the fixed point closes on the given load
}

// Guards of §8.3: zero torque, negative torque and zero speed.
TEST_F(CvtModelTest, ZeroTorqueIsAnUnloadedBelt) {
  const cvt::CvtResult r = model_.evaluate(point(30, 0.0, 3000));
  EXPECT_NE(r.flags & cvt::kZeroTorque, 0u);
  EXPECT_EQ(r.eta_PB, 1.0);
  EXPECT_EQ(r.F_K, 0.0);
  EXPECT_GT(r.T_L_prim, 0.0);  // the bearings still drag (T_L0)
  EXPECT_NEAR(r.T_1, r.T_L_prim, 1e-12);
}

TEST_F(CvtModelTest, NegativeTorqueIsFlaggedAsReversal) {
  const cvt::CvtResult r = model_.evaluate(point(30, -20.0, 3000));
  EXPECT_NE(r.flags & cvt::kTorqueReversal, 0u);
  EXPECT_FALSE(cvt::belt_state_modelled(r.flags));
  EXPECT_TRUE(std::isnan(r.eta_PB));
  EXPECT_NEAR(r.ratio, 0.5932, 0.0005);  // kinematics still known
}

// T_C > 0 but tiny at speed: the centrifugal clamping's slip loss (F_K ≈ 290 N independent of
// torque) would exceed T_C ω_C, i.e. a negative η_PB. That is a reversal of the output torque.
TEST_F(CvtModelTest, SlipLossAboveTheInputPowerIsFlaggedAsReversal) {
  const cvt::CvtResult r = model_.evaluate(point(30, 0.001, 2865));
  EXPECT_NE(r.flags & cvt::kTorqueReversal, 0u) << cvt::flag_names(r.flags);
  EXPECT_TRUE(std::isnan(r.eta_PB));
  EXPECT_TRUE(std::isnan(r.eta_SYS));
  const cvt::CvtResult ok = model_.evaluate(point(30, 1.0, 2865));  // 1 Nm: η_PB ≈ 0.92, modelled
  EXPECT_TRUE(cvt::belt_state_modelled(ok.flags));
  EXPECT_GT(ok.eta_PB, 0.9);
}

TEST_F(CvtModelTest, ZeroSpeedHasNoSlipLoss) {
  const cvt::CvtResult r = model_.evaluate(point(30, 70, 0));
  EXPECT_NE(r.flags & cvt::kZeroSpeed, 0u);
  EXPECT_TRUE(cvt::belt_state_modelled(r.flags));
  EXPECT_EQ(r.eta_PB, 1.0);
  EXPECT_EQ(r.P_loss_belt, 0.0);
  EXPECT_GT(r.F_K, 8.0 * r.T_over_r);  // clamping is still needed to hold the torque
  EXPECT_EQ(r.omega_D, 0.0);
}

TEST_F(CvtModelTest, OutsideTheValidatedRangeIsFlaggedButComputed) {
  const cvt::CvtResult r = model_.evaluate(point(60, 150, 6000));
  EXPECT_NE(r.flags & cvt::kOutsideValidatedRange, 0u);
  EXPECT_TRUE(cvt::belt_state_modelled(r.flags));
  EXPECT_GT(r.eta_PB, 0.9);
}

TEST_F(CvtModelTest, BadInputsThrowWithAMessage) {
  auto message = [&](cvt::CvtOperatingPoint op) -> std::string {
    try {
      model_.evaluate(op);
    } catch (const cvt::CvtInputError& e) {
      return e.what();
    }
    return "";
  };
  cvt::CvtOperatingPoint op = point(30, 70, 3000);
  op.s = std::nan("");
  EXPECT_NE(message(op).find("finite"), std::string::npos);
  op = point(-1, 70, 3000);
  EXPECT_NE(message(op).find("s must be > 0"), std::string::npos);
  op = point(0, 70, 3000);
  EXPECT_NE(message(op).find("s must be > 0"), std::string::npos);
  op = point(30, 70, -100);
  EXPECT_NE(message(op).find("speed"), std::string::npos);
  op = point(30, 70, 3000);
  op.clamp = cvt::ClampMode::clamping_force;
  op.F_K_applied = -10.0;
  EXPECT_NE(message(op).find("clamping force must be >= 0"), std::string::npos);
  op = point(30, 70, 3000);
  op.v_K = 0.0;
  EXPECT_NE(message(op).find("v_K"), std::string::npos);
  op = point(30, std::numeric_limits<double>::infinity(), 3000);
  EXPECT_NE(message(op).find("finite"), std::string::npos);
  cvt::CvtParams bad;
  bad.filling_degree = 1.2;
  EXPECT_THROW(cvt::CvtModel{bad}, cvt::CvtInputError);
}

// A tabulated model gives the same operating point at a table node and a continuous ratio
// between nodes (no search per step).
TEST(CvtModelTable, TabulatedModelMatchesTheSearchedOne) {
  cvt::CvtModel searched, tabulated;
  tabulated.tabulate_shapes(5e-3, 55e-3, 101);
  const cvt::CvtResult a = searched.evaluate(point(30, 70, 3000));
  const cvt::CvtResult b = tabulated.evaluate(point(30, 70, 3000));
  // The table node's s differs from 30 mm by rounding only: the same point to rounding.
  EXPECT_NEAR(a.ratio, b.ratio, 1e-12);
  EXPECT_EQ(a.F_K, b.F_K);
  EXPECT_NEAR(a.eta_SYS, b.eta_SYS, 1e-12);
  const cvt::CvtResult c = tabulated.evaluate(point(30.23, 70, 3000));
  EXPECT_LT(c.ratio, b.ratio);
  EXPECT_NEAR(c.ratio, searched.evaluate(point(30.23, 70, 3000)).ratio, 0.0002);  // CC1's i_TH tolerance
}
