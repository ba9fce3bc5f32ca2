#!/usr/bin/env bash
# The test suite's check that no program it starts outlives the test that started it: the C
# preprocessor (cpp and its cc1), POV-Ray, GNU parallel and hirsute itself. A process whose
# parent has gone is adopted by process 1; one of those, started since the suite began and still
# running (a zombie is not), fails the check. tests/CMakeLists.txt runs it as the setup and the
# cleanup of a fixture every test requires, so that `check` runs after the last test.
#
#   orphan_processes.sh start STAMP    notes in STAMP when the suite began
#   orphan_processes.sh check STAMP    fails, naming them, while such processes remain
#
# A killed process takes a moment to be reaped: `check` looks again for up to five seconds.
set -euo pipefail

mode=${1:?start or check}
stamp=${2:?the stamp file}

# Fields of /proc/PID/stat after the command name (which may hold spaces and parentheses):
# state, parent, …, and the start time in clock ticks since boot as the 20th.
fields() {
  local stat
  { read -r stat <"/proc/$1/stat"; } 2>/dev/null || return 1
  printf '%s\n' "${stat##*) }"
}

case "$mode" in
  start)
    read -r -a f < <(fields $$)
    echo "${f[19]}" >"$stamp"
    ;;
  check)
    read -r since <"$stamp"
    for try in $(seq 1 20); do
      left=()
      for dir in /proc/[0-9]*; do
        pid=${dir#/proc/}
        { read -r name <"$dir/comm"; } 2>/dev/null || continue
        case "$name" in
          cc1 | cc1plus | cpp | cpp-[0-9]* | povray | parallel | hirsute) ;;
          *) continue ;;
        esac
        rest=$(fields "$pid") || continue
        read -r -a f <<<"$rest"
        [ "${f[0]}" != Z ] && [ "${f[1]}" = 1 ] && [ "${f[19]}" -ge "$since" ] || continue
        command=$(tr '\0' ' ' <"$dir/cmdline" 2>/dev/null | cut -c1-300) || true
        left+=("$pid $name: $command")
      done
      [ ${#left[@]} -eq 0 ] && exit 0
      sleep 0.25
    done
    echo "processes the tests started outlived them (parent 1):" >&2
    printf '  %s\n' "${left[@]}" >&2
    exit 1
    ;;
  *)
    echo "usage: $0 start|check STAMP" >&2
    exit 2
    ;;
esac
