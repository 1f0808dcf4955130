"""Results from Python: results.h5 read as NumPy arrays and xarray Datasets, each dataset with
the units and description of the results schema (driver/results_schema.cc, the one place they
are named), its dimensions named by the schema's shape ("torques x positions")."""
import functools
import re

from . import _core


@functools.lru_cache(maxsize=1)
def results_schema():
    """Every dataset gearkit writes: a list of dicts with group (a pattern, <...> for the names
    that vary), dataset, shape, units and description - what `gearkit --print-results` prints."""
    return tuple(_core.results_schema())


def _group_regex(pattern):
    return re.compile("/".join(
        "".join("[^/]+" if part.startswith("<") else re.escape(part)
                for part in re.split(r"(<[^>]*>)", level) if part)
        for level in pattern.split("/")) + "$")


@functools.lru_cache(maxsize=1)
def _patterns():
    return [(_group_regex(e["group"]), e) for e in results_schema()]


def schema_entry(group, dataset):
    """The schema's entry of `dataset` in the group at path `group` ("stiffness/fzg"); a
    KeyError naming both where the schema has none."""
    group = group.strip("/")
    for regex, e in _patterns():
        if e["dataset"] == dataset and regex.match(group):
            return e
    raise KeyError(f"no dataset '{dataset}' in group '{group}' in the results schema "
                   "(gearkit --print-results lists them)")


def _dimensions(shape):
    """The dimension names of a schema shape: "torques x positions" -> torques, positions; a
    fixed length by what it holds, "2 (radius, axial)" -> radius_axial, else "3" -> n3;
    scalars none."""
    words = re.sub(r",\s*integers?$", "", shape.strip())
    if words in ("scalar", "integer", "integers"):
        return []
    dims = []
    for word in words.split(" x "):
        m = re.match(r"\s*([^(]*?)\s*(?:\((.*)\))?\s*$", word)
        name, inside = m.group(1), m.group(2)
        if name.isdigit():
            name = "_".join(re.findall(r"[A-Za-z0-9]+", inside)) if inside else "n" + name
        dims.append(name.replace(" ", "_"))
    return dims


class Results:
    """A results.h5: `results["stiffness/fzg/mesh_stiffness"]` a NumPy array,
    `results.dataset("stiffness/fzg")` the group as an xarray Dataset, `results.attrs` the
    run's attributes (scene, stages, warnings, notes, ...)."""

    def __init__(self, path):
        self.path = str(path)
        self.stages, self.status = [], 0
        self._attrs = None

    @property
    def attrs(self):
        """The run's attributes (read on first use: h5py and NumPy are imported when the
        results are read, so a run from Python starts as light as the executable)."""
        if self._attrs is None:
            import h5py
            with h5py.File(self.path, "r") as f:
                self._attrs = {k: (v.decode() if isinstance(v, bytes) else v)
                               for k, v in f.attrs.items()}
        return self._attrs

    def __getitem__(self, path):
        import h5py
        with h5py.File(self.path, "r") as f:
            return f[path][()]

    def groups(self, path="/"):
        """The names of the groups in the group at `path`."""
        import h5py
        with h5py.File(self.path, "r") as f:
            return [k for k, v in f[path].items() if isinstance(v, h5py.Group)]

    def datasets(self, path="/"):
        """The names of the datasets in the group at `path`."""
        import h5py
        with h5py.File(self.path, "r") as f:
            return [k for k, v in f[path].items() if isinstance(v, h5py.Dataset)]

    def dataset(self, path):
        """The datasets of the group at `path` as an xarray Dataset (as_dataset): dimensions
        named by the schema's shapes, coordinates, every variable with its `units` and
        `description`; the group's attributes as the Dataset's."""
        import h5py
        group = path.strip("/")
        with h5py.File(self.path, "r") as f:
            g = f[group]
            attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in g.attrs.items()}
            values = {name: obj[()] for name, obj in g.items() if isinstance(obj, h5py.Dataset)}
            descriptions = {name: obj.attrs["description"] for name, obj in g.items()
                            if isinstance(obj, h5py.Dataset) and "description" in obj.attrs}
        return as_dataset(group, values, attrs, descriptions)

    def __repr__(self):
        return f"<gearkit.Results {self.path}>"


def as_dataset(group, values, attrs=None, descriptions=None):
    """Arrays named as the results schema names the datasets of `group` ("stiffness/fzg") as an
    xarray Dataset: dimensions named by the schema's shapes (a dimension whose length differs
    between datasets gets the dataset's name as suffix), a 1-D dataset named as its dimension's
    singular (torque for torques, speed for speeds) its coordinate, every variable with its
    `units` and `description` (the schema's, or `descriptions[name]`). A KeyError for a name
    the schema does not have there."""
    import numpy as np
    import xarray as xr

    group = group.strip("/")
    variables, lengths = {}, {}
    for name, values_of in values.items():
        entry = schema_entry(group, name)
        dims = _dimensions(entry["shape"])
        if len(dims) != np.ndim(values_of):
            dims = [f"{name}_{k}" for k in range(np.ndim(values_of))]
        dims = [d if lengths.setdefault(d, n) == n else f"{d}_{name}"
                for d, n in zip(dims, np.shape(values_of))]
        description = (descriptions or {}).get(name, entry["description"])
        if isinstance(description, bytes):
            description = description.decode()
        variables[name] = (dims, values_of, {"units": entry["units"],
                                             "description": description})
    # a dimension named as a variable that is not its coordinate ("iterations": a count, and
    # the length of `change`) is renamed
    for name, (dims, values_of, var_attrs) in list(variables.items()):
        renamed = [d + "_index" if d in variables and variables[d][0] != [d] else d for d in dims]
        variables[name] = (renamed, values_of, var_attrs)
    coords = {}
    for name, (dims, values_of, var_attrs) in list(variables.items()):
        if len(dims) == 1 and dims[0] in (name + "s", name + "es"):
            coords[dims[0]] = (dims, values_of, var_attrs)
    return xr.Dataset(dict(variables), coords=coords, attrs=dict(attrs or {}))
