"""gearkit from Python: scenes, the driver's stage graph and its results.

    import gearkit
    scene = gearkit.Scene("cases/default.prm")
    scene["Loaded contact/fzg/torques"] = [100, 200, 300]
    results = gearkit.run_scene(scene, output_root="out")
    K = results.dataset("stiffness/fzg")["mesh_stiffness"]   # xarray, units N/m

Library level (SI units, library types): flanks - `Flanks.involute(InvoluteGear.create(data))`,
`bevel_pair_flanks(BevelPairDesign(), PinionMismatch())` -> (pinion, gear, Assembly),
`Flanks.measured(read_cmm_file(path))` or from arrays (`MeasuredMember`, `MeasuredFlank`,
`virtual_cmm`); `unloaded_tca(pinion, gear, assembly, options)` -> e_0 per position as NumPy
arrays (classical, or discrete-point on measured flanks). A scene's pair as the stages build
it: `scene.members("fzg")`, `scene.measured_members("fzg")`,
`gearkit.unloaded_tca(**scene.tca_inputs("fzg"))`; on its finite-element compliance, computed
once and cached: `loaded = scene.loaded_pair("fzg")`, `loaded.loaded_contact([50, 100, 400])`
-> e_L, K_m, loads and pressures as an xarray Dataset (as stiffness/<pair>), also on measured
or modified flanks (`flanks=(pinion, gear)`).

Dynamics at library level (SI: speeds in rad/s, `gearkit.rpm(...)` converts):
`scene.dynamics_model("fzg")` -> `PairExcitation` (its `PairModel`, static equilibrium,
torques and the stage's `SweepOptions`, as the dynamics stage builds them), `sweep(excitation,
speeds, options)` -> NumPy arrays per speed (the stage's sweep bit for bit);
`scene.train_model("drive")` -> `TrainModel`, `simulate_train(model, scene.train_options(
"drive"))` -> time series, mesh forces and impacts (the train stage's run bit for bit).

The module runs the same code as the `gearkit` executable (its results are bit for bit the
executable's); an input error is a ValueError with the driver's message; Ctrl-C stops a run at
its next progress step.
"""
import os as _os
import warnings as _warnings



def _built_for():
    """The message for an import under another Python than the module is built for."""
    import sys
    from ._build import python, version
    if _os.path.realpath(sys.executable) == _os.path.realpath(python):
        return None
    return (f"gearkit is built for {python} (Python {version}, with Debian's NumPy, h5py and "
            f"xarray); this is {sys.executable} (Python {sys.version.split()[0]}). Start it "
            f"with that interpreter: PYTHONPATH=build/python {python}")


try:
    from . import _core
    if _built_for() is not None:  # another interpreter: are Debian's packages there too?
        import h5py as _h5py  # noqa: F401
        import numpy as _numpy  # noqa: F401
except ImportError as _error:
    _message = _built_for()
    if _message is None:
        raise
    raise ImportError(f"{_message} ({_error})") from None
from .results import Results, results_schema, schema_entry
from ._core import (Assembly, BevelPairDesign, Flanks, InvoluteGear, InvoluteGearData,
                    MeasuredFlank, MeasuredMember, Misalignment, PinionMismatch, TcaOptions,
                    bevel_pair_flanks, create_pair, read_cmm_file, unloaded_tca, virtual_cmm,
                    working_centre_distance, write_cmm_file)
from ._core import (PairExcitation, PairModel, RunOptions, StaticEquilibrium, SweepOptions,
                    TrainModel, TrainRunOptions)
from .dynamics import rpm, simulate_train, sweep
from .scene import Scene, run_scene

__all__ = ["Scene", "run_scene", "Results", "results_schema", "schema_entry", "case", "cases",
           "blas_kernels", "InvoluteGearData", "InvoluteGear", "create_pair",
           "working_centre_distance", "Misalignment", "TcaOptions", "unloaded_tca", "Assembly",
           "Flanks", "BevelPairDesign", "PinionMismatch", "bevel_pair_flanks", "MeasuredFlank",
           "MeasuredMember", "read_cmm_file", "write_cmm_file", "virtual_cmm",
           "PairExcitation", "PairModel", "StaticEquilibrium", "RunOptions", "SweepOptions",
           "sweep", "rpm", "TrainModel", "TrainRunOptions", "simulate_train"]


def cases():
    """The names of the cases that ship with gearkit (cases/<name>.prm, cases/<name>/<name>.prm)."""
    root = _os.path.join(_core.source_dir, "cases")
    names = [f[:-4] for f in _os.listdir(root) if f.endswith(".prm")]
    names += [d for d in _os.listdir(root)
              if _os.path.isfile(_os.path.join(root, d, d + ".prm"))]
    return sorted(names)


def case(name):
    """The scene file of a shipped case ("default", "seed_spiral_bevel", ...)."""
    root = _os.path.join(_core.source_dir, "cases")
    for path in (_os.path.join(root, name + ".prm"), _os.path.join(root, name, name + ".prm")):
        if _os.path.isfile(path):
            return path
    raise KeyError(f"no case '{name}'; the cases: {', '.join(cases())}")


def blas_kernels():
    """The kernels OpenBLAS runs on in this process, and those the executable uses on this
    processor (it switches where OpenBLAS fell back to generic ones)."""
    return _core.blas_kernels(), _core.fitting_blas_kernels() or _core.blas_kernels()


_running, _fitting = blas_kernels()
if _running != _fitting and "OPENBLAS_CORETYPE" not in _os.environ:
    _warnings.warn(f"OpenBLAS runs its {_running} kernels here, the gearkit executable its "
                   f"{_fitting} ones: the finite elements run slower and their results differ from "
                   f"the executable's in the last bits. Start Python with "
                   f"OPENBLAS_CORETYPE={_fitting} for both.", RuntimeWarning, stacklevel=2)
