#!/usr/bin/env bash
# Times one batch run of ddtup over N images against N separate invocations on the same
# images (issue #6: the device and its pipelines are created once per run, and reading,
# optimizing and writing overlap). The images cycle through bench/data.
#
#   bench/batch_throughput.sh [-n COUNT] [-- DDTUP_OPTIONS…]      (default: 50 images, -s 2)
#
# DDTUP picks the binary (default: build/ddtup). Prints both wall times and the ratio.
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
ddtup=${DDTUP:-$repo/build/ddtup}
count=50
while [[ $# -gt 0 ]]; do
    case $1 in
        -n) count=$2; shift 2 ;;
        --) shift; break ;;
        *) echo "usage: $0 [-n COUNT] [-- DDTUP_OPTIONS…]" >&2; exit 2 ;;
    esac
done
options=("$@")
[[ ${#options[@]} -gt 0 ]] || options=(-s 2)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/in" "$work/batch" "$work/single"
mapfile -t sources < <(find "$repo/bench/data/real" "$repo/bench/data/artificial" -name '*.png' | sort)
for ((i = 0; i < count; ++i)); do
    cp "${sources[i % ${#sources[@]}]}" "$(printf '%s/in/img-%02d.png' "$work" "$i")"
done

now() { date +%s.%N; }

start=$(now)
"$ddtup" -i "$work/in" -o "$work/batch" -q "${options[@]}"
batch_s=$(awk -v a="$(now)" -v b="$start" 'BEGIN { print a - b }')

start=$(now)
for input in "$work"/in/*.png; do
    "$ddtup" "$input" "$work/single/$(basename "$input")" -q "${options[@]}"
done
single_s=$(awk -v a="$(now)" -v b="$start" 'BEGIN { print a - b }')

# Both ways must give the same files.
cmp_failures=0
for output in "$work"/batch/*.png; do
    cmp -s "$output" "$work/single/$(basename "$output")" || cmp_failures=$((cmp_failures + 1))
done

awk -v n="$count" -v b="$batch_s" -v s="$single_s" -v o="${options[*]}" -v d="$cmp_failures" 'BEGIN {
    printf "images            %d (options: %s)\n", n, o
    printf "one batch run     %.2f s  (%.3f s per image)\n", b, b / n
    printf "separate runs     %.2f s  (%.3f s per image)\n", s, s / n
    printf "speed-up          %.2fx\n", s / b
    printf "differing outputs %d\n", d
}'
