#!/usr/bin/env bash
# Builds Patina with AddressSanitizer and UndefinedBehaviorSanitizer (GCC, -O1 -g1)
# into $PATINA_SANITIZE_BUILD_DIR (default build-sanitize/) and runs the whole test suite
# under them, the command-line bad-input tests included. Any report fails the run.
# The third-party suppressions are in scripts/sanitize/, each with its reason; the run time
# is in docs/testing.md. Extra arguments go to ctest (e.g. -R cli.).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/bootstrap.sh
build=${PATINA_SANITIZE_BUILD_DIR:-build-sanitize}
here=$(pwd)
# -O1 -g1: line tables for the reports' stack traces, without the full debug information
# that doubles the build time of the template-heavy sources.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPATINA_SANITIZE=ON \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" \
      -DPATINA_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)"

# new_delete_type_mismatch=0: OpenImageIO 2.4's TextureSystem::destroy (Debian 12) deletes
# its TextureSystemImpl through the base class with a sized operator delete of 1 byte, inside
# libOpenImageIO (the report's frame #1); ASan can only switch this check off as a whole.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:new_delete_type_mismatch=0"
export LSAN_OPTIONS="suppressions=$here/scripts/sanitize/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$here/scripts/sanitize/ubsan.supp"
# (Sanitized code runs 2-5x slower: tests/CMakeLists.txt scales the tests' time limits.)
start=$(date +%s)
ctest --test-dir "$build" -j "$(nproc)" --output-on-failure "$@"
echo "sanitize: every test passed under ASan + UBSan in $(( $(date +%s) - start )) s" >&2
