"""gearkit.run_scene: the executable's stage graph from Python - results bit for bit the
executable's (every dataset and its attributes), read back as xarray with the schema's units and
dimensions; Ctrl-C stops a run with nothing half-written."""
import glob
import os
import signal
import threading

import h5py
import numpy as np
import pytest

import gearkit

# Cases the executable ran in ./test (the case tests), cheap enough to run again here (flanks and
# TCA, a gear train; the finite elements and the dynamics are compared stage by stage at library
# level in test_library.py and test_dynamics.py); every case, the default one included:
# GEARKIT_ALL_CASES=1 (the slow test python_every_case).
QUICK = ["published_pairs", "seed002_power_loss"]
EVERY = ["default", "published_pairs", "hunting", "seed_spiral_bevel", "fzg_loaded",
         "fzg_reference", "iso_helical", "seed001_spur_pair", "seed002_power_loss",
         "seed002_startup", "seed002_steady"]
CASES = EVERY if os.environ.get("GEARKIT_ALL_CASES") == "1" else QUICK


def scene_file(source_dir, case):
    path = os.path.join(source_dir, "cases", case + ".prm")
    return path if os.path.exists(path) else os.path.join(source_dir, "cases", case, case + ".prm")


def differences(a, b):
    """The datasets (and their attributes) of results files a and b that differ, bit for bit;
    run times (datasets named "seconds", as scripts/results_digest.py leaves them out) apart."""
    out = []

    def numbers(f):
        names = []
        f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset)
                     and n.split("/")[-1] != "seconds" else None)
        return names

    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        names_a, names_b = numbers(fa), numbers(fb)
        if sorted(names_a) != sorted(names_b):
            out.append(f"datasets: {sorted(set(names_a) ^ set(names_b))}")
        for n in names_a:
            if n not in fb:
                continue
            x, y = fa[n][()], fb[n][()]
            if np.shape(x) != np.shape(y) or np.asarray(x).tobytes() != np.asarray(y).tobytes():
                out.append(n)
            if dict(fa[n].attrs) != dict(fb[n].attrs):
                out.append(n + " (attributes)")
    return out


@pytest.mark.parametrize("case", CASES)
def test_results_bit_for_bit_the_executables(case, source_dir, case_out, tmp_path):
    executable = os.path.join(case_out, case, "results.h5")
    if not os.path.exists(executable):
        pytest.fail(f"{executable} missing: the case test case_{case}_run makes it")
    results = gearkit.run_scene(scene_file(source_dir, case), output_root=tmp_path)
    assert results.status == 0
    assert all(not s["reused"] for s in results.stages)  # computed here, from nothing
    assert differences(executable, results.path) == []


def test_results_as_xarray_with_the_schemas_units(case_out):
    results = gearkit.Results(os.path.join(case_out, "default", "results.h5"))
    ds = results.dataset("stiffness/fzg")
    k = ds["mesh_stiffness"]
    assert k.dims == ("torques", "positions")
    assert k.attrs["units"] == "N/m"
    assert k.attrs["units"] == gearkit.schema_entry("stiffness/fzg", "mesh_stiffness")["units"]
    np.testing.assert_array_equal(ds["torques"].values, results["stiffness/fzg/torque"])
    # the same numbers as h5py reads
    np.testing.assert_array_equal(k.values, results["stiffness/fzg/mesh_stiffness"])
    # the schema lists every dataset once, as --print-results does
    assert len(gearkit.results_schema()) > 300
    with pytest.raises(KeyError, match="K_m"):
        gearkit.schema_entry("stiffness/fzg", "K_m")


def test_ctrl_c_stops_a_run_with_nothing_half_written(source_dir, tmp_path):
    # SIGINT to this process after 3 s: the default case is then in its finite elements
    timer = threading.Timer(3.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            gearkit.run_scene(scene_file(source_dir, "default"), output_root=tmp_path)
    finally:
        timer.cancel()
    left = [os.path.join(d, f) for d, _, files in os.walk(tmp_path) for f in files]
    assert not any(f.endswith("results.h5") for f in left), left
    assert not any(f.endswith(".tmp") for f in left), left
    # and the module goes on working: the next run is complete
    results = gearkit.run_scene(scene_file(source_dir, "published_pairs"), output_root=tmp_path)
    assert results.status == 0


def test_every_group_of_every_case_reads_as_a_dataset(case_out):
    """Every group of every case the executable ran reads as an xarray Dataset: dimensions
    named from the schema's shapes (fixed lengths by what they hold: radius_axial, xyz), no
    dimension clashing with a variable, every variable with its units."""
    files = sorted(glob.glob(os.path.join(case_out, "*", "results.h5")))
    assert len(files) >= 4
    groups = 0
    for path in files:
        results = gearkit.Results(path)
        names = []
        with h5py.File(path, "r") as f:
            f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Group) else None)
        for name in names:
            ds = results.dataset(name)
            groups += 1
            for v in ds.data_vars.values():
                assert "units" in v.attrs, (path, name, v.name)
                assert all(not d[:1].isdigit() and "(" not in d for d in v.dims), (name, v.dims)
    assert groups > 100
