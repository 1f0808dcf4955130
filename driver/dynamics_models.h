// What the dynamics and train stages build from the scene and their upstream results before they
// run: a pair's excitations (the 14-DOF model on the TCA's tables in the system deflection's
// fixed point, its static equilibrium), the sweeps' options and tasks, and a gear train's model.
// The stages (stage_dynamics.cc, stage_train.cc, where these are defined) and the Python module
// call the same functions, so that a model built from Python is the stage's, bit for bit.
#pragma once

#include "driver/pair_members.h"
#include "driver/scene.h"
#include "driver/stages.h"
#include "dynamics/deflection.h"
#include "dynamics/sweep.h"
#include "dynamics/train.h"
#include "tca/unloaded_tca.h"

#include <optional>
#include <string>
#include <vector>

namespace gearkit
{
/// A pair of the scene as the dynamics stage places it: its theoretical members in their
/// assembly and the model's parameters placed there (axes, bearing positions).
struct PairDynamicsInputs
{
  const PairScene     *pair     = nullptr;
  const DynamicsScene *dynamics = nullptr;
  const TcaScene      *tca      = nullptr;
  PairMembers          members;
  PairModelParameters  parameters;
};

/// The inputs of pair `pair` (its flanks from the upstream "flanks" group).
PairDynamicsInputs
pair_dynamics_inputs(const Scene &scene, const PairScene &pair, const Upstream &upstream);

/// One excitation of a pair ("theoretical" or "measured" flanks): its model on the tables of the
/// TCA (`cycles` mesh cycles of positions_per_mesh samples), in the system deflection's fixed
/// point, and its static equilibrium; what the stage records of the deflected position.
struct PairExcitation
{
  std::string label;
  int         cycles       = 1; ///< mesh cycles of the excitation's period
  double      motor_torque = 0; ///< T_E [N m] (the scene's pinion torque)
  /// The fixed point: its model (on the deflected mesh's tables), static equilibrium and load
  /// torque are the excitation's.
  SystemDeflection deflection;
  /// The deflected position (`iterated`: the scene's system deflection on): the misalignment
  /// there (the scene's plus the deflection's), the members there (empty: not moved, the
  /// assembled ones) and their TCA.
  bool                       iterated = false;
  Misalignment               misalignment;
  std::optional<PairMembers> moved;
  TcaResult                  deflected;

  const PairModel &
  model() const
  {
    return *deflection.model;
  }
  const StaticEquilibrium &
  equilibrium() const
  {
    return deflection.equilibrium;
  }
  double
  load_torque() const
  {
    return deflection.load_torque;
  }
};

/// The excitation `label` of a pair as the dynamics stage builds it (upstream: flanks, ste,
/// measured and stiffness as the scene needs them). Throws InputError where the deflected TCA
/// fails.
PairExcitation
build_excitation(const std::string &label, const PairDynamicsInputs &in, const Upstream &upstream);

/// The sweep's speeds [rad/s], ascending (Dynamics/<pair>/speed from, speed to, speeds).
std::vector<double>
sweep_speeds(const DynamicsScene &d);

/// The options of the stage's sweep of an excitation up (ascending speeds) or down: the scene's
/// sweep settings, the speeds, the excitation's torques.
SweepOptions
excitation_sweep_options(const PairExcitation &e, const DynamicsScene &d, bool up);

/// One sweep from (q, v) as tasks: in `blocks` blocks of its speeds, each but the first started
/// `warmup` speeds early (split_sweep); their results concatenated are the sweep's.
std::vector<SweepTask>
sweep_block_tasks(const PairModel &model, const PairVector &q, const PairVector &v,
                  const SweepOptions &options, int blocks, int warmup);

/// The train's model as the train stage builds it: the scene's bodies, meshes and shafts, each
/// mesh's tooth pair tables from its pair's involute flanks at the mesh's centre distance, its
/// gear placed in the backlash, and the stiffness stage's K_m where the scene asks for it
/// (upstream "stiffness").
TrainModel
train_model(const Scene &scene, const TrainScene &train, const Upstream &upstream);
} // namespace gearkit
