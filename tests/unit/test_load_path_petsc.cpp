// What a branch restart compares (src/io/checkpoint_compare.h, docs/design-run.md): the scene's
// physics with its loads up to a stage end k (LoadPathStates), and which options may differ.
//  * a branch (one stage more, a snow and a wind that are zero in the base stages) agrees with its
//    base at every stage end of the base, and differs after;
//  * another value in a base stage, another support, a chamber sealed within the base stages and
//    another physical time of a base stage are seen from that stage end on, not before;
//  * a chamber sealed only in the branch's own stage is not;
//  * load options may differ on a branch, model options never, neither on a plain restart.
#include "../../src/io/checkpoint_compare.h"
#include "check.h"

using namespace etfe;

namespace {

// Two stages drawn (a support moved 5 then 10 mm), self-weight on; `extra` more stages.
SceneSpec Base(int extra) {
  SceneSpec s;
  s.name = "structure";
  const int n = 2 + extra;
  std::vector<double> draw = {-5, -10}, weight = {1, 1}, zero(2, 0.0);
  for (int k = 0; k < extra; ++k) draw.push_back(-10), weight.push_back(1), zero.push_back(0);
  const int d = s.AddSchedule({"boundary.ux", 0.0, draw});
  const int w = s.AddSchedule({"self_weight", 0.0, weight});
  s.constraints.push_back({3, 0, {{1.0, 0.0}, {d, -1}}});
  s.nodal_forces.push_back({5, 2, {{-2e-3, 0.0}, {w, -1}}});
  ChamberSpec c;
  c.name = "air";
  const int p = s.AddSchedule({"air", 0.0, std::vector<double>(n, 3e-4)});
  c.supplied = {{1.0, 0.0}, {p, -1}};
  s.chambers.push_back(c);
  s.pressures.push_back({{0, 1, 2}, {}, 0, 1.0});
  (void)zero;
  return s;
}

// The base with a third stage: 1.35 x self-weight, snow on node 7, wind suction on elements 4, 5.
SceneSpec Branch() {
  SceneSpec s = Base(1);
  s.schedules[1].values[2] = 1.35;
  const int snow = s.AddSchedule({"all.snow", 0.0, {0, 0, -1.125e-3}});
  s.nodal_forces.insert(s.nodal_forces.begin(), {7, 2, {{1.0, 0.0}, {snow, -1}}});
  const int wind = s.AddSchedule({"wind", 0.0, {0, 0, 5e-4}});
  s.pressures.insert(s.pressures.begin(), {{4, 5}, {{0.8, 0.0}, {wind, -1}}});
  return s;
}

std::vector<std::uint64_t> States(const SceneSpec &s, const StageClock &clock = StageClock()) {
  return LoadPathStates(s, 0.25, 0.0, clock);
}

} // namespace

int main() {
  const auto base = States(Base(0)), branch = States(Branch());
  CHECK(base.size() == 3 && branch.size() == 4, "one state per stage end: %zu and %zu", base.size(), branch.size());
  for (int k = 0; k <= 2; ++k) CHECK(base[k] == branch[k], "the branch agrees with its base at stage end %d", k);
  CHECK(branch[3] != States(Base(1))[3], "after the base, the branch's own loads count");

  SceneSpec heavier = Branch();
  heavier.schedules[1].values[1] = 1.1;  // self-weight 1.1 in stage 2
  const auto h = States(heavier);
  CHECK(h[1] == base[1] && h[2] != base[2], "another self-weight in stage 2: seen from stage end 2 on");

  SceneSpec moved = Branch();
  moved.constraints[0].node = 4;
  CHECK(States(moved)[0] != base[0], "another supported node: seen from the start");

  SceneSpec sealed_late = Branch();
  sealed_late.chambers[0].sealed_from_stage = 3;
  CHECK(States(sealed_late)[2] == base[2], "a chamber sealed in the branch's own stage 3 agrees with the base");
  SceneSpec sealed_early = Branch();
  sealed_early.chambers[0].sealed_from_stage = 2;
  const auto se = States(sealed_early);
  CHECK(se[1] == base[1] && se[2] != base[2], "a chamber sealed from stage 2: seen from stage end 2 on");

  StageClock clock;
  clock.duration = {60, 60, 600};
  clock.hold = {0, 0, 1};
  StageClock slower = clock;
  slower.duration[1] = 120;
  const auto c0 = States(Branch(), clock), c1 = States(Branch(), slower);
  CHECK(c0[1] == c1[1] && c0[2] != c1[2], "stage 2 lasting 120 s instead of 60 s: seen from stage end 2 on");
  StageClock longer_own = clock;
  longer_own.duration[2] = 6000;
  CHECK(States(Branch(), longer_own)[2] == c0[2], "the branch's own stage lasting longer agrees with the base");

  CHECK(CheckpointOptionMayChange("-film_all_snow", true) && CheckpointOptionMayChange("structure_stages", true) &&
            CheckpointOptionMayChange("-chamber_air_sealed_from_stage", true) &&
            CheckpointOptionMayChange("-load_increments", true),
        "load options may differ on a branch");
  CHECK(!CheckpointOptionMayChange("-material_young", true) && !CheckpointOptionMayChange("-membrane_wrinkling", true) &&
            !CheckpointOptionMayChange("-mesh_refine", true) && !CheckpointOptionMayChange("-scene", true) &&
            !CheckpointOptionMayChange("-contact_mu", true),
        "model options may not differ on a branch");
  CHECK(!CheckpointOptionMayChange("-film_right_material_yield", true) &&
            !CheckpointOptionMayChange("-film_roof_thickness", true) && !CheckpointOptionMayChange("-film_a_md", true) &&
            !CheckpointOptionMayChange("-film_all_stress_ratio", true) &&
            CheckpointOptionMayChange("-film_right_pressure", true) && CheckpointOptionMayChange("-film_md_snow", true),
        "a surface group's law, thickness, MD and stress ratio may not differ on a branch; its loads may");
  CHECK(!CheckpointOptionMayChange("-film_all_snow") && !CheckpointOptionMayChange("-structure_stages") &&
            CheckpointOptionMayChange("-snes_rtol") && CheckpointOptionMayChange("-restart_branch"),
        "a plain restart: loads may not differ, solver options and the restart options may");
  CHECK(OptionDifferences("-film_all_snow 0,0.75\n-material_young 800\n", "-film_all_snow 0,0,1.125\n-material_young 800\n",
                          true)
                .empty() &&
            !OptionDifferences("-material_young 800\n", "-material_young 801\n", true).empty(),
        "OptionDifferences on a branch lists the model's differences only");
  TEST_MAIN_END();
}
