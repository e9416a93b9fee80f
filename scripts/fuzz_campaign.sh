#!/usr/bin/env bash
# `make fuzz`: each libFuzzer harness of fuzz/ for SECONDS (default 600), one at a time (one
# core), from the checked-in seeds and past findings, with a 20 s per-input timeout and leak
# detection. New corpus entries and findings go to BUILD/fuzz/campaign/<harness>/ (never into
# fuzz/corpus). Prints per harness: executions, exec/s, corpus size, crashes, timeouts, leaks;
# the same table is written to BUILD/fuzz/campaign/summary.md.
#   scripts/fuzz_campaign.sh [BUILD] [SECONDS] [HARNESS...]
set -uo pipefail
build=${1:-build}
seconds=${2:-600}
shift $(( $# < 2 ? $# : 2 ))
harnesses=("$@")
# shellcheck disable=SC2207  # the one list of harnesses, one word each
[ ${#harnesses[@]} -eq 0 ] && harnesses=($(cat "$(dirname "$0")/../fuzz/harnesses.txt"))
src=$(cd "$(dirname "$0")/.." && pwd)
bin=$build/fuzz
if [ ! -x "$bin/fuzz_${harnesses[0]}" ]; then
  echo "fuzz: no harnesses in $bin (clang++ with libFuzzer missing? see fuzz/README.md)" >&2
  exit 1
fi
out=$build/fuzz/campaign
mkdir -p "$out"
summary=$out/summary.md
{
  echo "| harness | seconds | executions | exec/s | corpus (files) | crashes | timeouts | leaks | ooms |"
  echo "|---|---|---|---|---|---|---|---|---|"
} > "$summary"
echo "fuzz: $seconds s per harness, $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
status=0
for h in "${harnesses[@]}"; do
  dir=$out/$h
  mkdir -p "$dir/corpus" "$dir/findings"
  dirs=("$dir/corpus" "$src/fuzz/corpus/$h")
  [ -d "$src/fuzz/regressions/$h" ] && dirs+=("$src/fuzz/regressions/$h")
  start=$(date +%s)
  "$bin/fuzz_$h" "${dirs[@]}" -max_total_time="$seconds" -timeout=20 -detect_leaks=1 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$dir/findings/" > "$dir/log.txt" 2>&1
  rc=$?
  elapsed=$(( $(date +%s) - start ))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log.txt" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$dir/log.txt" | tail -1)
  corpus=$(find "$dir/corpus" "$src/fuzz/corpus/$h" -type f | wc -l)
  count() { find "$dir/findings" -name "$1-*" | wc -l; }
  crashes=$(count crash) timeouts=$(count timeout) leaks=$(count leak) ooms=$(count oom)
  printf 'fuzz_%-11s %5d s  %10s execs  %6s exec/s  corpus %5d  crashes %d  timeouts %d  leaks %d  ooms %d\n' \
    "$h" "$elapsed" "${execs:-?}" "${rate:-?}" "$corpus" "$crashes" "$timeouts" "$leaks" "$ooms"
  echo "| $h | $elapsed | ${execs:-?} | ${rate:-?} | $corpus | $crashes | $timeouts | $leaks | $ooms |" >> "$summary"
  if [ $rc -ne 0 ]; then
    status=1
    echo "  finding: $(ls "$dir/findings" | tr '\n' ' ')(log: $dir/log.txt)"
  fi
done
echo "fuzz: table in $summary"
exit $status
