#!/usr/bin/env bash
# Runs every libFuzzer target for a bounded time from its seed corpus; fails when one finds a
# crash, a sanitizer report, a leak, a timeout or an out-of-memory input (docs/fuzzing.md).
# Usage: tests/fuzz/run_fuzzers.sh [SECONDS_PER_TARGET] [TARGET...]
#   FUZZ_BUILD_DIR  where the fuzz preset built them (default build-fuzz)
#   FUZZ_OUT_DIR    working corpora, logs and crashing inputs (default $FUZZ_BUILD_DIR/fuzz-out)
#   FUZZ_FLAGS      extra libFuzzer flags, e.g. "-jobs=2 -workers=2" or "-dict=..."
set -uo pipefail
src=$(cd "$(dirname "$0")" && pwd)
seconds=${1:-60}
shift $(($# > 0 ? 1 : 0))
build=${FUZZ_BUILD_DIR:-$src/../../build-fuzz}
out=${FUZZ_OUT_DIR:-$build/fuzz-out}
targets=("$@")
((${#targets[@]})) || targets=(fuzz_scene fuzz_recording_jsonl fuzz_kinect_csv fuzz_ntu_skeleton fuzz_obj_mesh)

failed=()
for target in "${targets[@]}"; do
  exe=$build/bin/$target
  [ -x "$exe" ] || { echo "run_fuzzers: $exe missing (cmake --preset fuzz && cmake --build --preset fuzz)"; exit 2; }
  # The seeds stay as committed; what the fuzzer learns goes to a working corpus.
  corpus=$out/$target/corpus
  mkdir -p "$corpus" "$out/$target/artifacts"
  echo "== $target: ${seconds} s"
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: a reader allocating 2 GB for a
  # small file trusts a size field it should not.
  # shellcheck disable=SC2086
  "$exe" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$out/$target/artifacts/" ${FUZZ_FLAGS:-} \
    "$corpus" "$src/corpus/${target#fuzz_}" >"$out/$target/log.txt" 2>&1
  status=$?
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|^Done" "$out/$target/log.txt" | tr '\n' ' '
  echo
  if [ $status -ne 0 ]; then
    failed+=("$target")
    echo "run_fuzzers: $target FAILED (exit $status); input and stack:"
    ls "$out/$target/artifacts/"
    grep -E -A40 "ERROR: (AddressSanitizer|libFuzzer|LeakSanitizer)|runtime error:" "$out/$target/log.txt" | head -60
  fi
done
if ((${#failed[@]})); then
  echo "run_fuzzers: failures in ${failed[*]}; logs and inputs under $out"
  exit 1
fi
echo "run_fuzzers: ${#targets[@]} targets, ${seconds} s each: no crash"
