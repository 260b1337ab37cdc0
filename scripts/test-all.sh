#!/usr/bin/env bash
# The project's test command (README "Start here"; .ci/run runs exactly this): the Rust test
# suite, then the Python package's test suite (python/tests, pytest) against a fresh build of
# ./python in a virtual environment inside the repository (.venv, git-ignored), with its build
# and test tools from the package index. Needs a Rust toolchain and python3 (>= 3.9) with venv.
set -euo pipefail
cd "$(dirname "$0")/.."

# --- Rust ---
cargo test --workspace --release

# --- Python ---
python_start=$SECONDS
venv="${DYNCONTACT_VENV:-.venv}"
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
venv="$(cd "$venv" && pwd)"
py="$venv/bin/python"
export PATH="$venv/bin:$PATH"   # maturin's build backend runs the `maturin` of the venv
"$py" -m pip install --quiet --disable-pip-version-check \
    "maturin>=1.9.4,<2" "numpy>=1.21" pytest "dask[distributed]"
# The extension is built by maturin in release mode (as a user's `pip install ./python`) into the
# workspace's target directory, next to the release build of the tests.
"$py" -m pip install --quiet --disable-pip-version-check --no-build-isolation --force-reinstall --no-deps ./python
echo "scripts/test-all.sh: Rust tests done at ${python_start} s; Python venv and build took $((SECONDS - python_start)) s"
# The CLI that the Python results are compared with: the binary `cargo test --release` built.
DYNCONTACT_BIN="$PWD/target/release/dyncontact" "$py" -m pytest python/tests -q -rs
