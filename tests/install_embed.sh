#!/usr/bin/env bash
# Installs the build into a prefix inside the build directory (not
# /usr/local) and MOVES the tree elsewhere, so nothing may hold the path it was
# installed to; then builds examples/embed against the INSTALLED library
# (find_package: shared and static; plain `pkg-config --cflags --libs`, no
# --define-variable) and runs each; then imports the installed Python package
# with PYTHON. Usage: install_embed.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$1 src=$2 py=$3
work=$build/install-test
rm -rf "$work"
mkdir -p "$work"
staged=$work/staged
cmake --install "$build" --prefix "$staged" >/dev/null
# The package files must not name the install prefix: they find it from their own place.
if grep -rlF "$staged" "$staged/lib/pkgconfig" "$staged/lib/cmake"; then
  echo "the files above hold the install prefix $staged: not relocatable"; exit 1
fi
prefix=$work/moved/prefix
mkdir -p "$work/moved"
mv "$staged" "$prefix"
for f in lib/libgranflow.so lib/libgranflow.a bin/granflow include/granflow/granflow.h include/granflow/version.h \
         lib/pkgconfig/granflow.pc lib/cmake/granflow/granflowConfig.cmake share/granflow/python/granflow/sim.py; do
  [ -e "$prefix/$f" ] || { echo "install: $f missing under $prefix"; find "$prefix" -type f; exit 1; }
done
# The installed CLI runs from its prefix (RPATH $ORIGIN/../lib).
# (grep -q on a variable, not a pipe: with pipefail an early grep exit would
# give the writer SIGPIPE and fail a check that passed.)
ver=$("$prefix/bin/granflow" --version)
grep -q "granflow [0-9]" <<<"$ver" || { echo "installed CLI does not run"; exit 1; }

# 1. CMake: find_package(granflow) from the prefix, shared and static.
cmake -S "$src/examples/embed" -B "$work/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/cmake-build" >/dev/null
out=$("$work/cmake-build/embed")
grep -q '^ok: ' <<<"$out" || { echo "find_package build: $out"; exit 1; }
[ "$("$work/cmake-build/embed_static")" = "$out" ] || { echo "the static build prints differently"; exit 1; }
libs_static=$(ldd "$work/cmake-build/embed_static")
grep -q libgranflow <<<"$libs_static" && { echo "embed_static links libgranflow.so"; exit 1; }
# It uses the installed library, not the build tree's.
libs=$(ldd "$work/cmake-build/embed")
grep -q "$prefix/lib/libgranflow.so" <<<"$libs" ||
  { echo "embed (cmake) is not linked to the installed library:"; ldd "$work/cmake-build/embed"; exit 1; }

# 2. pkg-config, as a Makefile would: plain --cflags --libs (granflow.pc
# finds its prefix through ${pcfiledir}).
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
got=$(pkg-config --variable=libdir granflow)
[ "$(realpath "$got")" = "$(realpath "$prefix/lib")" ] ||
  { echo "pkg-config: libdir is $got, expected $prefix/lib"; exit 1; }
cc -std=c17 -Wall -Wextra -Werror $(pkg-config --cflags granflow) "$src/examples/embed/embed.c" -o "$work/embed-pc" \
   $(pkg-config --libs granflow) -Wl,-rpath,"$prefix/lib"
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
