#!/usr/bin/env bash
# Installs the build into a prefix inside the build directory, then builds
# examples/embed against the INSTALLED library (find_package: shared and
# static; pkg-config) and runs each; then imports the installed Python
# package with PYTHON. Usage: install_embed.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$1 src=$2 py=$3
work=$build/install-test
rm -rf "$work"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
for f in lib/libgranflow.so lib/libgranflow.a bin/granflow include/granflow/granflow.h include/granflow/version.h \
         lib/pkgconfig/granflow.pc lib/cmake/granflow/granflowConfig.cmake share/granflow/python/granflow/sim.py; do
  [ -e "$prefix/$f" ] || { echo "install: $f missing under $prefix"; find "$prefix" -type f; exit 1; }
done
# The installed CLI runs from its prefix (RPATH $ORIGIN/../lib).
grep -q "granflow [0-9]" <<< "$("$prefix/bin/granflow" --version)" || { echo "installed CLI does not run"; exit 1; }

# 1. CMake: find_package(granflow) from the prefix, shared and static.
cmake -S "$src/examples/embed" -B "$work/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/cmake-build" >/dev/null
out=$("$work/cmake-build/embed")
grep -q '^ok: ' <<< "$out" || { echo "find_package build: $out"; exit 1; }
[ "$("$work/cmake-build/embed_static")" = "$out" ] || { echo "the static build prints differently"; exit 1; }
# (ldd's output is read whole first: `ldd | grep -q` under pipefail fails
# whenever grep stops reading before ldd has written everything.)
grep -q libgranflow <<< "$(ldd "$work/cmake-build/embed_static")" && { echo "embed_static links libgranflow.so"; exit 1; }
# It uses the installed library, not the build tree's.
grep -q "$prefix/lib/libgranflow.so" <<< "$(ldd "$work/cmake-build/embed")" ||
  { echo "embed (cmake) is not linked to the installed library:"; ldd "$work/cmake-build/embed"; exit 1; }

# 2. pkg-config, as a Makefile would.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
# The .pc file holds the configured prefix; tell pkg-config where it really is.
pc="pkg-config --define-variable=prefix=$prefix"
cc -std=c17 -Wall -Wextra -Werror $($pc --cflags granflow) "$src/examples/embed/embed.c" -o "$work/embed-pc" \
   $($pc --libs granflow) -Wl,-rpath,"$prefix/lib"
out2=$("$work/embed-pc")
[ "$out" = "$out2" ] || { echo "pkg-config build prints differently:"; echo "$out"; echo "---"; echo "$out2"; exit 1; }
echo "$out2" | tail -1

# 3. The installed Python package loads the installed library by itself.
got=$(env -u GRANFLOW_LIB PYTHONPATH="$prefix/share/granflow/python" PYTHONDONTWRITEBYTECODE=1 "$py" -c \
  'import granflow; s = granflow.Simulation({"packing.particles": 300, "container.width": 10, "container.orifice_diameter": 5}); print(granflow.library_path, len(s))')
case $got in
  "$prefix/lib/libgranflow.so 300") echo "python: $got" ;;
  *) echo "installed python package: expected '$prefix/lib/libgranflow.so 300', got '$got'"; exit 1 ;;
esac
