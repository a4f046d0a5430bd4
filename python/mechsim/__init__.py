"""mechsim from Python (docs/python.md).

Load and check a scene, set its keys, run it in this process (the path `mechsim bench` and
`mechsim sweep` use) and get every compared signal, the reference, the errors, the report
figures and the summary as NumPy arrays and dicts; read an MCAP recording into arrays; run a
design study with the designs of `mechsim sweep`, here or on any concurrent.futures
executor (a Dask distributed Client included).
"""

import json
import os
import subprocess
import tempfile

import numpy as np

from . import _core

__all__ = ["Scene", "Result", "Launched", "Table", "load", "run", "launch", "read_mcap", "sweep"]

# build/bin/mechsim beside build/python/mechsim/ (the package is laid out in the build tree).
MECHSIM = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, "bin", "mechsim")


class Scene:
    """A scene file with --set overrides, checked as `mechsim check` checks it."""

    def __init__(self, path, set=None):
        self.path = os.fspath(path)
        self.sets = list(set or [])
        self.yaml = _core.check(self.path, self.sets)  # ValueError names file, key and expectation

    def set(self, key, value):
        """A new Scene with KEY=VALUE added ('follower.spring.preload', '150 N')."""
        return Scene(self.path, self.sets + [f"{key}={value}"])

    @property
    def overrides(self):
        """The overrides as the loader takes them (participants.<p>.params.<k>=...)."""
        return _core.overrides(self.sets)

    def run(self, run_dir=None):
        """One full run in this process, compared with the monolithic reference."""
        return run(self.path, self.sets, run_dir)

    def __repr__(self):
        return f"Scene({self.path!r}, set={self.sets!r})"


class Result:
    """A run's outcome: arrays of every compared signal and dicts of its figures.

    outcome, reason, steps, wall_time_s; t (s); signals[name] = {"unit", "cosim",
    "reference", "error"} (arrays on t); errors[name] = {"max_abs_error", "max_rel_error",
    "rms_abs_error", "rms_rel_error", ...}; report (the figures as `mechsim launch` writes
    them, each beside the reference's); figures (the same flattened, as a sweep's columns);
    summary (the whole summary.json of the run); run_dir (its node logs).
    """

    def __init__(self, raw, run_dir):
        self.summary = json.loads(raw["summary"])
        self.row = self.summary["row"]
        self.outcome = self.row["outcome"]
        self.reason = self.row["reason"]
        self.steps = self.row["steps"]
        self.wall_time_s = self.row["wall_time_s"]
        arrays = raw["arrays"]
        self.t = arrays.get("t", np.empty(0))
        self.signals = dict(arrays.get("signals", {}))
        self.errors = self.summary.get("signals", {})
        self.report = self.summary.get("report", [])
        self.figures = {k: v for k, v in self.row.items() if "(" in k and not k.endswith("_rel_error")}
        self.run_dir = run_dir

    @property
    def ok(self):
        return self.outcome == "ok"

    def __repr__(self):
        return f"Result(outcome={self.outcome!r}, steps={self.steps}, wall_time_s={self.wall_time_s:.3g})"


def load(path, set=None):
    """The scene at `path` with --set texts, checked; raises ValueError when refused."""
    return Scene(path, set)


def run(path, set=None, run_dir=None):
    """Runs the scene in process into run_dir (a fresh temporary folder if None)."""
    if run_dir is None:
        run_dir = tempfile.mkdtemp(prefix="mechsim-run-")
    run_dir = os.fspath(run_dir)
    return Result(_core.run(os.fspath(path), list(set or []), run_dir), run_dir)


class Launched:
    """A `mechsim launch` run (processes over DDS): its summary and the compared signals.

    exit_code; summary (the run's summary.json, None when the scene was refused); t and
    signals[name] = {"cosim", "reference"} (arrays, from the run folder's signals.csv);
    run_dir; output (what the command printed).
    """

    def __init__(self, exit_code, summary, output):
        self.exit_code = exit_code
        self.summary = summary
        self.output = output
        self.t = np.empty(0)
        self.signals = {}
        self.run_dir = None
        csv = (summary or {}).get("files", {}).get("signals_csv")
        if csv and os.path.exists(csv):
            self.run_dir = os.path.dirname(csv)
            with open(csv) as f:
                header = f.readline().strip().split(",")
            data = np.loadtxt(csv, delimiter=",", skiprows=1, ndmin=2)
            self.t = data[:, 0]
            for i, name in enumerate(header[1:], start=1):
                if not name.endswith(".reference"):
                    self.signals[name] = {"cosim": data[:, i], "reference": data[:, header.index(name + ".reference")]}

    def __repr__(self):
        return f"Launched(exit_code={self.exit_code}, run_dir={self.run_dir!r})"


def launch(path, set=None, runs_dir="runs", args=()):
    """Runs the scene as `mechsim launch` does (its processes over DDS); args: more of its flags."""
    cmd = [MECHSIM, "launch", os.fspath(path), "--runs-dir", os.fspath(runs_dir), "--no-progress"]
    for s in set or []:
        cmd += ["--set", s]
    with tempfile.TemporaryDirectory(prefix="mechsim-launch-") as tmp:
        summary_path = os.path.join(tmp, "summary.json")
        done = subprocess.run(cmd + ["--json", summary_path] + list(args), stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)
        summary = None
        if os.path.exists(summary_path):
            with open(summary_path) as f:
                summary = json.load(f)
    return Launched(done.returncode, summary, done.stdout)


def read_mcap(path):
    """{topic: {"t", "step", "run_id", field: array}} of an MCAP recording (`mechsim record`)."""
    return _core.read_mcap(os.fspath(path))


class Table:
    """A study's table (sweep.json): rows as dicts, and column(name) as a float array."""

    def __init__(self, document):
        self.document = document
        self.rows = document["rows"]
        self.columns = document["columns"]
        self.design = document["design"]
        self.counts = document["counts"]
        self.files = document.get("files", {})

    def column(self, name):
        """The column as float64 (NaN where a row has no number: refused, text)."""
        out = np.full(len(self.rows), np.nan)
        for i, row in enumerate(self.rows):
            v = row.get(name)
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                out[i] = v
        return out

    def __getitem__(self, name):
        return self.column(name)

    def __len__(self):
        return len(self.rows)

    def __repr__(self):
        return f"Table({len(self.rows)} rows, counts={self.counts})"


def _run_point(scene, overrides, point, point_dir):
    """One point on an executor's worker: its row (JSON text). Module-level, so it pickles by name."""
    return _core.run_point(scene, overrides, point, point_dir)


def sweep(scene, vary, set=None, method="grid", samples=0, seed=1, jobs=0, out="sweep", resume=False, plots=True,
          progress=True, max_hours=24.0, executor=None):
    """A design study, as `mechsim sweep SCENE --vary ...` runs it; returns its Table.

    vary: ["KEY=SPEC", ...] (a list "a,b", "lo..hi:n", "lo..hi:n:log"). Without an executor
    the command's own runner takes the points (jobs threads in this process). With one
    (concurrent.futures.Executor, or a dask.distributed.Client) each point is submitted to
    it; the table is written here from the rows the workers return, each worker writing its
    point's folder under out/points/ (on its own disk when the workers are elsewhere).
    """
    if isinstance(vary, str):
        vary = [vary]
    scene_path = os.path.abspath(os.fspath(scene.path if isinstance(scene, Scene) else scene))
    sets = (scene.sets if isinstance(scene, Scene) else []) + list(set or [])
    out = os.path.abspath(os.fspath(out))
    options = json.dumps({"scene": scene_path, "set": sets, "vary": list(vary), "method": method, "samples": samples,
                          "seed": seed, "jobs": jobs, "out": out, "resume": resume, "progress": progress,
                          "plots": plots, "max_hours": max_hours})
    if executor is None:
        code = _core.run_sweep(options)
        if code not in (0, 3):
            raise RuntimeError(f"mechsim.sweep: stopped with code {code} (the reason is on stderr)")
        with open(os.path.join(out, "sweep.json")) as f:
            return Table(json.load(f))
    study = json.loads(_core.prepare(options))
    rows, futures = [], []
    for point, finished in zip(study["points"], study["finished"]):
        if finished is not None:
            rows.append(finished)
            continue
        point_dir = os.path.join(out, "points", "%05d" % point["index"])
        futures.append(executor.submit(_run_point, study["scene"], study["overrides"], json.dumps(point), point_dir))
    for future in futures:
        rows.append(json.loads(future.result()))
    return Table(json.loads(_core.write_outputs(options, json.dumps(rows))))
