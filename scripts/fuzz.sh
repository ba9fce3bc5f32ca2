#!/usr/bin/env bash
# Builds the libFuzzer targets with the CMake preset `fuzz` (clang) and runs each in turn:
#   parse_derive_fuzzer      .l text: parser, compiler, derivation, homomorphism
#   interpret_fuzzer         the same text interpreted into a Scene and covered with plant hairs
#   feather_file_fuzzer      a feather type file (.fea), read and built into its geometry
#   view_file_fuzzer         a view file (.v): every command, the organ lines (hair:, feather:,
#                            fur …:, droplet:), the dynamics lines, function/curve lines
#   environment_fuzzer       open L-systems: a .e file, the answers a program sends back, query
#                            text, the built-in programs' specification files
#   animation_file_fuzzer    an animation file (.a) and the frames it gives
#   simulate_options_fuzzer  `hirsute simulate`'s argument vector, parsed and checked
#   preprocessor_messages_fuzzer  the C preprocessor's messages, read into diagnostics
#   mesh_file_fuzzer         a mesh file (PLY, OBJ, glTF, GLB, STL, OFF, COLLADA) through the
#                            mesh reader's checks and Assimp, in the fuzzer's process
#
#   scripts/fuzz.sh [SECONDS] [libFuzzer flags…]
#   FUZZ_TARGETS=interpret_fuzzer scripts/fuzz.sh 600              (one target)
#   FUZZ_TARGETS=view_file_fuzzer READER_SECONDS=300 scripts/fuzz.sh
#
# SECONDS (default 60) is the time of each of the two .l targets. The six reader targets run
# READER_SECONDS each, by default a third of SECONDS (at least 1): their inputs are small and
# their formats flat, so they cover in seconds what the .l targets take a minute for, and CI's
# stage (`scripts/fuzz.sh 60`: 2 × 60 s + 6 × 20 s after the build) stays within ten minutes.
#
# Seeds are prepared in build/fuzz/seeds/TARGET: every `.l` under models/ and tests/ (and of
# cpfg's conformance set in ../shared/conformance when it is there), each as written and as the C
# preprocessor hands it to the parser; every `.fea`; every `.v` as written and preprocessed; every
# `.a`; every `.e` and every specification file its executable line names (with the byte that
# picks the program), and a few answer and query texts; a few hand-written argument vectors for
# simulate; every mesh file under models/ and tests/ and a small one of each format (the first
# byte picks it). Each target has its dictionary in fuzz/. Seeds, the growing corpus and any crash
# files live in build/fuzz/, never in the repository. A finding ends the run with a non-zero
# status and leaves its input in build/fuzz/artifacts/; replay it with
#   build/fuzz/fuzz/TARGET build/fuzz/artifacts/crash-…
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift $(( $# > 0 ? 1 : 0 ))
reader_seconds=${READER_SECONDS:-$(( seconds / 3 > 0 ? seconds / 3 : 1 ))}
build="$root/build/fuzz"
all_targets="parse_derive_fuzzer interpret_fuzzer feather_file_fuzzer view_file_fuzzer \
environment_fuzzer animation_file_fuzzer simulate_options_fuzzer preprocessor_messages_fuzzer \
mesh_file_fuzzer"

cd "$root"
cmake --preset fuzz >/dev/null
targets=(${FUZZ_TARGETS:-$all_targets})
cmake --build --preset fuzz --target "${targets[@]}" -j "${JOBS:-$(nproc)}"

seeds="$build/seeds"
corpus_root="$build/corpus"
artifacts="$build/artifacts"
rm -rf "$seeds"
mkdir -p "$artifacts"
for target in $all_targets; do mkdir -p "$seeds/$target"; done
folders=("$root/models" "$root/tests")
[ -d "$root/../shared/conformance" ] && folders+=("$root/../shared/conformance")
seed_name() { printf '%s' "$1" | md5sum | cut -c1-16; }
# What a parser sees in a real run: cpp's output with its line markers. cpp runs with the limits
# a real run has (tests/bad_input holds a macro that asks for 2^40 copies of itself).
preprocessed() {
  (ulimit -v 1048576 && timeout 60 cpp -traditional-cpp -undef -nostdinc -x c \
    -I "$(dirname "$1")" "$1") >"$2" 2>/dev/null || rm -f "$2"
}

count=0
while IFS= read -r -d '' file; do
  name=$(seed_name "$file")
  cp "$file" "$seeds/parse_derive_fuzzer/$name.l"
  preprocessed "$file" "$seeds/parse_derive_fuzzer/$name.cpp.l"
  count=$((count + 1))
done < <(find "${folders[@]}" -name '*.l' -type f -print0 2>/dev/null)
cp "$seeds/parse_derive_fuzzer/"* "$seeds/interpret_fuzzer/"

while IFS= read -r -d '' file; do
  cp "$file" "$seeds/feather_file_fuzzer/$(seed_name "$file").fea"
done < <(find models tests -name '*.fea' -type f -print0)

while IFS= read -r -d '' file; do
  name=$(seed_name "$file")
  cp "$file" "$seeds/view_file_fuzzer/$name.v"
  preprocessed "$file" "$seeds/view_file_fuzzer/$name.cpp.v"
done < <(find models tests -name '*.v' -type f -print0)

while IFS= read -r -d '' file; do
  cp "$file" "$seeds/animation_file_fuzzer/$(seed_name "$file").a"
done < <(find models tests -name '*.a' -type f -print0)

# environment_fuzzer: the first byte picks the kind of text (fuzz/environment_fuzzer.cpp).
env_seeds="$seeds/environment_fuzzer"
programs=(honda81 ecosystem clover chiba density)
while IFS= read -r -d '' file; do
  name=$(seed_name "$file")
  { printf '\x00'; cat "$file"; } >"$env_seeds/$name.e"
  # The specification file the executable line names (its last word), for its program.
  read -r -a words < <(sed -n 's/^executable:[[:space:]]*//p' "$file" | head -n 1)
  [ ${#words[@]} -ge 2 ] || continue
  spec="$(dirname "$file")/${words[-1]}"
  for i in "${!programs[@]}"; do
    if [ "${programs[$i]}" = "${words[0]}" ] && [ -f "$spec" ]; then
      { printf '\x03'; printf "\\x0$i"; cat "$spec"; } >"$env_seeds/$name.spec"
    fi
  done
done < <(find models tests -name '*.e' -type f -print0)
printf '\x011 E(0.5,2)\n2 E(,3e2)\n3 E\n4 E(1,2,3,4,5,6,7,8,9,10,11)\nControl: 5\n' \
  >"$env_seeds/answers"
printf '\x01  7;E(-1e-3)\r\nnot a record\nControl: 4 2\n' >"$env_seeds/answers-rejected"
printf '\x021 E(1,2)F(0.5)\n0 0 0\n0 1 0\n-1 0 0\n0 0 -1\n0.1\n1\n2 E\n1 2\n\n\n\n\n\nControl: 5 1\n' \
  >"$env_seeds/queries"

# simulate_options_fuzzer: arguments separated by NUL bytes, @/ the coat-bending model.
sim_seeds="$seeds/simulate_options_fuzzer"
vector() { local out=$1; shift; printf '%s\0' "$@" >"$sim_seeds/$out"; }
vector plain @/bending.l @/bending.v -o out
vector animation @/bending.l @/bending.v @/bending.a -o out --frames 12 --fps 30 --obj
vector forces @/bending.l @/bending.v -o out --gravity 0 -9.81 0 --wind 1 0 0.5 --gusts 2 \
  --gust-scale 0.5 --gust-period 1.5 --gust-seed 7 --drag 0.1 --substeps 8 --segments 4
vector animate @/bending.l @/bending.v -o out --animate WIDTH=2:4 --no-frames --size 320x240
vector fur @/bending.l @/bending.v -o out --droplets 20 --droplet-radius 0.1 \
  --droplet-wetness 0.5 --droplet-seed 3 --no-fur --no-hairs --max-hairs 10
vector colours @/bending.l -o out -m 2:@/feather-coat.map -M @/feather-coat.map -n 3 \
  --threads 2 --max-modules 1000 --max-vertices 100000 --max-file-bytes 4096
vector weather @/bending.l @/bending.v -o out --drop 2:6 --drop 3:1:0.1:0.5 --rain 24:0.05 \
  --dry 0.5 --dry-from 4 --fur-force 0 -1 0 --fur-drag 2 --drop-seed 9
vector bad @/bending.l -o out --fps nan --frames 0 --gravity 1 2
# A value of thousands of digits (within -max_len below), read without a pattern's recursion.
vector long-animate @/bending.l @/bending.v -o out --no-frames \
  --animate "BEND=$(head -c 8000 /dev/zero | tr '\0' 9):9"

# preprocessor_messages_fuzzer: what cpp says about each .l and .v of tests/bad_input (read there
# by the fuzzer), with a few messages written by hand.
msg_seeds="$seeds/preprocessor_messages_fuzzer"
while IFS= read -r -d '' file; do
  (ulimit -v 1048576 && timeout 60 cpp -traditional-cpp -undef -nostdinc -x c \
    -fno-diagnostics-show-caret -I "$(dirname "$file")" "$file") 2>"$msg_seeds/$(seed_name "$file")" \
    >/dev/null || true
done < <(find "$root/tests/bad_input" \( -name '*.l' -o -name '*.v' \) -type f -print0)
find "$msg_seeds" -type f -empty -delete
printf '%s\n' "$root/tests/bad_input/missing_include.l:3:2: fatal error: no_such_header.h: No such file or directory" \
  "compilation terminated." >"$msg_seeds/missing"
printf '%s\n' "In file included from m.l:2:" "m.h:1:9: warning: #warning soft" \
  "m.h:4:2: error: #error hard" "cc1: out of memory allocating 8 bytes after a total of 8 bytes" \
  >"$msg_seeds/mixed"

# mesh_file_fuzzer: the first byte picks the format (fuzz/mesh_file_fuzzer.cpp: its value
# modulo 7 in this order).
mesh_seeds="$seeds/mesh_file_fuzzer"
mesh_formats=(ply obj gltf glb stl off dae)
mesh_seed() { # FORMAT-INDEX NAME, the file's bytes on standard input
  { printf "\\x0$1"; cat; } >"$mesh_seeds/$2"
}
for i in "${!mesh_formats[@]}"; do
  while IFS= read -r -d '' file; do
    mesh_seed "$i" "$(seed_name "$file").${mesh_formats[$i]}" <"$file"
  done < <(find models tests -iname "*.${mesh_formats[$i]}" -type f -print0)
done
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 9 9 9\n3 0 1 2\n4 0 1 2 3\n' |
  mesh_seed 0 square.ply
{ printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n'
  printf '\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x00'
  printf '\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00'; } | mesh_seed 0 triangle-binary.ply
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1 0 0\nvt 0 0\nvt 1 1\nvn 0 0 1\ng a\nusemtl m\nf 1/1/1 2/2/1 3/1/1\ng b\nf 1 3 4\n' |
  mesh_seed 1 square.obj
printf 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' |
  mesh_seed 4 triangle.stl
printf 'OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n' | mesh_seed 5 square.off
printf '<?xml version="1.0"?>\n<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">\n<asset><up_axis>Y_UP</up_axis></asset>\n<library_geometries><geometry id="g"><mesh>\n<source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>\n<technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>\n<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>\n<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>\n</mesh></geometry></library_geometries>\n<library_visual_scenes><visual_scene id="s"><node id="n"><node id="m"><instance_geometry url="#g"/></node></node></visual_scene></library_visual_scenes>\n<scene><instance_visual_scene url="#s"/></scene>\n</COLLADA>\n' |
  mesh_seed 6 triangle.dae
# A triangle as a binary glTF: its JSON chunk and its buffer of three positions.
if command -v python3 >/dev/null; then
  python3 - "$mesh_seeds/triangle.glb" <<'PY'
import json, struct, sys
positions = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
gltf = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"children": [1]}, {"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"byteLength": len(positions)}],
        "bufferViews": [{"buffer": 0, "byteLength": len(positions)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}]}
text = json.dumps(gltf).encode()
text += b' ' * (-len(text) % 4)
body = struct.pack('<II', len(text), 0x4E4F534A) + text + struct.pack('<II', len(positions), 0x004E4942) + positions
with open(sys.argv[1], 'wb') as out:
    out.write(b'\x03' + b'glTF' + struct.pack('<II', 2, 12 + len(body)) + body)
PY
fi

echo "fuzz: $count .l seed files; running ${targets[*]}" \
  "(.l targets $seconds s each, the readers $reader_seconds s each)" >&2

# libFuzzer's own work files go to the build folder too.
cd "$build"
for target in "${targets[@]}"; do
  own=()
  case "$target" in
    parse_derive_fuzzer | interpret_fuzzer) dict=lsystem time=$seconds ;;
    # Assimp (Debian's, not instrumented) leaks what it allocated when it gives up on a broken
    # file: its leaks are no finding here (the program reads meshes in a child process, whose
    # memory ends with it); crashes, hangs and memory errors still are.
    mesh_file_fuzzer) dict=mesh_file time=$reader_seconds own=(-detect_leaks=0) ;;
    *) dict=${target%_fuzzer} time=$reader_seconds ;;
  esac
  corpus="$corpus_root/$target"
  mkdir -p "$corpus"
  echo "fuzz: $target" >&2
  "$build/fuzz/$target" \
    -max_total_time="$time" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
    -dict="$root/fuzz/$dict.dict" -artifact_prefix="$artifacts/" -print_final_stats=1 \
    "${own[@]}" "$@" "$corpus" "$seeds/$target"
done
