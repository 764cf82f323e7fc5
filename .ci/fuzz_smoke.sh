#!/usr/bin/env bash
# Fuzz smoke test: builds the libFuzzer targets with clang (tests/fuzz/CMakeLists.txt) and
# runs each for FUZZ_SECONDS (default 60) from its seed corpus. Fails on any finding; the
# crashing input is left in build-fuzz/findings/ (freeze it in tests/fuzz/regressions/).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release \
  -DGRIDRT_FUZZ=ON -DGRIDRT_BUILD_TESTS=OFF >/dev/null
cmake --build build-fuzz -j2 --target fuzz_scene_loader fuzz_options
mkdir -p build-fuzz/findings
for target in scene_loader:corpus_scene options:corpus_options; do
  name=${target%%:*} seeds=tests/fuzz/${target#*:}
  work=build-fuzz/corpus_$name   # new inputs go here, never into the committed seeds
  mkdir -p "$work"
  echo "fuzz_$name: ${seconds} s"
  build-fuzz/fuzz/fuzz_$name -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix=build-fuzz/findings/"$name"- -print_final_stats=1 "$work" "$seeds"
done
