#!/usr/bin/env bash
# Per-step cost of an FMU participant against the same law as a native participant, in the
# same scene, measured interleaved (issue 27 item 7; docs/fmi.md "Cost of an FMU
# participant"). The NC loop's servo amplifier is played by
#   native        the native ServoAmplifierBlock (the scene as shipped)
#   me_fmi2       the test FMU of the same law, model exchange (tests/fmus, integrated by the
#                 node's CVODE like the native block)
#   export_fmi2   the native amplifier exported by `mechsim fmu export` (co-simulation, its
#                 own CVODE inside fmi2DoStep), step = the macro step
#   export_fmi3   the same as FMI 3
# Needs the build's mechsim, mechsim-bench-fmu and test FMUs (target test_fmus).
#   tools/bench-fmu.sh [ROUNDS] [END_S]
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-5}
end=${2:-0.05}
build=${BUILD_DIR:-build}
scene=config/scenes/nc_slide_loop.yaml
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for v in 2 3; do
  "$build/bin/mechsim" fmu export servo_amplifier --scene "$scene" --participant servo --fmi "$v" \
    -o "$tmp/servo_fmi$v.fmu" >/dev/null
done
params='parameters: {position_gain: 40 1/s, velocity_gain: 10, integral_time: 10 ms, antiwindup_time: 5 ms, tacho_filter_time: 0.3 ms, voltage_limit: 50 V, step_distance: 0.1 mm}'
"$build/bin/mechsim-bench-fmu" --scene "$scene" --rounds "$rounds" --end "$end" \
  --fmu "me_fmi2={file: $(cd "$build" && pwd)/tests/fmus/servo_amplifier_fmi2_me.fmu, interface: model-exchange, $params}" \
  --fmu "export_fmi2={file: $tmp/servo_fmi2.fmu, interface: co-simulation}" \
  --fmu "export_fmi3={file: $tmp/servo_fmi3.fmu, interface: co-simulation}"
