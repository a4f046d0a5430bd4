"""mechsim.sweep gives `mechsim sweep`'s table for the same design: on the command's own
runner, on a thread pool and on a local Dask cluster of two worker processes; and an MCAP
recording of `mechsim launch` read into arrays holds the numbers of the in-process run."""
import concurrent.futures
import glob
import json
import os
import subprocess
import tempfile

import numpy as np

import mechsim
from script_tests import run_tests

BIN = os.environ["MECHSIM_BIN_DIR"]
CAM_PRESS = os.path.join(os.environ["MECHSIM_SOURCE_DIR"], "config", "scenes", "cam_press.yaml")
SETS = ["time.end=0.2 s"]
VARY = ["follower.spring.preload=100 N,150 N", "follower.mass=25 kg,-1 kg"]
WORK = tempfile.mkdtemp(prefix="mechsim-python-sweep-")


def comparable(rows):
    """The rows without what differs from run to run (wall time)."""
    return [{k: v for k, v in r.items() if k != "wall_time_s"} for r in rows]


def command_table():
    out = os.path.join(WORK, "command")
    args = [os.path.join(BIN, "mechsim"), "sweep", CAM_PRESS, "--out", out, "--jobs", "2", "--no-plot", "--no-progress"]
    for s in SETS:
        args += ["--set", s]
    for v in VARY:
        args += ["--vary", v]
    subprocess.run(args, check=True, timeout=240)
    with open(os.path.join(out, "sweep.json")) as f:
        return json.load(f)


def test_same_table_everywhere():
    expected = command_table()
    assert expected["counts"] == {"ok": 2, "refused": 2}, expected["counts"]
    rows = comparable(expected["rows"])

    here = mechsim.sweep(CAM_PRESS, VARY, set=SETS, jobs=2, out=os.path.join(WORK, "here"), plots=False, progress=False)
    assert comparable(here.rows) == rows
    assert here.columns == expected["columns"]
    # Arrays of the table: the refused points are NaN.
    fmin = here["min(follower.contact_force)"]
    assert np.isnan(fmin[1]) and np.isnan(fmin[3]) and abs(fmin[2] - fmin[0] - 50.0) < 1e-6

    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        threads = mechsim.sweep(CAM_PRESS, VARY, set=SETS, out=os.path.join(WORK, "threads"), plots=False, executor=pool)
    assert comparable(threads.rows) == rows

    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        print("test_same_table_everywhere: Dask part skipped: python3-distributed is not installed")
        return
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        dask_table = mechsim.sweep(CAM_PRESS, VARY, set=SETS, out=os.path.join(WORK, "dask"), plots=False,
                                   executor=client)
    assert comparable(dask_table.rows) == rows
    with open(os.path.join(WORK, "dask", "sweep.json")) as f:
        assert comparable(json.load(f)["rows"]) == rows


def test_launch_and_mcap_into_arrays():
    runs = os.path.join(WORK, "runs")
    launched = mechsim.launch(CAM_PRESS, ["time.end=0.1 s", "record=true"], runs_dir=runs, args=["--no-plot"])
    assert launched.exit_code == 0, launched.output
    (bag,) = glob.glob(os.path.join(runs, "*", "recording.mcap"))
    topics = mechsim.read_mcap(bag)
    follower = topics["follower/state"]
    steps = follower["step"]
    assert np.all(np.diff(steps) == 1), "one sample per step, in order"
    assert np.allclose(follower["t"], steps * 1e-3, rtol=0, atol=1e-12)
    # The in-process run computes what the DDS processes computed, bit for bit: in the
    # recording, and in the launch's signals.csv (written with 17 digits: exact).
    run = mechsim.run(CAM_PRESS, ["time.end=0.1 s"])
    k = steps.astype(int)
    assert np.array_equal(follower["contact_force"], run.signals["follower.contact_force"]["cosim"][k])
    assert np.array_equal(launched.t, run.t)
    for name, s in run.signals.items():
        assert np.array_equal(launched.signals[name]["cosim"], s["cosim"]), name
        assert np.array_equal(launched.signals[name]["reference"], s["reference"]), name
    assert launched.summary["signals"]["follower.drive_torque"]["max_abs_error"] == run.errors["follower.drive_torque"]["max_abs_error"]


if __name__ == "__main__":
    run_tests(globals())
