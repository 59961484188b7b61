#!/usr/bin/env bash
# The project's checks, as CI runs them: set-up, formatting, lints, licences, tests (unit,
# integration and doc), and the example binary started directly, outside cargo.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/setup-test-peers.sh

echo "== format"
cargo fmt --all --check
echo "== licences"
cargo fetch --locked
python3 .ci/check-licences.py
echo "== import circles"
python3 .ci/check-import-circles.py
echo "== the README and the book"
python3 .ci/check-book.py
echo "== clippy"
# Tests, examples and benches write their fixtures directly (clippy.toml's banned methods);
# the library crates and the binaries write outputs only through yarok_core::output_file.
cargo clippy --workspace --all-targets --locked -- -D warnings -A clippy::disallowed_methods
cargo clippy --workspace --all-targets --features yarok/camera,yarok/viewer,yarok/zenoh,yarok/dataset --locked -- -D warnings -A clippy::disallowed_methods
cargo clippy --workspace --lib --bins --features yarok/camera,yarok/viewer,yarok/zenoh,yarok/dataset --locked -- -D warnings
echo "== tests"
if cargo nextest --version >/dev/null 2>&1; then
  echo "runner: cargo nextest (one process per test, no retries)"
  cargo nextest run --workspace --locked --no-fail-fast --retries 0
  echo "runner: cargo nextest, the camera, viewer, zenoh and dataset features' tests (and yarok-components' unit tests with them)"
  # Only the test binaries run are built: each holds the whole stack, and all of them again
  # would take minutes and gigabytes.
  cargo nextest run --workspace --features yarok/camera,yarok/viewer,yarok/zenoh,yarok/dataset --locked --no-fail-fast \
    --retries 0 --lib --test camera_decode --test video_device --test cam_real --test tactile_real \
    --test viewer --test zenoh_bridge --test named_state --test dataset_lerobot --test never_lose_a_file \
    -E 'kind(test) | binary_id(yarok-components)'
else
  echo "runner: cargo test (cargo-nextest is not installed)"
  cargo test --workspace --locked --no-fail-fast
  cargo test --features camera,viewer,zenoh,dataset --locked --no-fail-fast --test cam_real \
    --test tactile_real --test viewer --test zenoh_bridge --test dataset_lerobot --test never_lose_a_file
  cargo test -p yarok-hw --features camera --locked --no-fail-fast --test camera_decode \
    --test video_device
fi
echo "== without default features: no rendering (EGL), for the crates that have it"
cargo clippy -p yarok-mjc -p yarok-components -p yarok --no-default-features --all-targets --locked -- -D warnings -A clippy::disallowed_methods
if cargo nextest --version >/dev/null 2>&1; then
  cargo nextest run -p yarok-mjc -p yarok-components --no-default-features --locked --no-fail-fast --retries 0
  cargo nextest run -p yarok --no-default-features --locked --no-fail-fast --retries 0 --test render_feature
else
  cargo test -p yarok-mjc -p yarok-components --no-default-features --locked --no-fail-fast
  cargo test -p yarok --no-default-features --locked --no-fail-fast --test render_feature
fi
echo "== the Zenoh example: a world driven from another process through the bridge"
cargo run --locked --features yarok/camera,yarok/viewer,yarok/zenoh,yarok/dataset --example zenoh_remote
echo "== tests of process-wide state, as threads of one process (as cargo test runs them)"
cargo test --workspace --locked --test render_offscreen
cargo test --workspace --locked --test runtime_interrupt
cargo test --workspace --locked --test warnings_visible
cargo test --workspace --features yarok/camera,yarok/viewer,yarok/zenoh,yarok/dataset --doc --locked
echo "== the Python package: installed into a new venv by the README's command, then its tests (pytest)"
bash scripts/setup-python.sh
cache="${YAROK_CACHE_DIR:-$HOME/.cache/yarok}"
fresh="$(mktemp -d)"
python3 -m venv "$fresh/.venv"
"$fresh/.venv/bin/pip" install -q --disable-pip-version-check ./yarok-py
"$fresh/.venv/bin/python" -c "import yarok; print('import yarok:', yarok.__file__)"
rm -rf "$fresh"
# The tests run in the project's venv (pinned Gymnasium and pytest), with the same package.
"$cache/python/bin/pip" install -q --disable-pip-version-check --force-reinstall --no-deps ./yarok-py
(cd yarok-py && "$cache/python/bin/python" -m pytest -q -p no:cacheprovider tests)
echo "== the wheel, built once, installed where yarok was never built (an empty home, no Rust on PATH)"
wheels="$(mktemp -d)"
bash scripts/build-wheel.sh "$wheels"
wheel="$(ls "$wheels"/yarok-*.whl)"
size="$(stat -c %s "$wheel")"
echo "$(basename "$wheel"): $((size / 1024 / 1024)) MB"
[ "$size" -lt $((40 * 1024 * 1024)) ] || { echo "the wheel is over 40 MB" >&2; exit 1; }
"$cache/python/bin/auditwheel" show "$wheel"
elsewhere="$(mktemp -d)"
bare=(env -i HOME="$elsewhere" PATH="$elsewhere/venv/bin:/usr/bin:/bin" LANG=C.UTF-8)
# The way to the package registries (proxies, certificates, pip's settings) is kept.
for name in $(compgen -e | grep -E '^(PIP_|SSL_CERT_|REQUESTS_CA_BUNDLE$|(HTTPS?|NO|ALL)_PROXY$|(https?|no|all)_proxy$)'); do
  bare+=("$name=${!name}")
done
"${bare[@]}" /usr/bin/python3 -m venv "$elsewhere/venv"
"${bare[@]}" pip install -q --disable-pip-version-check "$wheel"
"${bare[@]}" python yarok-py/tests/check_installed_wheel.py
rm -rf "$wheels" "$elsewhere"
echo "== the learning loop with LeRobot and Stable-Baselines3: demonstrations, lerobot-train, LeRobot's own evaluation, PPO"
lerobot_python="$(bash scripts/setup-lerobot.sh)"
"$(dirname "$lerobot_python")/pip" install -q --disable-pip-version-check --force-reinstall --no-deps ./yarok-py
(cd yarok-py && YAROK_REQUIRE_LEROBOT=1 "$lerobot_python" -m pytest -q -p no:cacheprovider \
  tests/test_lerobot_loop.py tests/test_learners.py)
echo "== your own crate: examples/own_crate, a crate outside yarok's workspace, as the README sets it up"
(
  export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}"
  cd examples/own_crate
  cargo fmt --check
  cargo clippy --locked --workspace --all-targets -- -D warnings
  cargo test --locked
  cargo run --locked -- --env mock
  # Its worlds from Python: its own extension module (yarok_py::module!), installed beside the
  # yarok package the tests above installed, and its tests.
  "$cache/python/bin/pip" install -q --disable-pip-version-check --force-reinstall --no-deps ./py
  "$cache/python/bin/python" -m pytest -q -p no:cacheprovider py/tests
)
echo "== docs, with the default features and with every feature"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked --features yarok/camera,yarok/viewer,yarok/zenoh,yarok/dataset
echo "== example binary, started directly"
cargo build --examples --locked
examples="${CARGO_TARGET_DIR:-target}/debug/examples"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
env -u LD_LIBRARY_PATH "$examples/falling_boxes" "$out"
for image in falling_boxes_rgb.png falling_boxes_depth_mm.png; do
  test -s "$out/$image" || { echo "error: the example did not write $image" >&2; exit 1; }
done
echo "== embedding and behaviour examples"
for example in threaded local_set pendulum_clock pick_and_place printer_square; do
  env -u LD_LIBRARY_PATH "$examples/$example"
done
echo "== yarok run: every bundled world with its demo behaviour, in release, as the README runs them"
# One release build for all (an example's dev-dependencies unify features: built apart, twice).
cargo build --release --locked --bin yarok --example pick_and_place --example digit_world \
  --example geltip_world --example tactile_rig
yarok="${CARGO_TARGET_DIR:-target}/release/yarok"
"$yarok" run --list | while read -r world behaviour; do
  echo "-- yarok run $world ($behaviour)"
  case "${behaviour%%,*}" in
    idle | stack) "$yarok" run "$world" </dev/null ;;
    *) "$yarok" run "$world" --set "behaviour/out=\"$out/$world\"" </dev/null ;;
  esac
done
for image in digit_world/digit_left.png geltip_world/geltip_left.png tactile_rig_world/press_2.png \
  printer_world/printer_camera_3.png; do
  test -s "$out/$image" || { echo "error: yarok run wrote no $image" >&2; exit 1; }
done
echo "== the README's demo command: the DIGIT pick and place, its tactile images, a film and a recording"
mkdir -p "$out/demo"
(cd "$out/demo" && cargo run --release --locked --manifest-path "$OLDPWD/Cargo.toml" -- \
  run digit_world --record out/digit_world.mcap --video out/digit_world.mp4 </dev/null)
for file in digit_left.png digit_right.png digit_world.mcap digit_world.mp4; do
  test -s "$out/demo/out/$file" || { echo "error: the demo wrote no $file" >&2; exit 1; }
done
read_back=$("${YAROK_CACHE_DIR:-$HOME/.cache/yarok}/peers/bin/python" scripts/peers/mcap_summary.py \
  "$out/demo/out/digit_world.mcap")
grep -q "^image /arm/gripper/left_digit/image " <<<"$read_back" \
  || { echo "error: the demo's recording holds no tactile image" >&2; exit 1; }
echo "== the manipulation and tactile examples in release, as the README runs them"
cargo run --release --locked --example pick_and_place
cargo run --release --locked --example digit_world -- --set "behaviour/out=\"$out/examples\""
test -s "$out/examples/digit_left.png" || { echo "error: digit_world wrote no tactile image" >&2; exit 1; }
cargo run --release --locked --example geltip_world -- --set "behaviour/out=\"$out/examples\""
test -s "$out/examples/geltip_left.png" || { echo "error: geltip_world wrote no tactile image" >&2; exit 1; }
cargo run --release --locked --example tactile_rig -- --rigs 2 --out "$out/tactile_rig"
test -s "$out/tactile_rig/index.csv" || { echo "error: tactile_rig wrote no index" >&2; exit 1; }
echo "== all checks passed"
