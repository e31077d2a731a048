#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <cstring>

#include "controller/tick.hpp"

using namespace palprig;

namespace {

// Left half soft (0), right half hard (1), 100 x 100 mm.
MapScene half_hard_scene() {
  std::vector<float> v(std::size_t{11} * 11);
  for (int r = 0; r < 11; ++r)
    for (int c = 0; c < 11; ++c) v[r * 11 + c] = c >= 6 ? 1.0f : 0.0f;
  return MapScene(StiffnessMap(11, 11, 100, 100, v), MapSampling::nearest);
}

TouchSample press(double t, double x, double y, double force = 2.0) { return {t, x, y, force, true}; }

}  // namespace

TEST(Tick, FingerOverHardTissueGetsThePaperPressure) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  cfg.safety.slew_kPa_per_s = 1e9;
  TickState st = make_tick_state(cfg);
  // Pen at x = 50 (soft); finger 1 at x = 66 (hard); finger 2 at y + 16 (soft).
  const TickResult r = tick(st, cfg, scene, press(0, 50, 20), 0);
  EXPECT_NEAR(r.setpoint_kPa[0], 0.0, 1e-9);
  EXPECT_NEAR(r.setpoint_kPa[1], 11.75, 1e-9);  // reference press over a hard nodule
  EXPECT_NEAR(r.setpoint_kPa[2], 0.0, 1e-9);
  EXPECT_FLOAT_EQ(r.record.stiffness[1], 1.0f);
  EXPECT_TRUE(r.record.flags & kInContact);
  EXPECT_EQ(r.record.fault, FaultCode::none);
}

TEST(Tick, LiftedPenGivesZeroPressure) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  TickState st = make_tick_state(cfg);
  TouchSample s = press(0, 80, 20);
  s.in_contact = false;
  const TickResult r = tick(st, cfg, scene, s, 0);
  for (double p : r.setpoint_kPa) EXPECT_EQ(p, 0.0);
  EXPECT_FALSE(r.record.flags & kInContact);
}

TEST(Tick, NeverAboveMaxWhateverTheModelsAsk) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  cfg.safety.p_max_kPa = 15.0;
  cfg.safety.slew_kPa_per_s = 1e9;
  cfg.actuators.fill(ActuatorModel{0.01, 0.0});  // absurdly soft actuator: asks for huge pressures
  TickState st = make_tick_state(cfg);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-20, 120), force(0, 50);
  for (int k = 0; k < 5000; ++k) {
    const TickResult r = tick(st, cfg, scene, press(k * 1e-3, pos(rng), pos(rng), force(rng)), k * 1e-3);
    for (double p : r.setpoint_kPa) {
      ASSERT_TRUE(std::isfinite(p));
      ASSERT_GE(p, 0.0);
      ASSERT_LE(p, 15.0);
    }
  }
}

TEST(Tick, SlewLimitBoundsEachStep) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  cfg.safety.slew_kPa_per_s = 1000.0;  // 1 kPa per 1 ms tick
  TickState st = make_tick_state(cfg);
  tick(st, cfg, scene, press(0, 0, 20), 0);                                // all soft
  const TickResult r = tick(st, cfg, scene, press(0.001, 90, 20), 0.001);  // pen jumps onto hard tissue
  EXPECT_NEAR(r.setpoint_kPa[0], 1.0, 1e-9);
  EXPECT_TRUE(r.record.flags & kSlewLimited);
  EXPECT_NEAR(r.record.target_kPa[0], 11.75, 1e-6);
}

TEST(Tick, NonFiniteSampleVentsAndLatches) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  cfg.safety.slew_kPa_per_s = 1e9;
  TickState st = make_tick_state(cfg);
  EXPECT_GT(tick(st, cfg, scene, press(0, 90, 20), 0).setpoint_kPa[0], 10.0);
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()};
  for (double b : bad) {
    TickState s2 = st;
    const TickResult r = tick(s2, cfg, scene, press(0.001, b, 20), 0.001);
    for (double p : r.setpoint_kPa) EXPECT_EQ(p, 0.0);
    // A NaN position is reported as a bad position, not as a bad force.
    EXPECT_EQ(r.record.fault, FaultCode::bad_position);
    EXPECT_TRUE(r.record.flags & kVented);
    // Latched: a good sample afterwards still vents.
    const TickResult after = tick(s2, cfg, scene, press(0.002, 90, 20), 0.002);
    for (double p : after.setpoint_kPa) EXPECT_EQ(p, 0.0);
    EXPECT_EQ(s2.fault, FaultCode::bad_position);
    TickState s4 = st;
    EXPECT_EQ(tick(s4, cfg, scene, press(0.001, 90, 20, b), 0.001).record.fault, FaultCode::bad_sample);
    TickState s5 = st;
    EXPECT_EQ(tick(s5, cfg, scene, press(b, 90, 20), 0.001).record.fault, FaultCode::bad_time);
  }
  TickState s3 = st;
  EXPECT_EQ(tick(s3, cfg, scene, press(0.001, 90, 20, -1.0), 0.001).record.fault, FaultCode::bad_sample);
  EXPECT_NE(std::string(to_string(FaultCode::bad_position)).find("position"), std::string::npos);
}

TEST(Tick, NonFiniteModelOutputVents) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  cfg.actuators[1] = ActuatorModel{0.0, 0.0};  // degenerate line: division by zero
  TickState st = make_tick_state(cfg);
  const TickResult r = tick(st, cfg, scene, press(0, 50, 20), 0);
  EXPECT_EQ(r.record.fault, FaultCode::non_finite_target);
  for (double p : r.setpoint_kPa) EXPECT_EQ(p, 0.0);
}

TEST(Tick, StaleInputVents) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  cfg.safety.max_input_age_s = 0.05;
  TickState st = make_tick_state(cfg);
  EXPECT_EQ(tick(st, cfg, scene, press(0.0, 90, 20), 0.04).record.fault, FaultCode::none);
  const TickResult r = tick(st, cfg, scene, press(0.0, 90, 20), 0.06);
  EXPECT_EQ(r.record.fault, FaultCode::input_stale);
  for (double p : r.setpoint_kPa) EXPECT_EQ(p, 0.0);
}

// No padding in a record: its size is the sum of its fields' (tick, t_s, pen, the four per-finger
// pressures, wake-up and I/O times, fault, flags, reserved, finger positions and forces, vents,
// reserved, drag), so two records with the same fields have the same bytes.
static_assert(sizeof(TelemetryRecord) == 8 + 8 + 3 * 4 + 4 * kFingerCount * 4 + 2 * 4 + 1 + 1 + 2 +
                                             3 * kFingerCount * 4 + kFingerCount + 1 + 2 * kFingerCount * 4);

TEST(Tick, DeterministicForTheSameInputs) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  cfg.hysteresis_model[0].linear_weight = 0.7;  // exercise the compensation stage too
  TickState a = make_tick_state(cfg), b = make_tick_state(cfg);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(0, 100), force(0, 5);
  for (int k = 0; k < 2000; ++k) {
    const TouchSample s = press(k * 1e-3, pos(rng), pos(rng), force(rng));
    const TickResult ra = tick(a, cfg, scene, s, k * 1e-3);
    const TickResult rb = tick(b, cfg, scene, s, k * 1e-3);
    ASSERT_EQ(ra.setpoint_kPa, rb.setpoint_kPa);
    // Bit for bit: a record has no padding (the static_assert above), and its floats compared by
    // their bits, not by ==, is what "deterministic" means here.
    // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): the floats' bits are the point
    ASSERT_EQ(0, std::memcmp(&ra.record, &rb.record, sizeof ra.record));
  }
}

TEST(Tick, HysteresisInverseIsApplied) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  cfg.safety.slew_kPa_per_s = 1e9;
  PrandtlIshlinskii forward;
  forward.linear_weight = 0.5;  // the actuator gives half of what is commanded
  cfg.hysteresis_model.fill(forward);
  TickState st = make_tick_state(cfg);
  const TickResult r = tick(st, cfg, scene, press(0, 50, 20), 0);
  EXPECT_NEAR(r.setpoint_kPa[1], 2 * 11.75, 1e-9);
}

TEST(TickDirect, PassesTheSameSafetyStage) {
  TickConfig cfg;
  cfg.safety.p_max_kPa = 25;
  cfg.safety.slew_kPa_per_s = 1e9;
  TickState st = make_tick_state(cfg);
  TickResult r = tick_direct(st, cfg, {0.0, 10.0, 30.0}, 0);
  EXPECT_EQ(r.setpoint_kPa[0], 0.0);
  EXPECT_EQ(r.setpoint_kPa[1], 10.0);
  EXPECT_EQ(r.setpoint_kPa[2], 25.0);
  EXPECT_TRUE(r.record.flags & kClamped);
  r = tick_direct(st, cfg, {0.0, NAN, 5.0}, 0.001);
  EXPECT_EQ(r.record.fault, FaultCode::non_finite_target);
  for (double p : r.setpoint_kPa) EXPECT_EQ(p, 0.0);
}

// The first tick was once not slew-limited, so a pen already pressed on a tumor when a run
// started sent the full target to vented regulators in one tick.
TEST(Tick, FirstTickRisesFromVentedByOneSlewStep) {
  const auto scene = half_hard_scene();
  TickConfig cfg;  // 2000 kPa/s over the nominal 1 ms period: 2 kPa
  TickState st = make_tick_state(cfg);
  const TickResult r = tick(st, cfg, scene, press(0, 50, 20), 0);
  EXPECT_NEAR(r.record.target_kPa[1], 11.75, 1e-6);
  EXPECT_NEAR(r.setpoint_kPa[1], 2.0, 1e-9);
  EXPECT_TRUE(r.record.flags & kSlewLimited);
  cfg.period_s = 0.004;  // a slower loop allows a larger first step
  TickState slow = make_tick_state(cfg);
  EXPECT_NEAR(tick(slow, cfg, scene, press(0, 50, 20), 0).setpoint_kPa[1], 8.0, 1e-9);
  // tick_direct passes the same stage.
  TickState direct = make_tick_state(cfg);
  EXPECT_NEAR(tick_direct(direct, cfg, {30, 0, 0}, 0).setpoint_kPa[0], 8.0, 1e-9);
}

TEST(Tick, RestartFromVentedRisesAgainUnderTheSlewLimit) {
  const auto scene = half_hard_scene();
  TickConfig cfg;
  TickState st = make_tick_state(cfg);
  double t = 0;
  for (int k = 0; k < 20; ++k, t += 0.001) tick(st, cfg, scene, press(t, 50, 20), t);
  EXPECT_NEAR(st.last_setpoint_kPa[1], 11.75, 1e-9);
  st.restart_from_vented();  // e.g. a link outage vented the channels
  const TickResult r = tick(st, cfg, scene, press(t, 50, 20), t);
  EXPECT_NEAR(r.setpoint_kPa[1], 2.0, 1e-9);
  EXPECT_EQ(r.record.fault, FaultCode::none);
}

TEST(TickStages, HysteresisInverseThenSafetyAreTwoStages) {
  TickConfig cfg;
  cfg.safety.p_max_kPa = 25;
  cfg.safety.slew_kPa_per_s = 1e9;
  PrandtlIshlinskii forward;
  forward.linear_weight = 0.5;
  cfg.hysteresis_model.fill(forward);
  TickState st = make_tick_state(cfg);
  // The inverse doubles the target; it does not clamp (that is the safety stage's job).
  const ChannelPressures command = hysteresis_inverse_stage(st, {5, 10, 20});
  EXPECT_NEAR(command[0], 10.0, 1e-9);
  EXPECT_NEAR(command[2], 40.0, 1e-9);
  TickResult out;
  safety_stage(st, cfg, command, 0, out);
  EXPECT_NEAR(out.setpoint_kPa[0], 10.0, 1e-9);
  EXPECT_NEAR(out.setpoint_kPa[1], 20.0, 1e-9);
  EXPECT_EQ(out.setpoint_kPa[2], 25.0);
  EXPECT_TRUE(out.record.flags & kClamped);
  // A non-finite command (a broken inverse) vents and latches.
  TickResult bad;
  safety_stage(st, cfg, {1, NAN, 1}, 0.001, bad);
  EXPECT_EQ(bad.setpoint_kPa, (ChannelPressures{0, 0, 0}));
  EXPECT_EQ(st.fault, FaultCode::non_finite_target);
  // Once faulted, the inverse stage leaves its models alone.
  EXPECT_EQ(hysteresis_inverse_stage(st, {5, 5, 5})[0], 5.0);
}
