#!/usr/bin/python3
"""The twelve exports (six node types x FMI 2 and 3) checked with FMPy, an independent FMI
importer (docs/fmi.md, "Checked by hand with FMPy"); a check by hand, not a test: FMPy is
not a Debian package.

  PYTHONPATH=/path/to/fmpy/src tools/fmu/fmpy-check-exports.py BUILD_DIR WORK_DIR

Exports each type with BUILD_DIR/bin/mechsim into WORK_DIR, validates it
(fmpy.validation.validate_fmu) and simulates it over its default experiment
(fmpy.simulate_fmu); then runs config/scenes/cam_press.yaml natively and steps the exported
cam and follower with FMPy on the run's instants, with the inputs each node had (its
partner's logged samples), and prints how their outputs compare with the node logs."""
import glob, os, shutil, subprocess, sys

import numpy as np
from fmpy import read_model_description, simulate_fmu, extract
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXPORTS = [('cam_shaft', 'cam', 'cam_press.yaml'), ('follower', 'follower', 'cam_press.yaml'),
           ('servo_amplifier', 'servo', 'nc_slide_loop.yaml'), ('tachometer', 'tacho', 'nc_slide_loop.yaml'),
           ('slide', 'slide', 'nc_slide_loop.yaml'), ('cvt', 'cvt', 'line_shaft_4.yaml')]


def read_log(path):
    """A node's <node>.outputs.bin: the columns and the rows (libs/cosim output_log.h)."""
    with open(path, 'rb') as f:
        assert f.readline().startswith(b'mechsim-outputs')
        cols = f.readline().decode().strip().split(',')
        data = np.frombuffer(f.read(), dtype='<f8')
    n = len(data) // len(cols)
    return cols, data[:n * len(cols)].reshape(n, len(cols))


def export_and_simulate(mechsim, work):
    for node_type, participant, scene in EXPORTS:
        for fmi in (2, 3):
            f = os.path.join(work, '%s_fmi%d.fmu' % (node_type, fmi))
            subprocess.run([mechsim, 'fmu', 'export', node_type, '--scene', os.path.join(ROOT, 'config/scenes', scene),
                            '--participant', participant, '-o', f, '--fmi', str(fmi)], check=True, stdout=subprocess.DEVNULL)
            problems = validate_fmu(f)
            de = read_model_description(f).defaultExperiment
            h = float(de.stepSize)
            r = simulate_fmu(f, stop_time=min(float(de.stopTime), 2000 * h), step_size=h, output_interval=h)
            print('%-24s validation: %s; simulated %d steps to t = %.4g s' %
                  (os.path.basename(f), 'no problem' if not problems else problems, len(r) - 1, r['time'][-1]))


# Each FMU's inputs from its partner's topic fields (the node types' connection maps).
INPUTS = {'cam': ('follower', {'load_torque': 'drive_torque_rest', 'reflected_inertia': 'reflected_inertia'}),
          'follower': ('cam', {'angle': 'angle', 'speed': 'speed', 'lift': 'lift', 'lift_d1': 'lift_d1',
                               'lift_d2': 'lift_d2', 'pressure_angle': 'pressure_angle', 'acceleration_in': 'acceleration'})}


def compare_with_native(mechsim, work):
    runs = os.path.join(work, 'runs')
    subprocess.run([mechsim, 'launch', os.path.join(ROOT, 'config/scenes/cam_press.yaml'), '--runs-dir', runs,
                    '--no-plot', '--no-progress'], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    run = sorted(glob.glob(os.path.join(runs, 'cam_press-*')))[-1]
    logs = {n: read_log(os.path.join(run, n + '.outputs.bin')) for n in INPUTS}
    for node, node_type in (('cam', 'cam_shaft'), ('follower', 'follower')):
        for fmi in (2, 3):
            f = os.path.join(work, '%s_fmi%d.fmu' % (node_type, fmi))
            md = read_model_description(f)
            vr = {v.name: v.valueReference for v in md.modelVariables}
            unzipped = extract(f)
            fmu = (FMU2Slave if fmi == 2 else FMU3Slave)(guid=md.guid, unzipDirectory=unzipped,
                                                         modelIdentifier=md.coSimulation.modelIdentifier, instanceName=node)
            fmu.instantiate()
            cols, own = logs[node]
            partner_cols, partner = logs[INPUTS[node][0]]
            mapping = INPUTS[node][1]
            t = own[:, 0]
            u_at = lambda k: [partner[k, partner_cols.index(src)] for src in mapping.values()]
            set_values, get_values = (fmu.setReal, fmu.getReal) if fmi == 2 else (fmu.setFloat64, fmu.getFloat64)
            in_vrs = [vr[n] for n in mapping]
            names = [c for c in cols[1:] if c in vr]
            out_vrs = [vr[n] for n in names]
            if fmi == 2:
                fmu.setupExperiment(startTime=t[0], stopTime=t[-1])
                fmu.enterInitializationMode()
            else:
                fmu.enterInitializationMode(startTime=t[0], stopTime=t[-1])
            set_values(in_vrs, u_at(0))
            fmu.exitInitializationMode()
            got = np.zeros((len(t), len(out_vrs)))
            got[0] = get_values(out_vrs)
            for k in range(len(t) - 1):
                # The cam's input is a Jacobi hold (the partner's step-k sample); the follower's a
                # Gauss-Seidel one, interpolated between k and k+1 in the node: held at its mean here.
                u = u_at(k) if node == 'cam' else [(a + b) / 2 for a, b in zip(u_at(k), u_at(k + 1))]
                set_values(in_vrs, u)
                fmu.doStep(t[k], t[k + 1] - t[k])
                got[k + 1] = get_values(out_vrs)
            fmu.terminate()
            fmu.freeInstance()
            shutil.rmtree(unzipped, ignore_errors=True)
            ref = own[:, [cols.index(n) for n in names]]
            rel = np.abs(got - ref) / np.maximum(np.ptp(ref, axis=0), 1e-12)
            worst = np.unravel_index(np.argmax(rel), rel.shape)
            off = np.where(np.any(rel > 1e-3, axis=1))[0]
            print('%-9s FMI %d: %d instants, bit-identical at %d; worst %.3g of range (%s at t = %.4g s), rms %.3g; '
                  '%d instants off by more than 1e-3 of a range' %
                  (node, fmi, len(t), int(np.sum(np.all(got == ref, axis=1))), rel[worst], names[worst[1]], t[worst[0]],
                   np.sqrt(np.mean(rel ** 2)), len(off)))


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    mechsim = os.path.join(sys.argv[1], 'bin', 'mechsim')
    os.makedirs(sys.argv[2], exist_ok=True)
    export_and_simulate(mechsim, sys.argv[2])
    compare_with_native(mechsim, sys.argv[2])
