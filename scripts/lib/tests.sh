# tests.sh: run the workspace's test binaries in parallel lanes. Sourced, not run.
#   load_test_binaries NAME...   TEST_BINS: "NAME=PATH" lines, the executables of `cargo test
#                                --test NAME...` (built if need be)
#   xinit_check DIR              the lock-step and system tests again with random power-up
#                                values (BOTSIM_X_SEED=1..4, two lanes), logs in DIR
#   run_lanes LOG LANE...        run each LANE (a quoted list of "SEED:NAME" or "NAME" items) in
#                                its own background shell, its items one after another; every
#                                item's output goes to LOG-<lane>.log. Fails, after all lanes
#                                end, with each failing lane's item and last lines.
# A test binary is run from the repository's root, as cargo runs the root package's tests. The
# lanes exist because the RTL tests' longest test is one thread (cpu_lockstep's 2,000 random
# programs): run one binary at a time and a core idles.

load_test_binaries() {
  local args=() t
  for t in "$@"; do args+=(--test "$t"); done
  TEST_BINS=$(cargo test --workspace --release -q --no-run --message-format=json "${args[@]}" | python3 -c '
import json, sys
found = {}
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["target"]["kind"] == ["test"]:
        found[m["target"]["name"]] = m["executable"]
missing = [n for n in sys.argv[1:] if n not in found]
if missing:
    sys.exit("no test binary for: " + " ".join(missing))
for n in sys.argv[1:]:
    print(n + "=" + found[n])
' "$@")
}

# Items are "NAME" (the binary of that test, from $TEST_BINS: "NAME=PATH" lines) or
# "SEED:NAME" (the same with BOTSIM_X_SEED=SEED).
run_lanes() {
  local log=$1 lane i=0 pids=() failed=0
  shift
  for lane in "$@"; do
    i=$((i + 1))
    (
      local item seed name bin
      for item in $lane; do
        seed= name=$item
        if [[ $item == *:* ]]; then seed=${item%%:*}; name=${item#*:}; fi
        bin=$(printf '%s\n' "$TEST_BINS" | sed -n "s|^$name=||p")
        echo "== $item" >>"$log-$i.log"
        if ! env ${seed:+BOTSIM_X_SEED=$seed} "$bin" -q >>"$log-$i.log" 2>&1; then
          echo "$item" >"$log-$i.failed"
          exit 1
        fi
      done
    ) &
    pids+=($!)
  done
  for p in "${pids[@]}"; do wait "$p" || failed=1; done
  if [ "$failed" = 1 ]; then
    for ((j = 1; j <= i; j++)); do
      if [ -e "$log-$j.failed" ]; then
        tail -30 "$log-$j.log" >&2
        echo "failed: $(cat "$log-$j.failed")" >&2
      fi
    done
    return 1
  fi
}

# The lock-step and system tests, run again with random power-up values (--x-initial unique,
# BOTSIM_X_SEED=1..4): the RTL needs no state the device does not set. Seeds 1 and 3 in one
# lane, 2 and 4 in the other.
XINIT_TESTS="cpu_lockstep cpu_timing bot_spec scoreboard many_models"
xinit_check() {
  local dir=$1 seed item lanes=("" "")
  load_test_binaries $XINIT_TESTS || return 1
  for seed in 1 2 3 4; do
    for item in $XINIT_TESTS; do lanes[$(((seed - 1) % 2))]+=" $seed:$item"; done
  done
  run_lanes "$dir/xinit" "${lanes[@]}" || { echo "xinit: fails with the BOTSIM_X_SEED above" >&2; return 1; }
}
