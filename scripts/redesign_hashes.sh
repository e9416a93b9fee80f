#!/usr/bin/env bash
# The outputs a redesign must keep (issue 22, docs/architecture.md "Redesign record"): runs each
# with the given build and prints its sha256. Usage: scripts/redesign_hashes.sh BUILD_DIR OUT_DIR
# (from the source tree's top folder). About 3 minutes on 2 cores.
set -euo pipefail
build=$(realpath "$1"); out=$2
mkdir -p "$out"; out=$(realpath "$out")
plumage="$build/bin/plumage"
q=(-q)
"$plumage" "${q[@]}" characterize configs/species/rockdove.yaml --variant forest --fidelity preview \
  --out "$out/rockdove-forest-preview.plm"
"$plumage" "${q[@]}" table build configs/crystals/mallard-green.yaml --fidelity preview \
  --out "$out/mallard-green-preview.plt"
"$plumage" "${q[@]}" simulate configs/species/rockdove.yaml --lambda-nm 400:694:6 --theta-deg 0 \
  --phi-deg 0 --instances 50 --out "$out/rd.ffs" --csv "$out/rd.csv"
"$plumage" "${q[@]}" compare tests/cli/data/compare-tiny.yaml --out "$out/compare" --no-pictures > /dev/null
"$plumage" "${q[@]}" render configs/scenes/demo.yaml --out "$out/demo" --materials "$out/materials" > /dev/null
# Beyond the issue's five: a crystal species, the full-wave BEM and the generators' geometry.
"$plumage" "${q[@]}" simulate configs/validation/keratin-cylinder-bem.yaml --lambda-nm 550 \
  --directions full --out "$out/cyl.ffs" --csv "$out/cyl.csv"
"$plumage" "${q[@]}" geometry configs/species/hummingbird.yaml --instances 3 --out "$out/hb" > /dev/null
"$plumage" "${q[@]}" multilayer --stack "air | keratin 300 | {melanin 90 | keratin 100}*6 | air" \
  --lambda-nm 400:700:10 --theta-deg 0,30,60 --format csv > "$out/multilayer.csv"
cd "$out"
sha256sum rockdove-forest-preview.plm mallard-green-preview.plt demo/demo.exr rd.ffs compare/tiny-metrics.csv \
  rd.csv cyl.ffs cyl.csv multilayer.csv hb/* | sort -k2
