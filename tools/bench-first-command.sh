#!/usr/bin/env bash
# README's first command on a fresh Debian 12, timed (issue 31, item 2: <= 300 s on 2 cores to
# the first summary): a debootstrap minbase chroot of bookworm, a clean clone of REPO at REF
# inside it, then `tools/setup-and-run.sh --no-plot` as a newcomer runs it (packages, build,
# the cam press run). Prints the wall time of the whole command, of its apt-get part and of
# the build and run, and the CPU seconds (user, sys) of it all.
#   sudo tools/bench-first-command.sh [REPO] [REF]     defaults: this checkout, HEAD
# Needs root, debootstrap and network access to deb.debian.org. The minbase system is cached
# as a tarball (MECHSIM_MINBASE_TAR, default /var/tmp/mechsim-bookworm-minbase.tar) so a
# repetition does not wait for debootstrap; the chroot (MECHSIM_FRESH_ROOT, default
# /var/tmp/mechsim-fresh-root) is made anew each time. Measure on an otherwise idle machine.
set -euo pipefail
repo=$(realpath "${1:-$(dirname "$0")/..}")
ref=${2:-HEAD}
tar=${MECHSIM_MINBASE_TAR:-/var/tmp/mechsim-bookworm-minbase.tar}
root=${MECHSIM_FRESH_ROOT:-/var/tmp/mechsim-fresh-root}
[ "$(id -u)" -eq 0 ] || { echo "bench-first-command: needs root (debootstrap, chroot, mounts)" >&2; exit 1; }
command -v debootstrap >/dev/null || { echo "bench-first-command: needs debootstrap (apt-get install debootstrap)" >&2; exit 1; }

cleanup() {
  for m in dev/shm sys dev proc; do mountpoint -q "$root/$m" && umount "$root/$m"; done
  return 0
}
trap cleanup EXIT
cleanup
rm -rf "$root"
if [ ! -f "$tar" ]; then
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian
  tar -C "$root" -cf "$tar" .
else
  mkdir -p "$root" && tar -C "$root" -xf "$tar"
fi
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"
mount -t sysfs sys "$root/sys"
mount -t tmpfs tmpfs "$root/dev/shm"
cp /etc/resolv.conf "$root/etc/resolv.conf"
# A clean clone, as a user has it (git itself is not installed in the chroot yet: cloned from outside).
git clone -q "$repo" "$root/root/mechsim"
git -C "$root/root/mechsim" checkout -q "$ref"
echo "bench-first-command: $(git -C "$root/root/mechsim" log -1 --format='%h %s' | cut -c1-100), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"

chroot "$root" /bin/bash -c '
  cd /root/mechsim
  ms() { echo $(( $(date +%s%N) / 1000000 )); }
  seconds() { local m=${1%%m*} s=${1#*m}; s=${s%s}; echo "$(( m * 60 + ${s%.*} )).${s#*.}"; }
  start=$(ms)
  # The apt-get part first, on its own (the command runs it again and finds nothing missing).
  tools/install-deps.sh > /root/deps.log 2>&1 || { echo "install-deps failed:"; tail -5 /root/deps.log; exit 1; }
  deps=$(ms)
  rc=0
  tools/setup-and-run.sh --no-plot > /root/run.log 2>&1 || rc=$?
  end=$(ms)
  grep -q "run folder:" /root/run.log || rc=${rc/#0/1}
  # CPU of the children (install-deps and the command): the second line of `times`.
  times > /root/times.txt   # in this shell: a subshell would not count the children
  read -r cu cs < <(sed -n 2p /root/times.txt)
  echo "first command rc=$rc: $(( (end - start) / 1000 )) s to the first summary" \
       "(apt-get $(( (deps - start) / 1000 )) s, build and run $(( (end - deps) / 1000 )) s);" \
       "CPU of both: user $(seconds "$cu") s, sys $(seconds "$cs") s"
  tail -n 3 /root/run.log
'
