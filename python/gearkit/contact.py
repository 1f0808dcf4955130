"""A scene's pair on the compliance tables its compliance stage computed once: the loaded
contact at any torque, on the theoretical flanks or on others (measured, modified)."""
import numpy as np

from .results import as_dataset


class LoadedPair:
    """`Scene.loaded_pair(pair)`: the pair's members (`members`: pinion flanks, gear flanks,
    assembly), both members' compliance tables (`pinion_table`, `gear_table`) and
    `loaded_contact(torques)`, solved as the stiffness stage solves it."""

    def __init__(self, core):
        self._core = core

    @property
    def name(self):
        return self._core.name

    @property
    def positions(self):
        """The scene's positions per mesh cycle."""
        return self._core.positions

    @property
    def members(self):
        return self._core.members

    @property
    def pinion_table(self):
        return self._core.pinion_table

    @property
    def gear_table(self):
        return self._core.gear_table

    def loaded_contact(self, torques, positions=0, flanks=None):
        """The loaded contact over one mesh cycle at each pinion torque [N m]: an xarray
        Dataset named, dimensioned and with units as results.h5's stiffness/<pair> (e_L, K_m,
        load per tooth pair, pressures, contact cells), the torque its coordinate. `positions`
        per mesh cycle (0: the scene's). `flanks` = (pinion flanks, gear flanks): other flanks
        on the same compliance (measured ones, or the theoretical with modifications), each
        cell reading the tables at its own place. A torque some position of which fails is
        reported in attrs["refused"] and dropped (as the stiffness stage does); none solved is
        a ValueError. The GIL is released; Ctrl-C stops it."""
        torques = [float(t) for t in np.atleast_1d(torques)]
        pinion, gear = flanks if flanks is not None else (None, None)
        values = self._core.loaded_contact(torques, int(positions), pinion, gear)
        refused = values.pop("refused")
        if not len(values["refused_torque"]):
            del values["refused_torque"]
        return as_dataset(f"stiffness/{self.name}", values,
                          {"refused": refused,
                           "method": "fast mode: FE compliance (tooth segments) + half-space "
                                     "contact" + ("" if flanks is None else
                                                  ", on the flanks given")})

    def __repr__(self):
        return f"<gearkit.LoadedPair {self.name}>"
