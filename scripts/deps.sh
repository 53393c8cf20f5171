#!/usr/bin/env bash
# Installs the Debian packages granflow needs to build, test and draw pictures.
# Idempotent: does nothing when everything is present. Works as root, or with sudo.
set -euo pipefail
pkgs=(build-essential cmake pkg-config libinih-dev libcmocka-dev zlib1g-dev gnuplot-nox
      g++ libcairo2-dev voro++-dev lammps python3
      python3-numpy python3-pytest chromium fonts-dejavu-core
      clang libclang-rt-14-dev libomp-14-dev
      openmpi-bin libopenmpi-dev
      libjansson-dev help2man python3-venv python3-pip python3-build python3-setuptools
      python3-wheel python3-vtk9 python3-meshio xvfb)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "deps: installing ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
