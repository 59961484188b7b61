#!/usr/bin/env bash
# A benchmark of this tree and of another revision, in one run: the two builds' bench binaries
# run alternately, ROUNDS times each, on the same machine at the same time, so a change is
# measured against the code before it rather than against figures from another day.
#
#   bash scripts/bench-against.sh REV BENCH [ROUNDS] [-- BENCH ARGS]
#   bash scripts/bench-against.sh 4dbc36a compose 3
#
# REV is checked out in a temporary worktree; both sides build into this tree's target folder
# (their crates differ by path, so neither overwrites the other; shared dependencies build once).
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 REV BENCH [ROUNDS] [-- BENCH ARGS]" >&2; exit 2; }
rev=$1 bench=$2
shift 2
rounds=3
if [ $# -gt 0 ] && [ "$1" != "--" ]; then rounds=$1; shift; fi
[ "${1:-}" = "--" ] && shift
root=$(cd "$(dirname "$0")/.." && pwd)
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
before=$(mktemp -d)
git -C "$root" worktree add --detach "$before/tree" "$rev" >/dev/null
trap 'git -C "$root" worktree remove --force "$before/tree"' EXIT

# The bench's executable, built in `tree`.
executable() {
  (cd "$1" && cargo bench --locked --bench "$bench" --no-run --message-format=json) |
    python3 -c 'import json, sys
paths = [m["executable"] for m in map(json.loads, sys.stdin)
         if m.get("reason") == "compiler-artifact" and m.get("executable")
         and m["target"]["name"] == sys.argv[1]]
print(paths[-1])' "$bench"
}
old=$(executable "$before/tree")
new=$(executable "$root")
for round in $(seq 1 "$rounds"); do
  echo "== round $round: before ($rev)"
  (cd "$before/tree" && "$old" --bench "$@")
  echo "== round $round: after ($(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet || echo ', with changes'))"
  (cd "$root" && "$new" --bench "$@")
done
