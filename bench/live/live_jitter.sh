#!/usr/bin/env bash
# The control-loop period on etroll-emulated (real-time pacing, the servo bus
# emulated on a pty) in three conditions, run interleaved ROUNDS times:
#   none   rollsense run without --live
#   live   with --live (nobody watching: the feed formats and queues anyway)
#   slow   with --live and one client that asks for the event stream and
#          never reads it (dropped after 2 s of a full socket)
# Each run is one trial (about 11 s). Prints p50/p99/max of the period per
# condition (mean over rounds) and the paired difference of p99 against
# `none` with its 95 % confidence interval (Student t over the rounds).
#   bench/live/live_jitter.sh [build-dir] [rounds]
set -euo pipefail
build=${1:-build}
rounds=${2:-5}
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
emu_pid=
trap '[[ -n $emu_pid ]] && kill "$emu_pid" 2>/dev/null; rm -rf "$work"' EXIT
"$build/bin/rollsense-dxl-emu" --link "$work/bus" >"$work/emu.txt" 2>&1 &
emu_pid=$!
for _ in $(seq 100); do [[ -e $work/bus ]] && break; sleep 0.05; done

# A client that asks for /events and never reads (its receive buffer kept small).
slow_client() {
  python3 - "$1" <<'PY' &
import socket, sys, time
port = int(sys.argv[1])
s = socket.socket()
s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
s.connect(("127.0.0.1", port))
s.sendall(b"GET /events HTTP/1.1\r\nHost: x\r\n\r\n")
time.sleep(60)
PY
}

one_run() {  # condition round -> "condition p50 p99 max" (ms)
  local cond=$1 i=$2 log=$work/$1-$2.txt args=()
  [[ $cond != none ]] && args=(--live=0)
  "$build/bin/rollsense" run "$root/bench/live/one_trial.lua" --profile etroll-emulated \
    --set "dxl_device=$work/bus" --out "$work/out-$cond-$i" -q --no-progress "${args[@]}" 2>"$log" &
  local pid=$! client=
  if [[ $cond == slow ]]; then
    local port=
    for _ in $(seq 200); do
      port=$(sed -n 's/^live view: http:\/\/127\.0\.0\.1:\([0-9]*\)\/$/\1/p' "$log")
      [[ -n $port ]] && break
      sleep 0.02
    done
    slow_client "$port"
    client=$!
  fi
  wait "$pid"
  [[ -n $client ]] && kill "$client" 2>/dev/null
  sed -n 's/.*period p50 \([0-9.]*\) ms, p99 \([0-9.]*\) ms, max \([0-9.]*\) ms.*/'"$cond"' \1 \2 \3/p' "$log"
}

for i in $(seq 1 "$rounds"); do
  # Interleaved, the order rotating, so drift of the machine's load spreads over all three.
  case $((i % 3)) in
    0) order=(none live slow) ;;
    1) order=(live slow none) ;;
    *) order=(slow none live) ;;
  esac
  for c in "${order[@]}"; do one_run "$c" "$i" | sed "s/^/$i /" >>"$work/results.txt"; done
  echo "round $i of $rounds done" >&2
done

python3 - "$work/results.txt" <<'PY'
import math, sys, statistics as st
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
by = {}
for r, cond, p50, p99, mx in rows:
    by.setdefault(cond, {})[int(r)] = (float(p50), float(p99), float(mx))
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228,
       12: 2.179, 15: 2.131, 20: 2.086, 30: 2.042}
def t95(df):
    return T95.get(df) or T95[min(T95, key=lambda k: abs(k - df))]
print("control-loop period on etroll-emulated (100 Hz), mean over rounds [ms]:")
print(f"{'condition':10} {'rounds':>6} {'p50':>8} {'p99':>8} {'max':>8}")
for cond in ("none", "live", "slow"):
    v = list(by.get(cond, {}).values())
    if not v: continue
    print(f"{cond:10} {len(v):6d} " + " ".join(f"{st.mean(x[k] for x in v):8.3f}" for k in range(3)))
base = by.get("none", {})
for cond in ("live", "slow"):
    pairs = [(by[cond][r][1], base[r][1]) for r in by.get(cond, {}) if r in base]
    if len(pairs) < 2: continue
    d = [a / b - 1 for a, b in pairs]  # relative p99 difference per round
    m, h = st.mean(d), t95(len(d) - 1) * st.stdev(d) / math.sqrt(len(d))
    verdict = "no difference beyond 10 % shown" if m + h < 0.10 else "the interval reaches past +10 %"
    print(f"p99 {cond} vs none: {100*m:+.2f} % (95 % CI {100*(m-h):+.2f} % .. {100*(m+h):+.2f} %, "
          f"{len(d)} paired rounds): {verdict}")
PY
