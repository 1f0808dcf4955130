"""The dynamics at library level: a pair's excitation built by Scene.dynamics_model and swept by
gearkit.sweep gives the dynamics stage's sweeps bit for bit (whole sweeps up and down, in the
stage's blocks, theoretical and measured flanks), a train built by Scene.train_model and run by
gearkit.simulate_train the train stage's run bit for bit; bad arguments are ValueErrors naming
the parameter; Ctrl-C stops a sweep."""
import math
import os

import numpy as np
import pytest

import gearkit


def same(a, b):
    """Bit for bit: the same shape, type and bytes."""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


@pytest.fixture(scope="module")
def small_dynamics(tmp_path_factory):
    """The default pair with a constant K_m (no finite elements), both excitations, 7 speeds in
    2 blocks with a warm-up speed, a time series: the executable's stage run through run_scene."""
    root = tmp_path_factory.mktemp("dynamics")
    scene = gearkit.Scene(gearkit.case("default"))
    scene["Scene/name"] = "small_dynamics"
    scene["Scene/outputs"] = "measured, ste, dynamics"
    scene["Dynamics/fzg/mesh stiffness source"] = "constant"
    scene["Dynamics/fzg/mesh stiffness variation"] = 0.1
    scene["Dynamics/fzg/speed from"] = 2000
    scene["Dynamics/fzg/speed to"] = 20000
    scene["Dynamics/fzg/speeds"] = 7
    scene["Dynamics/fzg/settle cycles"] = 100
    scene["Dynamics/fzg/record cycles"] = 20
    scene["Dynamics/fzg/time series speeds"] = [5000]
    scene["Dynamics/fzg/sweep blocks"] = 2
    scene["Dynamics/fzg/warm-up speeds"] = 1
    results = gearkit.run_scene(scene, output_root=root)
    assert results.status == 0
    return scene, root, results


def assert_sweep_is_the_stages(sweep, results, group):
    """Every dataset of the stage's sweep group equals the Python sweep's (speed: rpm there),
    the time series too."""
    names = results.datasets(group)
    assert len(names) >= 14
    for name in names:
        stored = results[f"{group}/{name}"]
        mine = sweep["speed"] * 60 / (2 * math.pi) if name == "speed" else sweep[name]
        assert same(stored, mine), (group, name)
    series = results.groups(f"{group}/time_series") if "time_series" in results.groups(group) \
        else []
    assert len(series) == len(sweep["time_series"]) == 1  # at 5000 rpm
    for k, s in enumerate(sweep["time_series"]):
        at = f"{group}/time_series/{k}"
        assert same(results[at + "/speed"], s["speed"] * 60 / (2 * math.pi))
        for name in ("time", "dte", "transmission_error", "mesh_force"):
            assert same(results[f"{at}/{name}"], s[name]), (at, name)


@pytest.mark.parametrize("excitation", ["theoretical", "measured"])
def test_sweep_is_the_dynamics_stages(small_dynamics, excitation):
    scene, root, results = small_dynamics
    exc = scene.dynamics_model("fzg", output_root=root, excitation=excitation)
    at = f"dynamics/fzg/{excitation}"
    # the model as the stage built it: its static equilibrium, torques and period
    assert exc.label == excitation and exc.pair == "fzg"
    assert same(exc.static_equilibrium.mesh_force, results[at + "/static_mesh_force"])
    assert same(exc.static_equilibrium.deflection, results[at + "/static_deflection"])
    assert same(exc.load_torque, results[at + "/load_torque"])
    assert exc.excitation_cycles == results[at + "/excitation_cycles"] == \
        (3 if excitation == "measured" else 1)
    assert exc.model.tables["transmission_error"].size == 40 * exc.excitation_cycles
    assert exc.system_deflection["iterated"] and exc.system_deflection["converged"]
    assert (exc.sweep_blocks, exc.warmup_speeds) == (2, 1)
    if excitation == "theoretical":  # the stage's modes are the first excitation's
        assert same(exc.model.modes()["frequency"], results["dynamics/fzg/mode_frequency"])
    # whole sweeps up and down (each continues from speed to speed), in the stage's blocks
    speeds = exc.sweep_options.speeds
    assert len(speeds) == 7 and speeds[0] == pytest.approx(2000 * math.pi / 30)
    up = gearkit.sweep(exc)
    down = gearkit.sweep(exc, speeds[::-1])
    assert_sweep_is_the_stages(up, results, at + "/up")
    assert_sweep_is_the_stages(down, results, at + "/down")
    assert np.all(up["dynamic_load_factor"] > 0.5) and np.all(up["status"] < 2)


def test_sweep_of_a_bare_model_and_one_block(small_dynamics):
    """The PairModel with the excitation's options, from its static equilibrium, in one block:
    the first block of the stage's sweep (its first speeds) is the same, bit for bit; the last
    speeds differ only by the warm-up's continuation."""
    scene, root, results = small_dynamics
    exc = scene.dynamics_model("fzg", output_root=root)
    options = exc.sweep_options
    one = gearkit.sweep(exc.model, options=options)
    stored = results["dynamics/fzg/theoretical/up/dte_peak_to_peak"]
    first = len(options.speeds) // 2  # split_sweep's first block
    assert same(one["dte_peak_to_peak"][:first], stored[:first])
    assert one["speed"].size == 7
    # the options passed are not changed by speeds given
    gearkit.sweep(exc, gearkit.rpm([3000, 4000]))
    assert len(exc.sweep_options.speeds) == 7 and len(options.speeds) == 7


def test_train_run_is_the_train_stages(case_out, tmp_path):
    """Against the executable's run of the case (the case test case_seed002_power_loss)."""
    executable = os.path.join(case_out, "seed002_power_loss", "results.h5")
    if not os.path.exists(executable):
        pytest.fail(f"{executable} missing: the case test case_seed002_power_loss makes it")
    results = gearkit.Results(executable)
    scene = gearkit.Scene(gearkit.case("seed002_power_loss"))
    name = "chipped"
    model = scene.train_model(name, output_root=tmp_path)
    assert [m.name for m in model.meshes] == ["stage1", "stage2"]
    assert len(model.bodies) >= 3
    run = gearkit.simulate_train(model, scene.train_options(name))
    at = f"train/{name}"
    for key in ("time", "angle", "speed", "work", "kinetic", "potential", "dissipated",
                "energy_error"):
        assert same(run[key], results[f"{at}/{key}"]), key
    assert run["steps"] == results[at + "/steps"] and run["events"] == results[at + "/events"]
    for mesh in model.meshes:
        g = f"{at}/meshes/{mesh.name}"
        assert same(mesh.gear_angle_0, results[g + "/gear_angle_0"])
        assert same(mesh.pinion_base_radius, results[g + "/pinion_base_radius"])
        m = run["meshes"][mesh.name]
        for key in ("relative", "force", "force_magnitude", "pairs", "max_force",
                    "max_force_time", "max_penetration", "first_contact"):
            assert same(m[key], results[f"{g}/{key}"]), (mesh.name, key)
        for key in ("impacts", "drive_impacts", "coast_impacts"):
            assert m[key] == results[f"{g}/{key}"], (mesh.name, key)
        for key in ("side", "touch", "separation", "peak", "peak_time", "impulse"):
            assert same(m["contacts"][key], results[f"{g}/contacts/{key}"]), (mesh.name, key)
    assert run["meshes"]["stage1"]["impacts"] > 0


def test_bad_arguments_are_value_errors_naming_them(small_dynamics):
    scene, root, _ = small_dynamics
    with pytest.raises(ValueError, match="pair 'nope' is not in Scene/pairs"):
        scene.dynamics_model("nope", output_root=root)
    with pytest.raises(ValueError, match="excitation = 'simulated' is not allowed; expected "
                                         "theoretical or measured"):
        scene.dynamics_model("fzg", output_root=root, excitation="simulated")
    exc = scene.dynamics_model("fzg", output_root=root)
    with pytest.raises(ValueError, match=r"speeds\[1\] = -5 is not allowed; expected pinion "
                                         r"speeds > 0 in rad/s"):
        gearkit.sweep(exc, [100.0, -5.0])
    with pytest.raises(ValueError, match="options = None is not allowed with a PairModel"):
        gearkit.sweep(exc.model)
    with pytest.raises(ValueError, match="blocks = 0 is not allowed"):
        gearkit.sweep(exc, blocks=0)
    with pytest.raises(ValueError, match="start q has 3 values; expected the 14 DOFs"):
        gearkit.sweep(exc, start=([0, 0, 0], np.zeros(14)))
    options = gearkit.SweepOptions()
    with pytest.raises(ValueError, match="RunOptions.method = 'euler' is not allowed"):
        options.run.method = "euler"
    options.run.method = "cvode adams"
    assert options.run.method == "cvode adams"  # set in place, not on a copy
    with pytest.raises(ValueError, match="train 'nope' is not in Scene/trains"):
        scene.train_model("nope", output_root=root)
    with pytest.raises(ValueError, match="do not run the train stage"):
        gearkit.Scene(gearkit.case("seed002_power_loss")).set(
            "Scene/outputs", "flanks").train_model("perfect", output_root=root)


def test_ctrl_c_stops_a_sweep(small_dynamics):
    """SIGINT during a long sweep: a KeyboardInterrupt within a second or so, and the module
    goes on working."""
    import signal
    import threading
    import time
    scene, root, _ = small_dynamics
    exc = scene.dynamics_model("fzg", output_root=root)
    options = exc.sweep_options
    options.settle_cycles, options.steady_tolerance, options.record_cycles = 2000, 0, 500
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            gearkit.sweep(exc, gearkit.rpm(range(1000, 30000, 100)), options)
    finally:
        timer.cancel()
    assert time.monotonic() - start < 10  # the whole sweep takes over a minute
    assert gearkit.sweep(exc)["speed"].size == 7
