#!/usr/bin/env bash
# The costs a hostile or merely huge model can drive, each measured as the user meets it: the
# whole `hirsute` process under GNU time (wall seconds, peak MiB, exit code). Each row is an
# input that once took minutes or gigabytes (issue 21); it must now stay fast or stop at a limit
# with a message, which the last column shows.
#   scripts/bench-input-costs.sh            (builds build/release first)
# HIRSUTE=PATH skips the build.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
program="${HIRSUTE:-}"
if [[ -z "$program" ]]; then
  cmake --preset release >/dev/null
  cmake --build --preset release --target hirsute hirsute_drawing >/dev/null
  program="$root/build/release/cli/hirsute"
fi
program="$(realpath "$program")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"

# A block of N assignments, each with its own number (the compiler's constant table).
assignments() {
  python3 - "$1" > "assign-$1.l" <<'PY'
import sys
n = int(sys.argv[1])
body = "".join(f"x = x + {i}.5;\n" for i in range(n))
print(f"#define STEPS 1\nLsystem: 1\nStart: {{ x = 0;\n{body}printf(\"%g\\n\", x); }}\n"
      "derivation length: 1\nAxiom: A\nendlsystem")
PY
}
# A source file of about N MiB: a long axiom of parametric modules.
source_of() {
  python3 - "$1" > "source-$1.l" <<'PY'
import sys
n = int(sys.argv[1]) << 20
module = "F(1.5)+(2)"
print("Lsystem: 1\nderivation length: 0\nAxiom: " + module * (n // len(module)) + "\nendlsystem")
PY
}
# N peacock feathers (@Fe) at one spot.
feathers() {
  cp "$root/models/peacock-feather/"{peacock.fea,peacock-eye.png,peacock-feather.v} .
  python3 -c "import sys; print('Lsystem: 1\nderivation length: 0\nAxiom: ' + '@Fe(1)' * int(sys.argv[1]) + '\nendlsystem')" "$1" > "feathers-$1.l"
}

row() {
  local name="$1"; shift
  local status=0
  /usr/bin/time -f "%e %M" -o time.txt "$@" > out.txt 2> err.txt || status=$?
  read -r seconds kib < <(tail -1 time.txt)
  local said
  said="$(grep -m1 'error' err.txt | cut -c1-110 || true)"
  printf '%-38s %8s %9d %5d  %s\n' "$name" "$seconds" "$((kib / 1024))" "$status" "${said:-}"
}

printf '%-38s %8s %9s %5s  %s\n' "input" "seconds" "peak MiB" "exit" "first error line"
for n in 5000 50000; do
  assignments "$n"
  row "block of $n assignments (derive)" "$program" derive "assign-$n.l"
done
for mib in 4 16; do
  source_of "$mib"
  row "$mib MiB axiom (derive)" "$program" derive "source-$mib.l" -o axiom.str
done
for n in 400 4095; do
  feathers "$n"
  row "$n peacock @Fe (export --pov)" "$program" export "feathers-$n.l" peacock-feather.v \
    --pov feathers.pov
  row "$n peacock @Fe (render 640x480)" "$program" render "feathers-$n.l" peacock-feather.v \
    -o feathers.png --size 640x480
done
