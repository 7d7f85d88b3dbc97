#include <boost/test/unit_test.hpp>

#include <string>
#include <vector>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/scene_reader.hpp"

// [output] history and peaks (OutputSelection): the recorder only reads the solution, so leaving
// outputs out changes no impact, no energy and no statistic, bit for bit; each peak group and the
// history come out the same whatever else is recorded with them. On the paper scene, whose 45
// impacts and six holds exercise events, holds and restarts, for the exact path, CVODE BDF and HHT.

namespace tt = boost::test_tools;
using namespace pounding;

namespace {

analysis::Scene paper(const std::string& method, bool history, std::vector<std::string> peaks) {
  analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  scene.solver.method = method;
  scene.output.history = history;
  scene.output.peaks = std::move(peaks);
  scene.validate();
  return scene;
}

const std::vector<std::string> kAll{"displacements", "accelerations", "drifts"};

void require_same_peak(const solvers::Peak& a, const solvers::Peak& b) {
  BOOST_TEST(a.value == b.value);
  BOOST_TEST(a.t_s == b.t_s);
}

void require_same_peaks(const std::vector<solvers::Peak>& a, const std::vector<solvers::Peak>& b) {
  BOOST_REQUIRE_EQUAL(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) require_same_peak(a[k], b[k]);
}

/// The groups `part` recorded equal those of `full`, bit for bit.
void require_same_groups(const solvers::RunResult& part, const solvers::RunResult& full) {
  BOOST_REQUIRE_EQUAL(part.peaks.size(), full.peaks.size());
  for (std::size_t b = 0; b < full.peaks.size(); ++b) {
    BOOST_REQUIRE_EQUAL(part.peaks[b].floors.size(), full.peaks[b].floors.size());
    for (std::size_t f = 0; f < full.peaks[b].floors.size(); ++f) {
      const solvers::FloorPeaks &p = part.peaks[b].floors[f], &q = full.peaks[b].floors[f];
      if (part.outputs.displacement_peaks) {
        for (auto member : {&solvers::FloorPeaks::u_m, &solvers::FloorPeaks::v_m, &solvers::FloorPeaks::phi_rad}) {
          require_same_peak(p.*member, q.*member);
        }
        require_same_peaks(p.vertex_dx_m, q.vertex_dx_m);
      }
      if (part.outputs.acceleration_peaks) {
        for (auto member : {&solvers::FloorPeaks::ax_abs_mps2, &solvers::FloorPeaks::ay_abs_mps2,
                            &solvers::FloorPeaks::phi_ddot_radps2}) {
          require_same_peak(p.*member, q.*member);
        }
      }
      if (part.outputs.drift_peaks) {
        require_same_peak(p.drift_x, q.drift_x);
        require_same_peak(p.drift_y, q.drift_y);
        require_same_peaks(p.corner_drift_x, q.corner_drift_x);
        require_same_peaks(p.corner_drift_y, q.corner_drift_y);
      }
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(LeavingOutputsOutChangesNoImpactEnergyOrStatistic) {
  for (const std::string method : {"exact", "cvode-bdf", "hht"}) {
    BOOST_TEST_CONTEXT(method) {
      const solvers::RunResult full = analysis::run_scene(paper(method, true, kAll)).result;
      const solvers::RunResult bare = analysis::run_scene(paper(method, false, {})).result;
      BOOST_TEST(full.impacts.size() > 10u);  // the paper scene pounds
      BOOST_TEST(solvers::to_string(bare.status) == solvers::to_string(full.status));
      BOOST_TEST(bare.end_s == full.end_s);
      BOOST_REQUIRE_EQUAL(bare.impacts.size(), full.impacts.size());
      for (std::size_t i = 0; i < full.impacts.size(); ++i) {
        BOOST_TEST(bare.impacts[i].t_s == full.impacts[i].t_s);
        BOOST_TEST(bare.impacts[i].impulse_kNs == full.impacts[i].impulse_kNs);
        BOOST_TEST(bare.impacts[i].approach_velocity_mps == full.impacts[i].approach_velocity_mps);
        BOOST_TEST(bare.impacts[i].separation_velocity_mps == full.impacts[i].separation_velocity_mps);
      }
      BOOST_REQUIRE_EQUAL(bare.sustained_contacts.size(), full.sustained_contacts.size());
      for (std::size_t i = 0; i < full.sustained_contacts.size(); ++i) {
        BOOST_TEST(bare.sustained_contacts[i].release_s == full.sustained_contacts[i].release_s);
      }
      BOOST_TEST(bare.touches.size() == full.touches.size());
      BOOST_TEST(bare.energy.input_kJ == full.energy.input_kJ);
      BOOST_TEST(bare.energy.damping_kJ == full.energy.damping_kJ);
      BOOST_TEST(bare.energy.impact_loss_kJ == full.energy.impact_loss_kJ);
      BOOST_TEST(bare.energy.constraint_work_kJ == full.energy.constraint_work_kJ);
      BOOST_TEST(bare.energy.algorithmic_dissipation_kJ == full.energy.algorithmic_dissipation_kJ);
      BOOST_TEST(bare.energy.residual_kJ() == full.energy.residual_kJ());
      BOOST_TEST(bare.statistics.steps == full.statistics.steps);
      BOOST_TEST(bare.statistics.rhs_evaluations == full.statistics.rhs_evaluations);
      // Nothing else was recorded: the peaks stay at 0.
      BOOST_REQUIRE_EQUAL(bare.peaks.size(), full.peaks.size());
      BOOST_TEST(bare.peaks[1].floors.back().u_m.value == 0.0);
      BOOST_TEST(bare.peaks[1].floors.back().ax_abs_mps2.value == 0.0);
      BOOST_TEST(bare.peaks[1].floors.back().drift_x.value == 0.0);
      BOOST_TEST(full.peaks[1].floors.back().u_m.value != 0.0);
      BOOST_TEST(bare.history.columns.empty());
      BOOST_TEST(bare.history.rows.empty());
      BOOST_TEST(!full.history.rows.empty());
    }
  }
}

BOOST_AUTO_TEST_CASE(EachPeakGroupAndTheHistoryComeOutAsInTheFullRun) {
  for (const std::string method : {"exact", "cvode-bdf", "hht"}) {
    BOOST_TEST_CONTEXT(method) {
      const solvers::RunResult full = analysis::run_scene(paper(method, true, kAll)).result;
      // Without history the peaks still see the sample instants: all three groups unchanged.
      require_same_groups(analysis::run_scene(paper(method, false, kAll)).result, full);
      for (const std::string& group : kAll) {
        BOOST_TEST_CONTEXT(group) {
          const solvers::RunResult alone = analysis::run_scene(paper(method, false, {group})).result;
          BOOST_TEST(alone.outputs.displacement_peaks == (group == "displacements"));
          BOOST_TEST(alone.outputs.acceleration_peaks == (group == "accelerations"));
          BOOST_TEST(alone.outputs.drift_peaks == (group == "drifts"));
          require_same_groups(alone, full);
        }
      }
      const solvers::RunResult history = analysis::run_scene(paper(method, true, {})).result;
      BOOST_TEST(history.peaks[0].floors.front().drift_x.value == 0.0);
      BOOST_TEST(history.history.columns == full.history.columns, tt::per_element());
      BOOST_TEST(history.history.time_s == full.history.time_s, tt::per_element());
      BOOST_REQUIRE_EQUAL(history.history.rows.size(), full.history.rows.size());
      for (std::size_t r = 0; r < full.history.rows.size(); ++r) {
        BOOST_TEST((history.history.rows[r].array() == full.history.rows[r].array()).all());
      }
    }
  }
}
