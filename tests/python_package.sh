#!/usr/bin/env bash
# The Python package as a user installs it, offline, with Debian's packages
# only (python3-venv, python3-pip, python3-setuptools, python3-wheel,
# python3-build): from a copy of the source tree,
#   1. python3 -m venv --system-site-packages; pip install --no-build-isolation .
#   2. python3 -m build --no-isolation --wheel, the wheel installed in a second venv;
# each time `import granflow` from another directory loads the libgranflow.so
# inside the installed package (not a build tree's), and a small silo drains.
# setup.py's CMake step reuses this build (GRANFLOW_CMAKE_BUILD_DIR): the test
# is about the packaging, not a second compilation.
# Usage: python_package.sh PYTHON SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
py=$1 src=$2 build=$3 work=$4
rm -rf "$work"
mkdir -p "$work/src" "$work/elsewhere"
# Building writes into the source tree (build-python/, *.egg-info): use a copy.
tar -C "$src" --exclude='./build*' --exclude=./.git --exclude=./runs --exclude=./out --exclude=./dist \
    --exclude='*.egg-info' --exclude=__pycache__ --exclude=./python/granflow/libgranflow.so -cf - . |
  tar -C "$work/src" -xf -
export GRANFLOW_CMAKE_BUILD_DIR=$build PIP_NO_INDEX=1 PIP_DISABLE_PIP_VERSION_CHECK=1 PYTHONDONTWRITEBYTECODE=1
unset GRANFLOW_LIB PYTHONPATH

# What the installed package must do from a directory that is not the source.
check_import() { # VENV_PYTHON WHAT
  local got
  got=$(cd "$work/elsewhere" && "$1" -c '
import os, granflow
here = os.path.dirname(granflow.__file__)
assert granflow.library_path == os.path.join(here, "libgranflow.so"), (granflow.library_path, here)
assert "site-packages" in here, here
s = granflow.Simulation({"packing.particles": 300, "container.width": 10, "container.orifice_diameter": 5})
s.run(until=1.0)
t = s.particle_table()
assert len(t) == len(s) and s.stats()["particles_exited"] + len(s) == 300
print(granflow.__version__, len(s) < 300)')
  [ "$got" = "$("$build/granflow" --version | awk '{print $2}') True" ] ||
    { echo "$2: import granflow from another directory gave '$got'"; exit 1; }
  echo "$2: ok ($got)"
}

# 1. venv + pip install --no-build-isolation (setuptools and wheel from the system).
"$py" -m venv --system-site-packages "$work/venv"
"$work/venv/bin/pip" install -q --no-build-isolation "$work/src" >"$work/pip.log" 2>&1 ||
  { cat "$work/pip.log"; exit 1; }
check_import "$work/venv/bin/python" "pip install"

# 2. A wheel that carries libgranflow.so, installed in a fresh venv.
(cd "$work/src" && "$py" -m build --no-isolation --wheel --outdir "$work/dist" >"$work/build.log" 2>&1) ||
  { cat "$work/build.log"; exit 1; }
wheels=("$work"/dist/granflow-*.whl)
[ ${#wheels[@]} = 1 ] || { echo "expected one wheel, got: ${wheels[*]}"; exit 1; }
case $(basename "${wheels[0]}") in
  granflow-*-py3-none-linux_*.whl) ;;
  *) echo "wheel tag: $(basename "${wheels[0]}") (expected py3-none-linux_*)"; exit 1 ;;
esac
listing=$("$py" -m zipfile -l "${wheels[0]}")
for f in granflow/libgranflow.so granflow/__init__.py granflow/_lib.py granflow/errors.py granflow/snapshot.py; do
  grep -q " *$f " <<<"$listing" || grep -q "^$f" <<<"$listing" || { echo "the wheel has no $f:"; echo "$listing"; exit 1; }
done
"$py" -m venv --system-site-packages "$work/venv2"
"$work/venv2/bin/pip" install -q "${wheels[0]}" >"$work/pip2.log" 2>&1 || { cat "$work/pip2.log"; exit 1; }
check_import "$work/venv2/bin/python" "wheel"
