#!/usr/bin/env bash
# Fails when the shared library exports a symbol that does not start with gf_.
set -euo pipefail
lib=$1
bad=$(nm -D --defined-only "$lib" | awk '$2 ~ /[TDBR]/ {print $3}' | grep -v '^gf_' | grep -v '^_' || true)
if [ -n "$bad" ]; then echo "exported symbols without the gf_ prefix:"; echo "$bad"; exit 1; fi
n=$(nm -D --defined-only "$lib" | awk '$2 ~ /[TDBR]/' | grep -c ' gf_' || true)
echo "all $n exported symbols start with gf_"
[ "$n" -gt 0 ]
