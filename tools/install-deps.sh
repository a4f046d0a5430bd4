#!/usr/bin/env bash
# Installs the Debian 12 packages mechsim needs (apt-get), only when one is missing; safe to
# run again. Two sets, so that the first run does not wait for what only the tests need:
#   tools/install-deps.sh          build and run (README command 1: tools/setup-and-run.sh)
#   tools/install-deps.sh --tests  also the test suites, the fuzz build and the host test bed
#                                  (README command 2: tools/run-tests.sh)
set -euo pipefail

packages=(
  cmake g++ make ninja-build pkg-config git   # build (tools/build.sh uses Ninja when present)
  cyclonedds-dev cyclonedds-tools         # DDS (C API, idlc, ddsperf)
  libfastrtps-dev fastddsgen              # Fast DDS 2.9 (C++ API) and its IDL generator
  default-jre-headless fastdds-tools      # fastddsgen runs on Java; `fastdds shm clean`
  libsundials-dev                         # CVODE / ARKODE 6.4
  libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev
  gnuplot-nox                             # PNG plots
  libzstd-dev liblz4-dev                  # MCAP chunk compression
  libzip-dev libpugixml-dev               # FMU import: the archive and modelDescription.xml
  openssl                                 # `mechsim security init` (docs/security.md)
  libwebsocketpp-dev libasio-dev          # the live server (header-only; docs/live.md)
  pybind11-dev python3-dev python3-numpy  # the Python package `mechsim` (docs/python.md)
)
case "${1:-}" in
  "") ;;
  --tests)
    packages+=(
      libgtest-dev libbenchmark-dev       # tests, benchmarks
      iproute2 iptables                   # the multi-host test bed (tools/netns-hosts.sh)
      openssh-server openssh-client       # its sshd per host: runs over ssh (tests/hosts, docs/hosts.md)
      clang libclang-rt-14-dev            # sanitizer + libFuzzer build only (label fuzz, .ci/run)
      python3-dask python3-distributed    # mechsim.sweep on a local Dask cluster (docs/python.md)
    )
    # node + npm run the third-party MCAP reader test; machines that already have a Node.js
    # (e.g. from NodeSource, whose nodejs conflicts with Debian's npm) keep theirs.
    command -v node >/dev/null && command -v npm >/dev/null || packages+=(nodejs npm)
    ;;
  *) echo "usage: tools/install-deps.sh [--tests]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
