"""The flexible cam follower's lift-off speed over spring stiffness x preload (docs/studies.md).

A grid of mechsim runs of config/scenes/cam_lift_off.yaml over cam speed, spring preload and
spring stiffness (mechsim.sweep, every point a full co-simulation with its error against the
reference); for each spring, the lowest swept speed at which the follower lifts off, against
the kinetostatic prediction of the rigid follower (`mechsim cam-design --json`).

    PYTHONPATH=build/python python3 python/examples/lift_off_study.py [OUT_DIR]

Needs python3-matplotlib for the figure (OUT_DIR/lift_off_speed.png).
"""
import json
import os
import subprocess
import sys
import tempfile

import mechsim

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "config/scenes/cam_lift_off.yaml")
MECHSIM = os.path.join(ROOT, "build/bin/mechsim")
STIFFNESS = ["5 N/mm", "9 N/mm", "13 N/mm"]
PRELOAD = ["60 N", "90 N", "125 N"]
out = sys.argv[1] if len(sys.argv) > 1 else "lift_off_study"

table = mechsim.sweep(SCENE, ["cam.speed=40..120 rpm:17", "follower.spring.preload=" + ",".join(PRELOAD),
                              "follower.spring.stiffness=" + ",".join(STIFFNESS)], out=out)

def kinetostatic_rpm(stiffness, preload):
    with tempfile.NamedTemporaryFile(suffix=".json") as f:
        subprocess.run([MECHSIM, "cam-design", SCENE, "--set", "follower.spring.stiffness=" + stiffness,
                        "--set", "follower.spring.preload=" + preload, "--json", f.name],
                       check=True, stdout=subprocess.DEVNULL)
        return json.load(open(f.name))["lift_off_speed_rpm"]

results = []
for k in STIFFNESS:
    for f0 in PRELOAD:
        rows = [r for r in table.rows if r["outcome"] == "ok" and r["follower.spring.stiffness.text"] == k
                and r["follower.spring.preload.text"] == f0]
        rpm = lambda r: float(r["cam.speed.text"].split()[0])  # the speed as written: "65 rpm"
        lifted = sorted(rpm(r) for r in rows if r["max(follower.lift_off_count)"] > 0)
        simulated = lifted[0] if lifted else None
        # The co-simulation's worst error (max over the compared signals, share of range) in
        # contact and once the follower bounces.
        in_contact = max((r["worst_max_rel_error"] for r in rows if simulated is None or rpm(r) < simulated), default=None)
        bouncing = max((r["worst_max_rel_error"] for r in rows if simulated is not None and rpm(r) >= simulated), default=None)
        results.append({"stiffness": k, "preload": f0, "simulated_rpm": simulated,
                        "kinetostatic_rpm": kinetostatic_rpm(k, f0),
                        "worst_error_in_contact": in_contact, "worst_error_bouncing": bouncing})
        print(f"k {k:>8}  F0 {f0:>6}: lifts off from {simulated} rpm (5 rpm grid), kinetostatic "
              f"{results[-1]['kinetostatic_rpm']:.1f} rpm; worst error {100 * in_contact:.3f} % in contact, "
              f"{100 * bouncing:.1f} % bouncing" if bouncing is not None else "")
json.dump(results, open(os.path.join(out, "lift_off_speed.json"), "w"), indent=1)

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit("matplotlib missing (apt-get install python3-matplotlib): the table is in " + out)
fig, ax = plt.subplots(figsize=(9, 4.2))
for k, marker in zip(STIFFNESS, "os^"):
    rs = [r for r in results if r["stiffness"] == k]
    x = [float(r["preload"].split()[0]) for r in rs]
    ax.plot(x, [r["kinetostatic_rpm"] for r in rs], "--", marker=marker, color="gray")
    ax.plot(x, [r["simulated_rpm"] for r in rs], "-", marker=marker, label=f"k = {k}: simulated (5 rpm grid)")
ax.plot([], [], "--", color="gray", label="kinetostatic (rigid follower)")
ax.set_xlabel("spring preload [N]")
ax.set_ylabel("lift-off speed [rpm]")
ax.set_title("cam_lift_off: lowest cam speed with a lift-off")
ax.grid(True, alpha=0.3)
ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
fig.tight_layout()
fig.savefig(os.path.join(out, "lift_off_speed.png"), dpi=110)
print("figure:", os.path.join(out, "lift_off_speed.png"))
