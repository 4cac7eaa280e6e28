#!/usr/bin/env bash
# The Python package in CI (called by .ci/run from the repository root): a fresh virtual
# environment, the install command of README.md and docs/PYTHON.md, then the import, pytest
# and mypy. The wheel is built with the workspace's dev profile (optimised), so it reuses
# what `cargo test --workspace` compiled.
#
# `--prepare` only makes the environment and installs what the checks use (numpy, pytest,
# mypy): .ci/run starts it in the background while the Rust build runs, so the downloads cost
# no time. `--prepared` then does the rest in that environment. No flag does both.
set -euo pipefail
cd "$(dirname "$0")/../.."
mode=${1:-all}
case "$mode" in all|--prepare|--prepared) ;; *) echo "usage: ci.sh [--prepare|--prepared]" >&2; exit 2;; esac
venv=target/ci-python-venv
py="$venv/bin/python"
if [ "$mode" != --prepared ]; then
  rm -rf "$venv"
  python3 -m venv "$venv"
  "$py" -m pip install --quiet --upgrade pip
  "$venv/bin/pip" install --quiet numpy pytest mypy
fi
[ "$mode" != --prepare ] || exit 0
[ -x "$py" ] || { echo "ci.sh --prepared: no environment at $venv (run ci.sh --prepare first)" >&2; exit 1; }
# the documented install command, as a new user runs it
"$venv/bin/pip" install ./crates/python
"$py" -c "import centrifuge_cal; print('centrifuge_cal', centrifuge_cal.__version__)"
# pytest: exit status 5 (no tests collected) is a failure like any other non-zero one
"$venv/bin/centrifuge-cal" --version
"$py" -m pytest crates/python/tests -q -p no:cacheprovider
(cd crates/python && "../../$venv/bin/mypy")
