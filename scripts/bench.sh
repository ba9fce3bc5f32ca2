#!/usr/bin/env bash
# Builds Hirsute in Release (without the tests) and prints the derivation benchmark's figures
# (in process, then the whole `hirsute derive` process timed with GNU time), then the
# interpretation benchmark's (string to Scene: modules and triangles per second), with
# HAIRS=1 the hair benchmarks' and with FUR=1 the fur strand export's.
# Arguments go to the derivation benchmark: --model NAME, --repeat N, --models DIR;
# INTERPRET_ARGS to the interpretation benchmark (e.g. "--model tubes --repeat 10").
#   scripts/bench.sh --repeat 5
# BUILD_DIR overrides the build folder; JOBS the build's parallel jobs (default: all cores).
# HIRSUTE=PATH skips the build and the in-process benchmarks and prints only the whole-process
# table for that program (e.g. HIRSUTE=build/release/cli/hirsute, an existing Release build);
# NATIVE=PATH then names the loops floor program to print below it
# (build/release/bench/hirsute_loops_native_bench).
set -euo pipefail
cd "$(dirname "$0")/.."

build="${BUILD_DIR:-build/bench}"
program="${HIRSUTE:-}"
if [[ -z "$program" ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DHIRSUTE_BUILD_TESTS=OFF \
    -DHIRSUTE_BUILD_BENCH=ON >/dev/null
  cmake --build "$build" --target hirsute hirsute_derive_bench hirsute_interpret_bench \
    hirsute_loops_native_bench -j "${JOBS:-$(nproc)}"
  "$build/bench/hirsute_derive_bench" "$@"
  echo
  program="$build/cli/hirsute"
fi

# cpfg on the same kinds of model, as issue 10 of the project measured it (cpfg built from vlab
# 9bf820d, `cpfg -g -str`, string written with -o, whole process, best of 5, on the machines
# the project is measured on): seconds and peak MiB. cpfg is not installed here, so these are
# that measurement's figures, not a run of this script. The goal is 3x cpfg's speed and at most
# its peak memory. Kinds without a figure (branching) print none.
# leaves, fourier and coin are this project's models of the three kinds issue 27 timed cpfg on
# (its models, of the shapes these follow, are not in the repository): cpfg's seconds from that
# table; its memory there was about our peak (our/cpfg 0.86x-0.96x), given here as 18 MiB.
cpfg_reference() {
  case "$1" in
    parametric) echo "1.03 56" ;;
    signal) echo "0.98 18" ;;
    loops) echo "1.21 18" ;;
    stochastic) echo "0.16 20" ;;
    leaves) echo "0.97 18" ;;
    fourier) echo "1.19 18" ;;
    coin) echo "0.15 18" ;;
    *) echo "" ;;
  esac
}

# The same models as a user runs them: the whole `hirsute derive MODEL.l [MODEL.v] -o OUT`
# process (start-up, preprocessor, derivation, -str text), best wall time of RUNS (default 5)
# and the peak resident size that GNU time reports (the largest of hirsute and its cpp).
runs="${RUNS:-5}"
# Wall seconds since an $EPOCHREALTIME reading, to the millisecond (GNU time's %e has two
# decimals: a tenth of the stochastic kind's time). It includes starting GNU time itself.
elapsed() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.3f", b - a }'; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
printf '%-11s %8s %6s %10s %9s %10s %13s %14s %8s %8s %5s\n' "model" "whole s" "cpu s" \
  "1 thread s" "peak MiB" "text bytes" "cpfg s (ref)" "cpfg MiB (ref)" "speed" "memory" "goal"
for model in models/bench/*.l; do
  name="$(basename "$model" .l)"
  # The interpretation and feather benchmarks' models, not derivation kinds.
  [[ "$name" == tubes || "$name" == feather-coat ]] && continue
  view=()
  [[ -f "${model%.l}.v" ]] && view=("${model%.l}.v")
  best=""
  cpu=""
  single=""
  peak=0
  for ((run = 0; run < runs; ++run)); do
    started="$EPOCHREALTIME"
    /usr/bin/time -f '%e %U %S %M' -o "$out/time" "$program" derive "$model" "${view[@]}" \
      -o "$out/$name.str"
    seconds="$(elapsed "$started")"
    read -r _ user system kib <"$out/time"
    if [[ -z "$best" ]] || awk -v a="$seconds" -v b="$best" 'BEGIN { exit !(a < b) }'; then
      best="$seconds"
    fi
    used="$(awk -v u="$user" -v s="$system" 'BEGIN { printf "%.2f", u + s }')"
    if [[ -z "$cpu" ]] || awk -v a="$used" -v b="$cpu" 'BEGIN { exit !(a < b) }'; then
      cpu="$used"
    fi
    ((kib > peak)) && peak="$kib"
    # The same on one thread (--threads 1): what the parts of long steps win.
    started="$EPOCHREALTIME"
    /usr/bin/time -f '%e %U %S %M' -o "$out/time" "$program" derive "$model" "${view[@]}" \
      -o "$out/$name.str" --threads 1
    seconds="$(elapsed "$started")"
    read -r _ user system kib <"$out/time"
    if [[ -z "$single" ]] || awk -v a="$seconds" -v b="$single" 'BEGIN { exit !(a < b) }'; then
      single="$seconds"
    fi
    ((kib > peak)) && peak="$kib"
  done
  mib="$(awk -v k="$peak" 'BEGIN { printf "%.1f", k / 1024 }')"
  read -r cpfg_s cpfg_mib <<<"$(cpfg_reference "$name")"
  if [[ -n "${cpfg_s:-}" ]]; then
    # speed: how many times faster than cpfg; memory: our peak as a share of cpfg's.
    read -r speed memory goal <<<"$(awk -v s="$best" -v m="$mib" -v cs="$cpfg_s" -v cm="$cpfg_mib" \
      'BEGIN { sp = cs / s; me = m / cm; printf "%.2fx %.2fx %s", sp, me, (sp >= 3 && me <= 1) ? "met" : "no" }')"
  else
    cpfg_s="-" cpfg_mib="-" speed="-" memory="-" goal="-"
  fi
  printf '%-11s %8s %6s %10s %9s %10s %13s %14s %8s %8s %5s\n' "$name" "$best" "$cpu" "$single" "$mib" \
    "$(stat -c %s "$out/$name.str")" "$cpfg_s" "$cpfg_mib" "$speed" "$memory" "$goal"
  unset cpfg_s cpfg_mib
done
echo "(whole process, best of $runs: wall time to the millisecond (GNU time's own start included)"
echo " with a thread a core ($(nproc) here), the CPU time (user + system) of hirsute and its cpp,"
echo " and the wall time with --threads 1;"
echo " peak resident size the largest of the runs, GNU time's %M,"
echo " which counts the preprocessor cpp that hirsute runs as cpfg does; cpfg columns: issue 10's"
echo " measurement of cpfg, not run here; speed = cpfg s / ours, memory = ours / cpfg's;"
echo " goal: at least 3x the speed at no more than cpfg's memory)"

# The floor under the loops kind: its blocks compiled natively (bench/loops_native_bench.cpp),
# the same libm calls and power operator, checked against the string hirsute derived above;
# whole process, best of RUNS, on every core and on one. No evaluator can run the model in less.
native="${NATIVE:-$build/bench/hirsute_loops_native_bench}"
if [[ -x "$native" && -f "$out/loops.str" ]]; then
  # The last line: every ^ as libm's pow, as cpfg's evaluator computes it, on one thread as
  # cpfg runs: the arithmetic of cpfg's own run, against cpfg's figure for the whole of it.
  for how in "0" "1" "1 --libm-pow"; do
    read -r threads pow <<<"$how"
    best=""
    for ((run = 0; run < runs; ++run)); do
      started="$EPOCHREALTIME"
      "$native" --threads "$threads" ${pow:+"$pow"} --check "$out/loops.str" >"$out/native" ||
        { cat "$out/native"; exit 1; }
      seconds="$(elapsed "$started")"
      if [[ -z "$best" ]] || awk -v a="$seconds" -v b="$best" 'BEGIN { exit !(a < b) }'; then
        best="$seconds"
      fi
    done
    if [[ -n "$pow" ]]; then
      echo "loops.l's blocks compiled natively with libm's pow for every ^ (cpfg's arithmetic)," \
        "one thread: $best s (best of $runs, the same string; cpfg's figure for its whole run: 1.21 s)"
    else
      label="$([[ "$threads" == 0 ]] && echo "a thread a core" || echo "one thread")"
      echo "loops.l's blocks compiled natively, $label: $best s (best of $runs, the same string;" \
        "cpfg/3 = $(awk 'BEGIN { printf "%.2f", 1.21 / 3 }') s)"
    fi
  done
fi
[[ -n "${HIRSUTE:-}" ]] && exit 0
echo
# shellcheck disable=SC2086  # INTERPRET_ARGS is a list of arguments
"$build/bench/hirsute_interpret_bench" ${INTERPRET_ARGS:-}

# HAIRS=1 adds the hair benchmarks: the renderer's instanced hairs against raw GL lines of the
# same segments, and a million hairs exported (POV-Ray's parse time when povray is installed).
if [[ "${HAIRS:-0}" == 1 ]]; then
  cmake --build "$build" --target hirsute_hair_render_bench hirsute_hair_export_bench \
    -j "${JOBS:-$(nproc)}"
  echo
  "$build/bench/hirsute_hair_render_bench"
  echo
  "$build/bench/hirsute_hair_export_bench" --runs 1
fi

# FUR=1 adds the fur strand export: the furry torus scaled to about a million strands, written
# to POV-Ray (strands per second) and rendered by POV-Ray at 640×480 (parse and trace times,
# peak memory; several minutes on two cores).
if [[ "${FUR:-0}" == 1 ]]; then
  cmake --build "$build" --target hirsute_fur_export_bench -j "${JOBS:-$(nproc)}"
  echo
  "$build/bench/hirsute_fur_export_bench"
fi
