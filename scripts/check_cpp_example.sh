#!/usr/bin/env bash
# Builds examples/estimate_pose against the core as installed from a plain CMake build (BUILD, with
# SANITIZE ON when that build has the sanitizers), as a program outside this project would
# (find_package(stocs)), and runs it on a scene the build's `stocs synth` generates. Exits non-zero
# when any step fails or the example does not find every object.
#   scripts/check_cpp_example.sh BUILD [ON|OFF]
set -euo pipefail
source "$(dirname "$0")/common.sh"
[ $# -ge 1 ] || { echo "usage: $0 BUILD [SANITIZE ON|OFF]" >&2; exit 2; }
build=$(cd "$1" && pwd)
prefix="$build-install"
example="$build-example"
rm -rf "$prefix" "$example"
cmake --install "$build" --prefix "$prefix" > "$build-install.log"
flags=""
if [ "${2:-OFF}" = ON ]; then flags="-fsanitize=address,undefined"; fi
cmake -S "$REPO/examples/estimate_pose" -B "$example" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="$flags" > "$example.cmake.log" 2>&1 ||
  { cat "$example.cmake.log"; exit 1; }
cmake --build "$example" -j"$JOBS"
"$build/stocs" synth --out "$example/scene" --objects 4 --distractors 1 --seed 2 --quiet > /dev/null
ASAN_OPTIONS=detect_leaks=1:halt_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  XDG_CACHE_HOME="$example/cache" "$example/estimate_pose" "$example/scene"
echo "check_cpp_example: examples/estimate_pose built against the installed core and ran"
