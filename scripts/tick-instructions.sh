#!/usr/bin/env bash
# Counts with valgrind the instructions a tick adds to a raw `mj_step` on the floor-only model of
# `cargo bench --bench platform`: the platform's with one pending wait and with ten, and the bare
# executor's. Wall time moves by several per cent with where the code lands in the binary; this
# count repeats, run after run of a build, to within one instruction a tick.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/debian-packages.sh
install_missing_packages "valgrind" valgrind

bench=$(cargo bench --locked --bench platform --no-run 2>&1 | sed -n 's/.*Executable .*(\(.*\))$/\1/p')
YAROK_CACHE_DIR=$(mktemp -d)
export YAROK_CACHE_DIR
trap 'rm -rf "$YAROK_CACHE_DIR"' EXIT
# Every counted run then loads the model from the cache alike, so start-up cancels out.
"$bench" --once platform 1 1 >/dev/null

count() {
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bench" --once "$@" 2>&1 |
    sed -n 's/.*Collected : \([0-9]*\)$/\1/p'
}
# Instructions a tick: the difference between a long run and a short one, so start-up cancels.
per_tick() {
  local short long
  short=$(count "$1" 1000 "$2")
  long=$(count "$1" 21000 "$2")
  echo $(((long - short) / 20000))
}

raw=$(per_tick raw 0)
echo "raw mj_step: $raw instructions a step"
for side in platform bare; do
  for waits in 1 10; do
    added=$(($(per_tick "$side" "$waits") - raw))
    awk -v side="$side" -v waits="$waits" -v raw="$raw" -v added="$added" 'BEGIN {
      printf "%-8s pending waits: %2d  +%d instructions a tick: %.1f %% of raw at the instructions a cycle of mj_step\n",
        side, waits, added, 100 * raw / (raw + added) }'
  done
done
