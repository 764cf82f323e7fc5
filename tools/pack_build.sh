#!/usr/bin/env bash
# tools/pack_build.sh BUILD PACK: copies what tools/gpu_check.sh runs, from a build folder
# into PACK, for another machine that has none of gridrt's libraries: gridrt, the device
# suites' test programs (tests/) and the shared libraries they load (lib/; glibc and the
# C++ runtime excepted, which the other machine has). There, run with
# LD_LIBRARY_PATH=PACK/lib. For another x86 machine, build without -march=native:
#   cmake -S . -B build-portable -DGRIDRT_NATIVE=OFF -DCMAKE_CXX_FLAGS=-march=x86-64-v3
set -eu
[ $# -eq 2 ] || { echo "usage: tools/pack_build.sh BUILD PACK" >&2; exit 2; }
build=$1
pack=$2
suites=$("$(dirname "$0")/gpu_check.sh" --suites)
for suite in $suites; do
  [ -x "$build/tests/${suite}_test" ] || { echo "pack_build: no $build/tests/${suite}_test" >&2; exit 1; }
done
[ -x "$build/gridrt" ] || { echo "pack_build: no $build/gridrt" >&2; exit 1; }
rm -rf "$pack"
mkdir -p "$pack/tests" "$pack/lib"
cp "$build/gridrt" "$pack/"
for suite in $suites; do cp "$build/tests/${suite}_test" "$pack/tests/"; done
# The libraries ldd resolves to a path, less the C library's and the C++ runtime's.
for program in "$pack/gridrt" "$pack"/tests/*; do ldd "$program"; done |
  awk '$3 ~ /^\// {print $3}' | sort -u |
  grep -v -E '/(libc|libm|libpthread|libdl|librt|ld-linux-x86-64|libstdc\+\+|libgcc_s)\.so' |
  while read -r library; do cp -L "$library" "$pack/lib/"; done
strip "$pack/gridrt" "$pack"/tests/*
du -sh "$pack"
