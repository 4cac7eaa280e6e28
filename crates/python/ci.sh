#!/usr/bin/env bash
# The Python package in CI (called by .ci/run from the repository root): a fresh virtual
# environment, the install command of README.md and docs/PYTHON.md, then the import, pytest
# and mypy. The wheel is built with the workspace's dev profile (optimised), so it reuses
# what `cargo test --workspace` compiled.
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=target/ci-python-venv
rm -rf "$venv"
python3 -m venv "$venv"
py="$venv/bin/python"
"$py" -m pip install --quiet --upgrade pip
# the documented install command, as a new user runs it
"$venv/bin/pip" install ./crates/python
"$py" -c "import centrifuge_cal; print('centrifuge_cal', centrifuge_cal.__version__)"
"$venv/bin/pip" install --quiet pytest mypy
# pytest: exit status 5 (no tests collected) is a failure like any other non-zero one
"$venv/bin/centrifuge-cal" --version
"$py" -m pytest crates/python/tests -q -p no:cacheprovider
(cd crates/python && "../../$venv/bin/mypy")
