#!/usr/bin/env bash
# A test bed of N "hosts" on one machine: N network namespaces, each with an eth0 joined by
# a veth pair to a bridge that lives in a namespace of its own, addresses 10.77.0.1..N/24.
# Multicast is dropped on every host (iptables), as on many plant networks: a run on this
# bed proves that mechsim's multi-host configuration needs only unicast (docs/hosts.md).
#
#   tools/netns-hosts.sh up N     build the bed (removes an old one of the same prefix first)
#   tools/netns-hosts.sh down     remove it: every process inside, every namespace and link
#   tools/netns-hosts.sh exec I CMD...   run CMD on host I (1..N)
#
# MECHSIM_NETNS_PREFIX (default "msh") names the namespaces <prefix>-h1..N and <prefix>-br,
# so that two beds can exist side by side. Needs root (CAP_NET_ADMIN and CAP_SYS_ADMIN).
set -euo pipefail

prefix="${MECHSIM_NETNS_PREFIX:-msh}"
bridge_ns="$prefix-br"

usage() {
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
}

need_root() {
  if [ "$(id -u)" -ne 0 ]; then
    echo "netns-hosts: needs root (network namespaces, veth pairs, iptables)" >&2
    exit 77
  fi
  command -v ip >/dev/null || { echo "netns-hosts: 'ip' is missing (Debian package iproute2)" >&2; exit 1; }
}

our_namespaces() {
  ip netns list 2>/dev/null | awk '{print $1}' | grep -E "^$prefix-(h[0-9]+|br)$" || true
}

down() {
  local ns pids
  for ns in $(our_namespaces); do
    # Processes first: a namespace whose processes live on is not gone.
    pids=$(ip netns pids "$ns" 2>/dev/null || true)
    if [ -n "$pids" ]; then
      kill -TERM $pids 2>/dev/null || true
      for _ in 1 2 3 4 5 6 7 8 9 10; do
        pids=$(ip netns pids "$ns" 2>/dev/null || true)
        [ -z "$pids" ] && break
        sleep 0.1
      done
      [ -n "$pids" ] && kill -KILL $pids 2>/dev/null || true
    fi
  done
  # Deleting a namespace deletes the veth ends inside it, and with them their peers.
  for ns in $(our_namespaces); do ip netns del "$ns"; done
  for ns in $(our_namespaces); do
    echo "netns-hosts: namespace $ns is still there" >&2
    return 1
  done
}

up() {
  local n="$1" i ns
  [[ "$n" =~ ^[0-9]+$ ]] && [ "$n" -ge 1 ] && [ "$n" -le 20 ] || { echo "netns-hosts: up N: expected 1..20 hosts, got '$n'" >&2; exit 2; }
  down
  ip netns add "$bridge_ns"
  ip -n "$bridge_ns" link set lo up
  ip -n "$bridge_ns" link add br0 type bridge
  ip -n "$bridge_ns" link set br0 up
  for i in $(seq 1 "$n"); do
    ns="$prefix-h$i"
    ip netns add "$ns"
    ip -n "$ns" link set lo up
    # Created inside the host namespace, the bridge end moved out: no link ever exists in
    # the namespace this script runs in.
    ip -n "$ns" link add eth0 type veth peer name "vh$i" netns "$bridge_ns"
    ip -n "$ns" addr add "10.77.0.$i/24" dev eth0
    ip -n "$ns" link set eth0 up
    ip -n "$bridge_ns" link set "vh$i" master br0
    ip -n "$bridge_ns" link set "vh$i" up
    # Unicast only, as on a plant network that blocks multicast.
    if command -v iptables >/dev/null; then
      ip netns exec "$ns" iptables -A OUTPUT -o eth0 -d 224.0.0.0/4 -j DROP
      ip netns exec "$ns" iptables -A INPUT -i eth0 -d 224.0.0.0/4 -j DROP
    fi
  done
}

case "${1:-}" in
  up) need_root; up "${2:-}";;
  down) need_root; down;;
  exec)
    need_root
    i="${2:-}"; shift 2 || true
    exec ip netns exec "$prefix-h$i" "$@";;
  -h|--help|help) usage;;
  *) usage >&2; exit 2;;
esac
