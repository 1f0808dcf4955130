"""Dynamics at library level, SI units: speed sweeps of the 14-DOF pair model and the run of a
gear train, as the dynamics and train stages compute them (the same library calls).

    exc = scene.dynamics_model("fzg")                 # PairExcitation, as the stage builds it
    up = gearkit.sweep(exc)                           # the stage's sweep up, bit for bit
    down = gearkit.sweep(exc, exc.sweep_options.speeds[::-1])
    train = scene.train_model("drive")                # TrainModel
    run = gearkit.simulate_train(train, scene.train_options("drive"))
"""
import math

from . import _core


def sweep(model, speeds=None, options=None, *, start=None, blocks=None, warmup=None):
    """Sweeps a pair model over pinion speeds with continuation (dynamics/sweep.h): the state at
    the end of one speed starts the next, in the order given.

    model: a PairExcitation (Scene.dynamics_model) or its PairModel.
    speeds: pinion speeds in rad/s (SI; from rpm: rpm * pi / 30), in the order swept; None: the
        options' (a PairExcitation's: the dynamics stage's, ascending - reversed, its sweep down).
    options: SweepOptions (torques, cycles, integrator ...); None: the PairExcitation's (the
        scene's); required with a bare PairModel. Not changed (speeds go into a copy).
    start: (q, v), 14 values each; None: the static equilibrium under the options' load torque
        (a PairExcitation's: the stage's, at rest).
    blocks, warmup: the sweep in `blocks` blocks of speeds on threads, each but the first started
        `warmup` speeds early; None: a PairExcitation's Dynamics/<pair>/sweep blocks and warm-up
        speeds (so that its sweep is the stage's bit for bit), else 1 and 0.

    Returns a dict of NumPy arrays, one value per speed in the order swept: speed [rad/s],
    status (0 steady, 1 not steady within the settle cycles, 2 diverged: its results 0),
    dte_peak_to_peak, dte_rms, relative_peak_to_peak, relative_rms [m], max_mesh_force [N],
    dynamic_load_factor, contact_loss, events, period, settled_cycles, diverged, diverged_time
    [s], with Newmark steps_per_cycle and error_estimate; dte_spectrum (speeds x orders) [m] at
    spectrum_order; time_series: a list of dicts (speed, time, dte, transmission_error,
    mesh_force) at the options' series speeds. The log's progress line shows; Ctrl-C stops it.
    """
    import numpy as np  # imported on first use: `import gearkit` stays light
    if isinstance(model, _core.PairExcitation):
        excitation, pair_model = model, model.model
        if options is None:
            options = excitation.sweep_options
        if blocks is None:
            blocks = excitation.sweep_blocks
        if warmup is None:
            warmup = excitation.warmup_speeds
        if start is None:
            start = (excitation.static_equilibrium.q, np.zeros(14))
    elif isinstance(model, _core.PairModel):
        pair_model = model
        if options is None:
            raise ValueError("gearkit.sweep: options = None is not allowed with a PairModel; "
                             "expected SweepOptions with its torques (a scene's excitation, "
                             "Scene.dynamics_model, brings the stage's)")
    else:
        raise TypeError(f"gearkit.sweep: model is a {type(model).__name__}; expected a "
                        "PairExcitation (Scene.dynamics_model) or a PairModel")
    if not isinstance(options, _core.SweepOptions):
        raise TypeError(f"gearkit.sweep: options is a {type(options).__name__}; expected "
                        "gearkit.SweepOptions")
    options = _core.SweepOptions(options)
    if speeds is not None:
        options.speeds = [float(w) for w in np.atleast_1d(np.asarray(speeds, dtype=float))]
    if start is None:
        start = (pair_model.static_equilibrium(options.load_torque).q, np.zeros(14))
    q, v = start
    return _core.sweep(pair_model, [float(x) for x in q], [float(x) for x in v], options,
                       1 if blocks is None else int(blocks), 0 if warmup is None else int(warmup))


def rpm(speeds):
    """Speeds in rpm as rad/s (x pi / 30), what gearkit.sweep takes."""
    import numpy as np  # imported on first use: `import gearkit` stays light
    return np.asarray(speeds, dtype=float) * (math.pi / 30)


def simulate_train(model, options=None):
    """Runs a gear train (dynamics/train.h) from its bodies' initial angles and speeds, as the
    train stage does. model: a TrainModel (Scene.train_model); options: TrainRunOptions (the
    scene's: Scene.train_options; None: the library's defaults).

    Returns a dict: time [s]; angle, speed (bodies x samples) [rad, rad/s]; work, kinetic,
    potential, dissipated [J]; energy_error; steps, events, integrator; meshes: per mesh name a
    dict of relative (S) [m], force (drive +, coast -) and force_magnitude [N], pairs,
    impacts, drive_impacts, coast_impacts, max_force [N], max_force_time [s], max_penetration
    [m], first_contact [s] (-1: none) and contacts (side +1 drive / -1 coast, touch,
    separation, peak, peak_time, impulse). The progress line shows; Ctrl-C stops it."""
    if not isinstance(model, _core.TrainModel):
        raise TypeError(f"gearkit.simulate_train: model is a {type(model).__name__}; expected "
                        "a TrainModel (Scene.train_model)")
    return _core.simulate_train(model, _core.TrainRunOptions() if options is None else options)
