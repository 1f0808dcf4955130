"""gearkit.Scene: every parameter by path with its value as the driver read it, set and checked
with the driver's own checks (a ValueError with its message), unknown paths refused with the
near names, written back and read again to the same parameters."""
import os

import pytest

import gearkit


def test_parameters_by_path_as_the_driver_read_them(source_dir):
    scene = gearkit.Scene(os.path.join(source_dir, "cases", "default.prm"))
    assert scene.name == "default"
    assert scene.pairs == ["fzg"]
    assert scene["Flanks/fzg/Pinion/number of teeth"] == "16"
    assert scene["Flanks/fzg/Gear/number of teeth"] == "24"
    # a default the file does not set is there too, as the driver declares it
    assert scene["Dynamics/fzg/record cycles"] == "50"
    assert len(scene.parameters()) > 200


def test_set_checked_with_the_drivers_checks(source_dir, tmp_path):
    scene = gearkit.Scene(os.path.join(source_dir, "cases", "default.prm"))
    scene["Dynamics/fzg/speeds"] = 7
    assert scene.check() == scene.warnings
    assert scene["Dynamics/fzg/speeds"] == "7"
    # a value the pattern refuses, and a unit slip the plausibility check names
    scene["Flanks/fzg/Pinion/number of teeth"] = 0
    with pytest.raises(ValueError, match="number of teeth"):
        scene.check()
    scene["Flanks/fzg/Pinion/number of teeth"] = 16
    scene["Flanks/fzg/Pinion/face width"] = 0.014  # metres in a mm field
    with pytest.raises(ValueError) as e:
        scene.check()
    message = str(e.value)
    assert "face width" in message and "(as changed in Python)" in message
    assert "gearkit-scene-" not in message  # the temporary file is not what the user knows


def test_unknown_parameter_named_with_the_near_ones(source_dir):
    scene = gearkit.Scene(os.path.join(source_dir, "cases", "default.prm"))
    with pytest.raises(KeyError, match="settle cycles"):
        scene["Dynamics/fzg/settle cycle"] = 100


def test_written_and_read_again_to_the_same_parameters(source_dir, tmp_path):
    for case in ("default.prm", "hunting.prm", "published_pairs.prm",
                 os.path.join("seed002_steady", "seed002_steady.prm")):
        scene = gearkit.Scene(os.path.join(source_dir, "cases", case))
        scene["TCA/" + scene.pairs[0] + "/positions per mesh cycle"] = 24
        path = tmp_path / os.path.basename(case)
        scene.write(path)
        again = gearkit.Scene(path)
        assert again.parameters() == scene.parameters(), case
        assert again.name == scene.name


def test_a_bad_scene_file_is_a_value_error(tmp_path):
    bad = tmp_path / "bad.prm"
    bad.write_text("subsection Scene\n  set outputs = nothing\nend\n")
    with pytest.raises(ValueError, match="outputs"):
        gearkit.Scene(bad)


def test_library_tca_of_conjugate_involutes_is_flat():
    """Exact solution: unmodified involute flanks transmit uniformly at any centre distance
    (e_0 constant to round-off), and a gear's data are checked (ValueError naming the field)."""
    p, g = gearkit.InvoluteGearData(), gearkit.InvoluteGearData()
    p.teeth, g.teeth = 19, 37
    p.normal_module = g.normal_module = 2e-3
    pinion, gear = gearkit.create_pair(p, g)
    a = gearkit.working_centre_distance(pinion, gear)
    options = gearkit.TcaOptions()
    options.positions_per_mesh = 12
    for centre_distance in (a, a + 0.1e-3):
        e0 = gearkit.unloaded_tca(pinion, gear, centre_distance, options)["transmission_error"]
        assert e0.max() - e0.min() < 1e-10
    bad = gearkit.InvoluteGearData()
    bad.teeth = 2
    with pytest.raises(ValueError, match="teeth"):
        gearkit.InvoluteGear.create(bad)


def test_a_changed_scene_finds_its_files_beside_the_original(source_dir, case_out, tmp_path):
    """Files a scene names relatively are found beside the scene file, also once it is changed
    in Python (the driver then reads a rewritten copy in a temporary folder): the default pair's
    measurements exported by the executable (out/default/cmm) read back as CMM files."""
    import shutil
    shutil.copy(os.path.join(source_dir, "cases", "default.prm"), tmp_path / "mine.prm")
    for member in ("pinion", "gear"):
        shutil.copy(os.path.join(case_out, "default", "cmm", f"fzg_{member}.cmm"), tmp_path)
    scene = gearkit.Scene(tmp_path / "mine.prm")
    scene["Scene/outputs"] = "measured"
    scene["Measured flanks/fzg/source"] = "cmm files"
    scene["Measured flanks/fzg/pinion file"] = "fzg_pinion.cmm"
    scene["Measured flanks/fzg/gear file"] = "fzg_gear.cmm"
    scene.check()
    results = gearkit.run_scene(scene, output_root=tmp_path / "out")
    assert results.status == 0
    assert len(results.groups("measured/fzg/pinion")) == 32  # every pinion flank measured
    # a file that is not there is named as the scene names it
    scene["Measured flanks/fzg/gear file"] = "missing.cmm"
    with pytest.raises(ValueError, match="missing.cmm"):
        scene.check()
