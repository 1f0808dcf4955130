"""Scenes from Python: read a scene file, get and set its parameters by path, check it with the
driver's own checks, write it back, and run it through the driver's stage graph."""
import difflib
import os
import tempfile

from . import _core
from .results import Results


def _parse_blocks(sections):
    """The parameters of the driver's canonical section blocks ("subsection A / set x = 1 /
    end"), as an ordered dict "A/B/x" -> "1"."""
    params = {}
    for name in sections:
        path = [name]  # a block is its section's inside
        for raw in sections[name].splitlines():
            line = raw.strip()
            if not line:
                continue
            if line.startswith("subsection "):
                path.append(line[len("subsection "):].strip())
            elif line == "end":
                path.pop()
            elif line.startswith("set "):
                key, _, value = line[len("set "):].partition("=")
                params["/".join(path + [key.strip()])] = value.strip()
    return params


def _render(params):
    """The parameters as a scene file's text (subsections nested, one `set` per line)."""
    lines, open_path = [], []
    for path, value in params.items():
        *sections, key = path.split("/")
        common = 0
        while (common < len(open_path) and common < len(sections)
               and open_path[common] == sections[common]):
            common += 1
        for depth in range(len(open_path), common, -1):
            lines.append("  " * (depth - 1) + "end")
        for depth in range(common, len(sections)):
            lines.append("  " * depth + "subsection " + sections[depth])
        open_path = sections
        lines.append("  " * len(sections) + f"set {key} = {value}")
    for depth in range(len(open_path), 0, -1):
        lines.append("  " * (depth - 1) + "end")
    return "\n".join(lines) + "\n"


def _text(value):
    """A Python value as a scene file writes it: true/false, numbers as repr, lists with
    commas."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return ", ".join(_text(v) for v in value)
    return str(value)


class Scene:
    """A scene file as the driver reads it (.prm, .json or .xml): every parameter, defaults
    filled in, by its path ("Dynamics/fzg/speeds"). Changed parameters are checked with the
    driver's own checks by `check()` (or before a run); `write()` saves the scene."""

    def __init__(self, path):
        self.path = os.path.abspath(os.fspath(path))
        self._core = _core.read_scene(self.path)
        self._params = _parse_blocks(self._core.sections)
        self._changed = False

    @classmethod
    def read(cls, path):
        return cls(path)

    # -- parameters
    def parameters(self):
        """Every parameter: path -> its value as the scene file writes it."""
        return dict(self._params)

    def _known(self, path):
        if path not in self._params:
            close = difflib.get_close_matches(path, self._params.keys(), n=3, cutoff=0.6)
            raise KeyError(f"scene {self.path}: no parameter '{path}'" +
                           (f"; did you mean {', '.join(repr(c) for c in close)}?" if close
                            else "; Scene.parameters() lists them all"))

    def __getitem__(self, path):
        self._known(path)
        return self._params[path]

    def get(self, path):
        """The parameter's value as the scene file writes it (a string)."""
        return self[path]

    def __setitem__(self, path, value):
        self._known(path)
        self._params[path] = _text(value)
        self._changed = True

    def set(self, path, value):
        """Sets a parameter (bool, number, list or text; in the units the scene file uses).
        Checked by check() or before a run."""
        self[path] = value
        return self

    def text(self):
        """The scene as a .prm file's text (every parameter, defaults included)."""
        return _render(self._params)

    # -- checks and files
    def check(self):
        """The driver's checks of the scene as it now stands: a ValueError with the driver's
        message (parameter, value, what is allowed, the likely unit slip) where it refuses it.
        Returns the warnings (values a real design can have that look like a slip)."""
        if self._changed:
            shown = f"{self.path} (as changed in Python)"
            with tempfile.TemporaryDirectory(prefix="gearkit-scene-") as folder:
                # the file's name gives the output folder where Scene/name is empty
                tmp = os.path.join(folder, os.path.basename(self.path))
                if not tmp.endswith(".prm"):
                    tmp = os.path.splitext(tmp)[0] + ".prm"
                with open(tmp, "w", encoding="utf-8") as f:
                    f.write(self.text())
                try:
                    core = _core.read_scene(tmp, os.path.dirname(self.path), shown)
                except ValueError as e:
                    raise ValueError(str(e).replace(tmp, shown)) from None
            self._core, self._changed = core, False
        return list(self._core.warnings)

    def write(self, path):
        """Writes the scene as a .prm file (through a temporary file renamed into place)."""
        path = os.fspath(path)
        tmp = path + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(self.text())
        os.replace(tmp, path)

    # -- what the driver read
    @property
    def name(self):
        self.check()
        return self._core.name

    @property
    def outputs(self):
        self.check()
        return list(self._core.outputs)

    @property
    def pairs(self):
        self.check()
        return list(self._core.pairs)

    @property
    def trains(self):
        self.check()
        return list(self._core.trains)

    @property
    def warnings(self):
        return self.check()

    def _root(self, output_root):
        self.check()
        return os.fspath(output_root)

    def members(self, pair, output_root="out"):
        """(pinion flanks, gear flanks, assembly) of the scene's pair as the stages build them
        (the flanks stage run or reused in output_root's cache: a spiral bevel pinion with the
        modified roll it synthesises)."""
        return _core.pair_members(self._core, pair, self._root(output_root))

    def measured_members(self, pair, output_root="out"):
        """(pinion, gear) measured flanks of the pair as the measured stage stores them
        (MeasuredMember: CMM files read, or synthesised); Flanks.measured(m) interpolates one."""
        return _core.measured_members(self._core, pair, self._root(output_root))

    def tca_inputs(self, pair, output_root="out"):
        """The scene's pair as the stages build it, for gearkit.unloaded_tca:
        dict(pinion, gear, assembly, options)."""
        pinion, gear, assembly = self.members(pair, output_root)
        return dict(pinion=pinion, gear=gear, assembly=assembly,
                    options=self._core.tca_options(pair))

    def loaded_pair(self, pair, output_root="out"):
        """The pair on the compliance tables of its compliance stage (run, or reused from
        output_root's cache - the finite elements are computed once): a LoadedPair whose
        loaded_contact(torques) solves as the stiffness stage does, at any torque."""
        from .contact import LoadedPair
        return LoadedPair(_core.loaded_pair(self._core, pair, self._root(output_root)))

    def dynamics_model(self, pair, output_root="out", excitation="theoretical"):
        """The excitation ("theoretical" or "measured" flanks) of a pair as the dynamics stage
        builds it: a PairExcitation with its model (PairModel: the 14-DOF model on the TCA's
        tables in the system deflection's fixed point), static equilibrium, torques and the
        stage's sweep options, for gearkit.sweep. The stages it needs (flanks, ste, ...) run or
        are reused from the cache in output_root as by run_scene (the log to sys.stdout); the
        dynamics stage itself does not run. SI units."""
        self.check()
        return _core.dynamics_excitation(self._core, pair, excitation, os.fspath(output_root))

    def train_model(self, name, output_root="out"):
        """A gear train of the scene as the train stage builds it (TrainModel: bodies, meshes
        with their tooth pair tables, shafts), for gearkit.simulate_train; the stages it needs
        run or are reused from the cache in output_root. SI units."""
        self.check()
        return _core.train_model(self._core, name, os.fspath(output_root))

    def train_options(self, name):
        """The run options of a gear train as the scene sets them (TrainRunOptions, SI)."""
        self.check()
        return _core.train_run_options(self._core, name)

    def __repr__(self):
        return f"<gearkit.Scene {self.path}{' (changed)' if self._changed else ''}>"


def run_scene(scene, output_root="out", plot=False):
    """Runs a scene (a Scene or a scene file's path) through the driver's stage graph: the
    stages its outputs need, reusing verified cached ones, results.h5 written atomically, the
    report (and with plot=True the pictures) - what `gearkit [--plot] SCENE` does. The log goes
    to sys.stdout; Ctrl-C stops the run at its next progress step. Returns the Results."""
    if not isinstance(scene, Scene):
        scene = Scene(scene)
    scene.check()
    summary = _core.run_scene(scene._core, os.fspath(output_root), plot)
    results = Results(summary["results_file"])
    results.stages = summary["stages"]
    results.status = summary["status"]
    return results
