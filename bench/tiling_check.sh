#!/usr/bin/env bash
# Tiled against untiled output on every bundled image (bench/data): the largest difference in
# 8-bit levels and the share of samples that differ, for the CPU backend's tiles (which are
# automatic beyond its working memory) and the consistent surface, at ×2 and ×4.
#
#   bench/tiling_check.sh [TILE_SIDE] [-- DDTUP_OPTIONS…]      (default: 128)
#
# DDTUP picks the binary (default: build/ddtup). Needs vips (libvips-tools) for the comparison.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
ddtup=${DDTUP:-$repo/build/ddtup}
side=${1:-128}
[ $# -eq 0 ] || shift
[ "${1:-}" != -- ] || shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

printf '| image | scale | largest difference (levels) | differing samples |\n|---|---|---|---|\n'
for input in "$repo"/bench/data/real/*.png "$repo"/bench/data/artificial/*.png; do
    name=$(basename "$input" .png)
    for scale in 2 4; do
        # A tile side beyond the image makes it one piece.
        "$ddtup" "$input" "$work/whole.png" -s "$scale" -q --backend cpu --tile 1000000 "$@"
        "$ddtup" "$input" "$work/tiled.png" -s "$scale" -q --backend cpu --tile "$side" "$@"
        vips subtract "$work/whole.png" "$work/tiled.png" "$work/difference.v"
        vips abs "$work/difference.v" "$work/magnitude.v"
        largest=$(vips max "$work/magnitude.v")
        vips relational_const "$work/magnitude.v" "$work/differs.v" more 0
        share=$(vips avg "$work/differs.v")  # 255 where a sample differs
        samples=$(($(vipsheader -f width "$work/differs.v") * $(vipsheader -f height "$work/differs.v") *
                   $(vipsheader -f bands "$work/differs.v")))
        printf '| %s | ×%s | %.0f | %s |\n' "$name" "$scale" "$largest" \
            "$(awk -v s="$share" -v n="$samples" 'BEGIN { printf "%.0f of %d (%.5f %%)", s / 255 * n, n, s / 255 * 100 }')"
    done
done
