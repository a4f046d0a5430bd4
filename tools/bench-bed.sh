# Sourced by the bench scripts that run nc_slide_loop across three hosts of the namespace
# test bed (bench-hosts.sh, bench-faults.sh): builds the bed (MECHSIM_NETNS_PREFIX), starts
# an agent on hosts 2 and 3 on domain 7, and removes all of it when the script exits.
# Defines: mechsim, scene, work; three_host_args (the --set options that place servo, tacho
# and slide on hosts a, b, c); rate FILE.json (its steps/s).
[ "$(id -u)" -eq 0 ] || { echo "$(basename "$0"): needs root (network namespaces)" >&2; exit 77; }
mechsim="$PWD/build/bin/mechsim"
scene="$PWD/config/scenes/nc_slide_loop.yaml"
work="$(mktemp -d /tmp/mechsim-bench-bed.XXXXXX)"
bed_agents=()
bed_cleanup() {
  for pid in "${bed_agents[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  tools/netns-hosts.sh down
  rm -rf "$work"
}
trap bed_cleanup EXIT
tools/netns-hosts.sh up 3
for h in 2 3; do
  tools/netns-hosts.sh exec "$h" "$mechsim" agent --domain 7 --address "10.77.0.$h" --peers 10.77.0.1 --allow-unauthenticated \
    --work-dir "$work/agent$h" > "$work/agent$h.log" 2>&1 &
  bed_agents+=($!)
done
three_host_args=(--set dds.domain=7 --set hosts.a.address=10.77.0.1 --set hosts.b.address=10.77.0.2
                 --set hosts.b.control=dds_agent --set hosts.c.control=dds_agent
                 --set hosts.c.address=10.77.0.3 --set participants.servo.host=a --set participants.tacho.host=b
                 --set participants.slide.host=c)
rate() { grep -o '"steps_per_second": *[0-9.e+]*' "$1" | head -1 | sed 's/.*: *//'; }
