// What a checkpoint must agree on with the run that restarts from it (private to src/io):
// fingerprints of the mesh and of the resolved physics, and the options as "-name value" lines.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "etfe/base/fnv64.h"
#include "etfe/assembly/problem.h"

namespace etfe {

// Options that may differ between a checkpoint's run and its restart: how the increments are
// solved and what is written, never what is computed (the list: checkpoint_compare.cpp).
// branch: on a branch restart (-restart_branch), where the scene's load options may change too.
bool CheckpointOptionMayChange(const std::string &option, bool branch = false);
// Coordinates, triangles, node and element sets of the scene's global mesh (rank 0).
std::uint64_t MeshFingerprint(const MeshData &mesh);
// What the options resolve to: schedules, constraints, loads, supports, contact parameters,
// thickness, material constants. Catches what the option lists cannot (changed defaults).
// The scene's part is hashed on rank 0's global description at set-up (ScenePhysicsState, kept
// as Problem::scene_physics_state); PhysicsFingerprint goes on from it with the contact set and
// the material, so the value is that of one hash over all of it.
std::uint64_t ScenePhysicsState(const SceneSpec &scene, double thickness, double min_area_ratio);
std::uint64_t PhysicsFingerprint(const Problem *problem);
// The same hash gone on from another scene state (a LoadPathStates entry): contact set, material.
std::uint64_t PhysicsFingerprintFrom(const Problem *problem, std::uint64_t scene_state);
// Per stage end k = 0..stages, the scene's physics with its loads up to load time k only: the
// film, supports, constraints, chambers and the non-zero loads with their values at stage ends
// 0..k (rank 0's global description). A run that branches from a checkpoint at stage end k must
// agree on entry k with the run that wrote it; what the loads do after k is the branch's own.
// With the physical time of those stages when the clock is active (-load_stage_duration, holds).
std::vector<std::uint64_t> LoadPathStates(const SceneSpec &scene, double thickness, double min_area_ratio,
                                          const StageClock &clock);
// The options in force, one "-name value" per line, sorted by name.
PetscErrorCode OptionsAsLines(std::string *lines);
// The options that differ (other than those that may change), as a table for a message;
// empty when they agree.
std::string OptionDifferences(const std::string &checkpoint_lines, const std::string &current_lines,
                              bool branch = false);

} // namespace etfe
