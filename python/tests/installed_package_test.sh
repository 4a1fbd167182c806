#!/usr/bin/env bash
# `pip install .` as a user would, offline: a venv over Debian's packages, the package built by
# pip from a copy of the source tree (no build folder), then the Python tests against the
# installed module, not the build tree's.
#   installed_package_test.sh SOURCE_DIR PCSIM_BIN PYTHON
set -euo pipefail
source_dir=$1 pcsim_bin=$2 python=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/pcsim-pip.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir "$work/src"
tar -C "$source_dir" --exclude='./build*' --exclude=./.git -cf - . | tar -C "$work/src" -xf -
"$python" -m venv --system-site-packages "$work/venv"
CMAKE_BUILD_PARALLEL_LEVEL=2 "$work/venv/bin/pip" install --quiet --no-build-isolation --no-index "$work/src"
cd "$source_dir"
installed=$(cd "$work" && "$work/venv/bin/python" -c 'import pcsim; print(pcsim.__file__)')
case $installed in
  "$work/venv/"*) echo "pcsim imported from $installed" ;;
  *) echo "FAIL: pcsim imported from $installed, not the venv" >&2; exit 1 ;;
esac
env -u PYTHONPATH PCSIM_BIN="$pcsim_bin" PCSIM_SOURCE_DIR="$source_dir" \
  "$work/venv/bin/python" -m pytest -q -p no:cacheprovider python/tests/test_run.py python/tests/test_inputs.py python/tests/test_sweep.py
