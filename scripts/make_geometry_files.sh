#!/usr/bin/env bash
# Writes the CAD files of problems/geometry/ from their gmsh geometry files with gmsh's
# OpenCASCADE kernel: each <body>.geo listed below as <body>.step (AP214), replaced only once
# gmsh has written it whole. Run from anywhere:
#   scripts/make_geometry_files.sh
set -euo pipefail
DIR="$(cd "$(dirname "$0")/.." && pwd)/problems/geometry"
for body in filleted_bar; do
  for ext in step; do
    tmp="$(mktemp "$DIR/.${body}.XXXXXX.$ext")"
    gmsh -0 "$DIR/$body.geo" -o "$tmp" -format "$ext" > /dev/null
    mv "$tmp" "$DIR/$body.$ext"
    echo "wrote $DIR/$body.$ext"
  done
done
