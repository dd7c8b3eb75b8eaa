#!/usr/bin/env bash
# Fetch the three course world maps (third-party data, never committed here) into DEST/maps,
# as BOTSIM_REFERENCE expects them, and check them against their published SHA-256 sums.
# Source: the public repository pdxrayw/ECE540Proj2 (the Fall 2014 release); give a local
# checkout of it as SOURCE to skip the download.
# Usage: scripts/ci/fetch-maps.sh DEST [SOURCE]
set -euo pipefail
dest=${1:?usage: fetch-maps.sh DEST [SOURCE]}
src=${2:-}
if [ -z "$src" ]; then
  src=$(mktemp -d)
  trap 'rm -rf "$src"' EXIT
  git clone -q --depth 1 https://github.com/pdxrayw/ECE540Proj2 "$src"
fi
mkdir -p "$dest/maps"
for m in part1 lr loop; do
  for ext in txt coe; do
    cp "$src/project2_release_r0/world_maps/world_map_$m/map/world_map_$m.$ext" "$dest/maps/"
  done
done
cd "$dest/maps"
sha256sum --quiet -c - <<'SUMS'
143d433db078f049701bea3404a36a4637807fd30ed2cada0f80724d2f994c60  world_map_part1.txt
96ae88a527e038ab12620b977ea11c70fd49000138ed842c4b271a9c6c314257  world_map_part1.coe
661b6d9be893c2f90b7c2f6d53e06155bb7ff23f7ab6af04e1ff54006d8a892d  world_map_lr.txt
ae2c9e543b6806d174632b4661c862fe8a9b4ca904414fa0ad634bebee86dc75  world_map_lr.coe
6ea8f57e64688b90f658341a65f5bc98baeed7fba4354bbf7cbac5b942de89f7  world_map_loop.txt
14ce39cf23a297d6cfb96bf411ad9e7195296d762e31370e7de08ea361968794  world_map_loop.coe
SUMS
echo "fetch-maps: the three course maps are in $dest/maps (SHA-256 checked)"
