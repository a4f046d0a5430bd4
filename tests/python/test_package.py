"""The package `mechsim` (docs/python.md): a scene loaded, checked, set and run in process."""
import os
import tempfile

import numpy as np

import mechsim
from script_tests import run_tests

SCENES = os.path.join(os.environ["MECHSIM_SOURCE_DIR"], "config", "scenes")
CAM_PRESS = os.path.join(SCENES, "cam_press.yaml")


def refused(fn, expected):
    try:
        fn()
    except ValueError as e:
        assert expected in str(e), f"{expected!r} not in {e}"
        return
    raise AssertionError(f"accepted, expected a refusal with {expected!r}")


def test_load_check_set():
    scene = mechsim.load(CAM_PRESS)
    assert "cam_press" in scene.yaml
    shorter = scene.set("time.end", "0.1 s").set("follower.spring.preload", "150 N")
    assert shorter.overrides == ["time.end=0.1 s", "participants.follower.params.spring.preload=150 N"]
    assert "150" in shorter.yaml
    refused(lambda: scene.set("follower.bogus", "1"), "unknown key 'bogus'")
    refused(lambda: scene.set("follower.mass", "25 mm"), "expected a mass")


def test_run_in_process():
    run_dir = tempfile.mkdtemp(prefix="mechsim-python-test-")
    r = mechsim.load(CAM_PRESS, ["time.end=0.2 s"]).run(run_dir)
    assert r.ok, r.reason
    assert r.steps == 200  # 0.2 s at 1 ms
    assert r.t.shape == (201,) and r.t[0] == 0.0 and abs(r.t[-1] - 0.2) < 1e-12
    assert set(r.signals) == {"follower.contact_force", "follower.drive_torque", "cam.pressure_angle", "cam.shaft_torque"}
    for name, s in r.signals.items():
        assert s["cosim"].shape == r.t.shape and s["reference"].shape == r.t.shape
        assert np.array_equal(s["error"], s["cosim"] - s["reference"])
        # The summary's figure is the largest of these differences, computed in C++ from the same arrays.
        assert abs(np.max(np.abs(s["error"])) - r.errors[name]["max_abs_error"]) <= 1e-12 * max(1.0, r.errors[name]["max_abs_error"])
    assert r.signals["follower.contact_force"]["unit"] == "N"
    # The report's minimum contact force is the minimum of the co-simulated series.
    fc = r.signals["follower.contact_force"]["cosim"]
    assert r.figures["min(follower.contact_force)"] == np.min(fc)
    assert os.path.exists(os.path.join(run_dir, "follower.outputs.bin"))
    # A scene the run refuses is an outcome, not an exception.
    bad = mechsim.run(CAM_PRESS, ["follower.mass=-1 kg"])
    assert bad.outcome == "refused" and "mass" in bad.reason and bad.t.size == 0


if __name__ == "__main__":
    run_tests(globals())
