#include <boost/test/unit_test.hpp>

#include <cmath>

#include "pounding/excitation/ground_motion.hpp"
#include "pounding/input_error.hpp"

namespace tt = boost::test_tools;
using namespace pounding::excitation;

namespace {

/// a_i = i (so the value at a time says where it was read from), t_i = i·dt.
RecordSamples ramp(std::size_t count, double dt) {
  RecordSamples samples;
  for (std::size_t i = 0; i < count; ++i) {
    samples.time_s.push_back(static_cast<double>(i) * dt);
    samples.accel.push_back(static_cast<double>(i));
  }
  return samples;
}

ExcitationSpec spec_in(AccelUnits units) {
  ExcitationSpec spec;
  spec.file = "synthetic";
  spec.units = units;
  return spec;
}

}  // namespace

BOOST_AUTO_TEST_CASE(InterpolatesLinearlyAndIsZeroOutsideTheRecord) {
  const GroundMotion motion({0.0, 0.1, 0.3}, {0.0, 2.0, -2.0}, 0.0);
  BOOST_TEST(motion.accel_at(0.05) == 1.0, tt::tolerance(1e-14));
  BOOST_TEST(motion.accel_at(0.2) == 0.0, tt::tolerance(1e-14));
  BOOST_TEST(motion.accel_at(0.3) == -2.0);
  BOOST_TEST(motion.accel_at(0.31) == 0.0);
  BOOST_TEST(motion.accel_at(-0.01) == 0.0);
  BOOST_TEST(motion.peak_mps2() == 2.0);
  BOOST_TEST(motion.peak_time_s() == 0.1);
}

BOOST_AUTO_TEST_CASE(ConvertsUnitsToMetresPerSecondSquared) {
  BOOST_TEST(process_record(ramp(3, 0.01), spec_in(AccelUnits::cm_per_s2)).accel_mps2()[2] == 0.02,
             tt::tolerance(1e-15));
  ExcitationSpec in_g = spec_in(AccelUnits::g);
  in_g.g_mps2 = 9.80665;
  BOOST_TEST(process_record(ramp(3, 0.01), in_g).accel_mps2()[2] == 2 * 9.80665, tt::tolerance(1e-15));
  // US customary records: the inch is 0.0254 m and the foot 0.3048 m exactly.
  BOOST_TEST(process_record(ramp(3, 0.01), spec_in(AccelUnits::in_per_s2)).accel_mps2()[2] == 2 * 0.0254,
             tt::tolerance(1e-15));
  BOOST_TEST(process_record(ramp(3, 0.01), spec_in(AccelUnits::ft_per_s2)).accel_mps2()[2] == 2 * 0.3048,
             tt::tolerance(1e-15));
  BOOST_TEST((parse_accel_units("in/s2") == AccelUnits::in_per_s2));
  BOOST_TEST(!parse_accel_units("in/s^2").has_value());
}

BOOST_AUTO_TEST_CASE(TimeStepOverrideRespacesTheSamples) {
  ExcitationSpec spec = spec_in(AccelUnits::m_per_s2);
  spec.dt_override_s = 0.05;
  const GroundMotion motion = process_record(ramp(11, 0.02), spec);
  BOOST_TEST(motion.end_s() == 0.5, tt::tolerance(1e-14));
  BOOST_TEST(motion.accel_at(0.075) == 1.5, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(CutInterpolatesItsEndsAndStartsAtZero) {
  ExcitationSpec spec = spec_in(AccelUnits::m_per_s2);
  spec.start_s = 0.015;
  spec.duration_s = 0.04;  // [0.015, 0.055] of a record sampled every 0.01 s
  const GroundMotion motion = process_record(ramp(11, 0.01), spec);
  const std::vector<double> expected_t = {0.0, 0.005, 0.015, 0.025, 0.035, 0.04};
  const std::vector<double> expected_a = {1.5, 2, 3, 4, 5, 5.5};
  BOOST_TEST_REQUIRE(motion.time_s().size() == expected_t.size());
  for (std::size_t i = 0; i < expected_t.size(); ++i) {
    BOOST_TEST(motion.time_s()[i] == expected_t[i], tt::tolerance(1e-12));
    BOOST_TEST(motion.accel_mps2()[i] == expected_a[i], tt::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(ScalingToPeakSetsTheLargestMagnitude) {
  RecordSamples samples{{0, 1, 2, 3}, {0.1, -0.4, 0.3, 0.2}};
  ExcitationSpec spec = spec_in(AccelUnits::g);
  spec.scale_to_pga_g = 0.32;
  const GroundMotion motion = process_record(samples, spec);
  BOOST_TEST(motion.accel_mps2()[1] == -0.32 * 9.81, tt::tolerance(1e-14));  // sign kept
  BOOST_TEST(motion.accel_mps2()[2] == 0.24 * 9.81, tt::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(DirectionIsStoredInRadians) {
  ExcitationSpec spec = spec_in(AccelUnits::g);
  spec.direction_deg = 30.0;
  BOOST_TEST(process_record(ramp(3, 0.01), spec).direction_rad() == M_PI / 6, tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(PaperReadingKeeps245SamplesScaledTo032g) {
  ExcitationSpec spec = spec_in(AccelUnits::g);
  spec.file = POUNDING_EXAMPLES_DIR "/records/elcentro1940_ns_0.02s.AT2";
  spec.dt_override_s = 0.05;
  spec.duration_s = 12.2;
  spec.scale_to_pga_g = 0.32;
  const GroundMotion motion = load_ground_motion(spec);
  BOOST_TEST(motion.time_s().size() == 245u);
  BOOST_TEST(motion.end_s() == 12.2, tt::tolerance(1e-12));
  BOOST_TEST(motion.peak_mps2() == 0.32 * 9.81, tt::tolerance(1e-14));
  BOOST_TEST(motion.peak_time_s() == 101 * 0.05, tt::tolerance(1e-12));  // file peak is sample 101
}

BOOST_AUTO_TEST_CASE(BadProcessingOptionsNameTheirKey) {
  ExcitationSpec spec = spec_in(AccelUnits::g);
  spec.dt_override_s = 0.0;
  BOOST_CHECK_EXCEPTION(process_record(ramp(3, 0.01), spec), pounding::InputError,
                        [](const auto& e) { return e.key() == "excitation.dt_s" && e.value() == "0"; });
  spec = spec_in(AccelUnits::g);
  spec.start_s = 5.0;
  BOOST_CHECK_EXCEPTION(process_record(ramp(3, 0.01), spec), pounding::InputError,
                        [](const auto& e) { return e.key() == "excitation.start_s"; });
}

BOOST_AUTO_TEST_CASE(NonFiniteTimeIsRefusedWithoutReadingOutsideTheSamples) {
  // A diverged solver asked for a_g(NaN): NaN passed every range test and read past the end.
  const GroundMotion motion({0.0, 0.1, 0.3}, {0.0, 2.0, -2.0}, 0.0);
  BOOST_CHECK_THROW(motion.accel_at(std::nan("")), NonFiniteTime);
  BOOST_CHECK_THROW(motion.accel_at(INFINITY), NonFiniteTime);
  BOOST_CHECK_THROW(motion.accel_at(-INFINITY), NonFiniteTime);
}

namespace {

/// The InputError that processing `samples` with `spec` throws; fails the test if none is.
pounding::InputError refusal(const RecordSamples& samples, const ExcitationSpec& spec) {
  try {
    process_record(samples, spec);
  } catch (const pounding::InputError& error) {
    return error;
  }
  BOOST_FAIL("no error");
  return pounding::InputError("", "", "");
}

/// The InputError that `work` throws; fails the test if none is.
template <class Work>
pounding::InputError refusal_of(Work work) {
  try {
    work();
  } catch (const pounding::InputError& error) {
    return error;
  }
  BOOST_FAIL("no error");
  return pounding::InputError("", "", "");
}

bool names(const pounding::InputError& e, const std::string& key, const std::string& value, const std::string& limit) {
  const std::string text = e.what();
  const bool ok = e.key() == key && text.find(value) != std::string::npos && text.find(limit) != std::string::npos;
  if (!ok) BOOST_TEST_MESSAGE("unexpected message: " << text);
  return ok;
}

}  // namespace

BOOST_AUTO_TEST_CASE(RecordTimesOutsideThePhysicalRangeAreRefused) {
  RecordSamples negative{{-1.0, 0.0, 1.0}, {0, 1, 0}};
  BOOST_TEST(names(refusal(negative, spec_in(AccelUnits::g)), "excitation.file", "-1", "[0, 3600] s"));
  RecordSamples epoch{{0.0, 1e20}, {0, 1}};
  BOOST_TEST(names(refusal(epoch, spec_in(AccelUnits::g)), "excitation.file", "1e+20", "[0, 3600] s"));
  ExcitationSpec huge_dt = spec_in(AccelUnits::g);
  huge_dt.dt_override_s = 1e306;
  BOOST_TEST(names(refusal(ramp(3, 0.01), huge_dt), "excitation.dt_s", "1e+306", "[1e-05, 1] s"));
}

BOOST_AUTO_TEST_CASE(DurationBeyondTheRecordIsRefused) {
  ExcitationSpec spec = spec_in(AccelUnits::g);
  spec.duration_s = 1.0;  // the ramp ends at 0.1 s
  BOOST_TEST(names(refusal(ramp(11, 0.01), spec), "excitation.duration_s", "1", "give at most that"));
  spec.duration_s = 0.1;  // exactly the record: accepted
  BOOST_TEST(process_record(ramp(11, 0.01), spec).end_s() == 0.1, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(AQuietTailAppendsZeroSamplesAtTheRecordsSpacingAfterTheScaling) {
  ExcitationSpec spec = spec_in(AccelUnits::m_per_s2);
  spec.scale_to_pga_g = 1.0;      // the ramp's peak, 10 m/s2 at 0.1 s, becomes g
  spec.free_vibration_s = 0.025;  // not a whole number of intervals: three zero samples cover it
  const GroundMotion motion = process_record(ramp(11, 0.01), spec);
  BOOST_TEST(motion.time_s().size() == 14u);
  BOOST_TEST(motion.end_s() == 0.13, tt::tolerance(1e-12));
  BOOST_TEST(motion.accel_mps2()[10] == 9.81, tt::tolerance(1e-14));     // scaled as before
  BOOST_TEST(motion.accel_at(0.105) == 9.81 / 2, tt::tolerance(1e-12));  // linear to zero over one interval
  BOOST_TEST(motion.accel_at(0.125) == 0.0);
  BOOST_TEST(motion.peak_mps2() == 9.81, tt::tolerance(1e-14));
  spec.free_vibration_s = 0.03;  // a whole number: no extra sample
  BOOST_TEST(process_record(ramp(11, 0.01), spec).time_s().size() == 14u);
  spec.free_vibration_s = -1.0;
  BOOST_TEST(names(refusal(ramp(11, 0.01), spec), "excitation.free_vibration_s", "-1", "[0, 600] s"));
  spec.free_vibration_s = 601.0;
  BOOST_TEST(names(refusal(ramp(11, 0.01), spec), "excitation.free_vibration_s", "601", "[0, 600] s"));
}

BOOST_AUTO_TEST_CASE(AbsurdScalingAndGravityAreRefused) {
  ExcitationSpec spec = spec_in(AccelUnits::g);
  spec.scale_factor = 1e308;
  BOOST_TEST(names(refusal(ramp(3, 0.01), spec), "excitation.scale_factor", "1e+308", "limit of 10 g"));
  spec = spec_in(AccelUnits::g);
  spec.g_mps2 = 1e308;
  BOOST_TEST(names(refusal(ramp(3, 0.01), spec), "excitation.g_mps2", "1e+308", "[9, 10.5] m/s2"));
  spec = spec_in(AccelUnits::g);
  spec.direction_deg = 1e300;
  BOOST_TEST(names(refusal(ramp(3, 0.01), spec), "excitation.direction_deg", "1e+300", "[-360, 360] deg"));
  spec = spec_in(AccelUnits::g);
  spec.scale_to_pga_g = 50.0;
  BOOST_TEST(names(refusal(ramp(3, 0.01), spec), "excitation.scale_to_pga_g", "50", "(0, 10] g"));
  spec = spec_in(AccelUnits::g);  // a record in cm/s² read as g peaks far above 10 g
  BOOST_TEST(names(refusal(RecordSamples{{0, 1}, {0, 300}}, spec), "excitation.units", "300", "limit of 10 g"));
}

namespace {

/// H1 on `h1` with H2 on `h2`, a pair (spec.second set, its file "synthetic-2").
GroundMotion pair_of(const RecordSamples& h1, const RecordSamples& h2, ExcitationSpec spec) {
  spec.second = SecondComponentSpec{.file = "synthetic-2", .read = {}, .units = spec.units, .dt_override_s = {}};
  return process_record(h1, spec, h2);
}

}  // namespace

BOOST_AUTO_TEST_CASE(APairIsBothRecordsOnTheUnionOfTheirTimesOverTheSpanBothCover) {
  // H1 every 0.02 s to 0.2 s, H2 every 0.03 s to 0.15 s: the pair spans [0, 0.15] on H1's times
  // and H2's own, each component linear between its own samples (a_i = i: value = t / dt).
  const GroundMotion motion = pair_of(ramp(11, 0.02), ramp(6, 0.03), spec_in(AccelUnits::m_per_s2));
  BOOST_TEST(motion.is_pair());
  const std::vector<double> expected{0.0, 0.02, 0.03, 0.04, 0.06, 0.08, 0.09, 0.10, 0.12, 0.14, 0.15};
  BOOST_TEST(motion.time_s() == expected, tt::tolerance(1e-12) << tt::per_element());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    BOOST_TEST(motion.accel_mps2(0)[i] == expected[i] / 0.02, tt::tolerance(1e-9));
    BOOST_TEST(motion.accel_mps2(1)[i] == expected[i] / 0.03, tt::tolerance(1e-9));
  }
  // A time of H2 within round-off of one of H1 (0.06 = 3 x 0.02 = 2 x 0.03) is H1's, not a sliver.
  BOOST_TEST(motion.time_s()[4] == 3 * 0.02);
  BOOST_TEST(motion.accel_at(0.05, 1) == 0.05 / 0.03, tt::tolerance(1e-12));
  BOOST_TEST(motion.accel_at(0.2, 1) == 0.0);  // past the pair's end
}

BOOST_AUTO_TEST_CASE(APairIsScaledByOneFactorFromItsLargerPeak) {
  ExcitationSpec spec = spec_in(AccelUnits::m_per_s2);
  spec.scale_to_pga_g = 0.5;
  spec.g_mps2 = 10.0;
  // H1 peaks at 4 (at 0.04 s), H2 at -8 within the common span [0, 0.04] (its -10 lies beyond).
  const RecordSamples h2{{0.0, 0.01, 0.02, 0.03, 0.04, 0.05}, {0.0, -2.0, -4.0, -6.0, -8.0, -10.0}};
  const GroundMotion motion = pair_of(ramp(5, 0.01), h2, spec);
  BOOST_TEST(motion.peak_mps2(1) == 5.0, tt::tolerance(1e-14));
  BOOST_TEST(motion.peak_mps2(0) == 2.5, tt::tolerance(1e-14));  // the ratio kept: 4/8 of 0.5 g
  BOOST_TEST(motion.end_s() == 0.04, tt::tolerance(1e-14));      // H1 ends first
}

BOOST_AUTO_TEST_CASE(APairThatSharesNoTimeOrBadSecondKeysAreRefusedByName) {
  RecordSamples late = ramp(3, 0.01);
  for (double& t : late.time_s) t += 1.0;
  BOOST_TEST(names(refusal_of([&] { pair_of(ramp(3, 0.01), late, spec_in(AccelUnits::g)); }), "excitation.second.file",
                   "synthetic-2", "shares no time span"));
  ExcitationSpec spec = spec_in(AccelUnits::g);
  spec.second = SecondComponentSpec{.file = "synthetic-2",
                                    .read = {.format = RecordFormat::columns, .time_column = 2, .accel_column = 2},
                                    .units = AccelUnits::g,
                                    .dt_override_s = {}};
  BOOST_TEST(names(refusal_of([&] { process_record(ramp(3, 0.01), spec, ramp(3, 0.01)); }),
                   "excitation.second.accel_column", "2", "excitation.second.time_column"));
  spec.second = SecondComponentSpec{.file = "synthetic-2", .read = {}, .units = AccelUnits::g, .dt_override_s = 1e-9};
  BOOST_TEST(names(refusal_of([&] { process_record(ramp(3, 0.01), spec, ramp(3, 0.01)); }), "excitation.second.dt_s",
                   "1e-09", "[1e-05, 1] s"));
  spec.second =
      SecondComponentSpec{.file = "synthetic-2", .read = {}, .units = AccelUnits::g, .dt_override_s = {}};  // 300 g
  BOOST_TEST(names(refusal_of([&] {
                     process_record(ramp(3, 0.01), spec, RecordSamples{{0, 0.02}, {0, 300}});
                   }),
                   "excitation.second.units", "", "limit of 10 g"));
}

BOOST_AUTO_TEST_CASE(TheDesignSpectrumHasItsFourBranches) {
  const DesignSpectrum asce{.sds_g = 1.0, .sd1_g = 0.6, .tl_s = 8.0};  // T0 = 0.12 s, TS = 0.6 s
  BOOST_TEST(asce.sa_g(0.0) == 0.4);
  BOOST_TEST(asce.sa_g(0.06) == 0.7, tt::tolerance(1e-14));
  BOOST_TEST(asce.sa_g(0.3) == 1.0);
  BOOST_TEST(asce.sa_g(1.2) == 0.5, tt::tolerance(1e-14));
  BOOST_TEST(asce.sa_g(10.0) == 0.6 * 8.0 / 100.0, tt::tolerance(1e-14));
  const SaScaling range = parse_sa_scaling("asce7(SDS=1.0,SD1=0.6)@0.2-2T1", "k");
  BOOST_TEST(range.design->tl_s == 8.0);
  BOOST_TEST(range.building == 3);
  BOOST_TEST((range.from == 0.2 && range.to == 2.0));
  BOOST_TEST(parse_sa_scaling("asce7(SDS=1,SD1=0.6,TL=4)@0.2T1-2T1", "k").from == 0.2);
  SaScaling seconds = parse_sa_scaling("asce7(SDS=1,SD1=0.6)@0.1-1.5s", "k");
  const std::vector<double> periods = seconds.periods_s();
  BOOST_TEST(periods.size() == static_cast<std::size_t>(kSaRangePeriods));
  BOOST_TEST(periods.front() == 0.1, tt::tolerance(1e-14));
  BOOST_TEST(periods.back() == 1.5, tt::tolerance(1e-14));
  for (const char* bad : {"asce7(SDS=1)@0.2-2T1", "asce7(SDS=1,SD1=0.6)@2-0.2T1", "asce7(SDS=1,SD1=0.6,X=1)@0.2-2T1",
                          "asce7(SDS=0,SD1=0.6)@0.2-2T1", "asce7(SDS=1,SD1=0.6,TL=50)@0.2-2T1",
                          "asce7(SDS=1,SD1=0.6)@0.001-1s", "asce7(SDS=1,SD1=0.6)@T1", "asce7SDS=1@0.2-2T1"}) {
    BOOST_TEST(
        names(refusal_of([&] { parse_sa_scaling(bad, "excitation.scale_to_sa"); }), "excitation.scale_to_sa", bad, ""),
        bad);
  }
}

BOOST_AUTO_TEST_CASE(SpectralScalingIsReadAsTargetAtPeriod) {
  const SaScaling at_t1 = parse_sa_scaling("0.5g@T1", "k");
  BOOST_TEST(at_t1.target_g == 0.5);
  BOOST_TEST(at_t1.building == 3);
  BOOST_TEST(!at_t1.period_s.has_value());
  BOOST_TEST(parse_sa_scaling("1g@B2", "k").building == 2);
  BOOST_TEST(*parse_sa_scaling("0.25g@1.2s", "k").period_s == 1.2);
  BOOST_TEST(*parse_sa_scaling("0.25g@0.3", "k").period_s == 0.3);
  for (const char* bad : {"0.5@T1", "g@T1", "0.5g@", "0.5g@T2", "0.5g@B3", "0.5g@1.2ss", " 0.5g@1", "0.5g@nan",
                          "0.5g@inf", "0g@T1", "11g@T1", "0.5g@20", "0.5g@0.001", "0.5gT1"}) {
    BOOST_TEST(
        names(refusal_of([&] { parse_sa_scaling(bad, "excitation.scale_to_sa"); }), "excitation.scale_to_sa", bad, ""),
        bad);
  }
  // One scaling at a time; a building's period must be resolved before the record is read.
  ExcitationSpec spec = spec_in(AccelUnits::g);
  spec.scale_to_sa = parse_sa_scaling("0.5g@T1", "excitation.scale_to_sa");
  BOOST_TEST(names(refusal(ramp(3, 0.01), spec), "excitation.scale_to_sa", "0.5g@T1", "read with its scene"));
  spec.scale_to_pga_g = 0.3;
  BOOST_TEST(names(refusal(ramp(3, 0.01), spec), "excitation.scale_to_sa", "0.5g@T1", "give one scaling"));
}
