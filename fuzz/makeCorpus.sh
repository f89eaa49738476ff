#!/usr/bin/env bash
# Writes the seed corpora fuzz/corpus/<target>/data-* from the fixtures in tests/data (files
# OpenFOAM wrote). The hand-written seeds next to them (names without "data-") are kept.
# Re-run after changing the fixtures; the output is committed.
set -euo pipefail
cd "$(dirname "$0")"
data=../tests/data
corpus=corpus

for target in dictionaryFuzzer asciiListFuzzer binaryListFuzzer pointFieldFuzzer polyMeshFuzzer; do
  mkdir -p "$corpus/$target"
  rm -f "$corpus/$target"/data-*
done

# dictionaryFuzzer: dictionaries of every kind the project reads.
d=$corpus/dictionaryFuzzer
cp $data/dictionaries/boundary $d/data-boundary
cp $data/dictionaries/includeEtc $d/data-includeEtc
cp $data/dictionaries/missingInclude $d/data-missingInclude
cp $data/dictionaries/includes/main $d/data-includesMain
cp $data/dictionaries/includes/sub/coefficients $d/data-includesCoefficients
cp $data/dictionaries/loop/a $d/data-loopA
cp $data/dictionaries/pointField/ascii/1/pointDisplacement $d/data-pointDisplacementAscii
cp $data/dictionaries/pointField/binary/1/pointDisplacement $d/data-pointDisplacementBinary
cp $data/boundaryMotion/pointPatchConditions/0/pointDisplacement $d/data-pointDisplacementPatchConditions
for c in multiRotationTranslation oscillatingRotation rotationPolynomialOmega rotationTableOmega tabulated6DoF pointPatchConditions; do
  cp $data/boundaryMotion/$c/constant/dynamicMeshDict $d/data-dynamicMeshDict-$c
done
for f in blockMeshDict controlDict fvSchemes fvSolution; do
  cp $data/checkMesh/skewedHex/system/$f $d/data-$f
done
cp $data/formats/ascii/constant/polyMesh/faceZones $d/data-faceZones
cp $data/formats/binary/constant/polyMesh/faceZones $d/data-faceZonesBinary

# asciiListFuzzer: the list files of small ascii meshes (header and body).
d=$corpus/asciiListFuzzer
for f in points faces owner neighbour; do
  cp $data/dictionaries/pointField/ascii/constant/polyMesh/$f $d/data-pointFieldMesh-$f
done
cp $data/formats/asciiFaceCompactList/constant/polyMesh/faces $d/data-faceCompactList
cp $data/formats/ascii/constant/polyMesh/points $d/data-formatsAscii-points

# binaryListFuzzer: binary bodies (header removed) behind a selector byte:
# bits 0-2 list kind (0 vectorField, 1 faceList, 2 faceCompactList, 3 labelList, 4 scalarField,
# 5 boolList), bit 3 64-bit labels, bit 4 32-bit scalars; see FuzzEntryPoints.hpp.
d=$corpus/binaryListFuzzer
body() { python3 -c '
import sys
text = open(sys.argv[1], "rb").read()
start = text.index(b"FoamFile")
close = text.index(b"}", start)
sys.stdout.buffer.write(bytes([int(sys.argv[2])]) + text[close + 1:])' "$@"; }
for variant in binary:0 binaryLabel64:8; do
  folder=${variant%%:*}; bits=${variant#*:}
  body $data/formats/$folder/constant/polyMesh/points $((0 | bits)) > $d/data-$folder-points
  body $data/formats/$folder/constant/polyMesh/faces $((2 | bits)) > $d/data-$folder-faces
  body $data/formats/$folder/constant/polyMesh/owner $((3 | bits)) > $d/data-$folder-owner
  body $data/formats/$folder/constant/polyMesh/neighbour $((3 | bits)) > $d/data-$folder-neighbour
done

# pointFieldFuzzer: pointDisplacement files of the fuzz mesh (tests/data/dictionaries/pointField).
d=$corpus/pointFieldFuzzer
cp $data/dictionaries/pointField/ascii/0/pointDisplacement $d/data-ascii0
cp $data/dictionaries/pointField/ascii/1/pointDisplacement $d/data-ascii1
cp $data/dictionaries/pointField/binary/1/pointDisplacement $d/data-binary1

# polyMeshFuzzer: whole polyMesh folders, the files joined by the separator @@file@@ in the
# order points faces owner neighbour boundary [pointZones faceZones cellZones].
d=$corpus/polyMeshFuzzer
join() {
  local out=$1 folder=$2; shift 2
  local first=1
  : > "$out"
  for f in "$@"; do
    [ $first = 1 ] || printf '@@file@@' >> "$out"
    first=0
    if [ -e "$folder/$f" ]; then cat "$folder/$f" >> "$out"; else cat "$folder/$f.gz" >> "$out"; fi
  done
}
join $d/data-pointFieldMesh $data/dictionaries/pointField/ascii/constant/polyMesh points faces owner neighbour boundary
for format in ascii asciiFaceCompactList asciiGzip binary binaryLabel64; do
  join $d/data-formats-$format $data/formats/$format/constant/polyMesh \
    points faces owner neighbour boundary pointZones faceZones cellZones
done

for target in dictionaryFuzzer asciiListFuzzer binaryListFuzzer pointFieldFuzzer polyMeshFuzzer; do
  echo "$target: $(ls "$corpus/$target" | wc -l) seeds, $(du -sk "$corpus/$target" | cut -f1) kB"
done
