#!/usr/bin/env bash
# `cmake --install` of this build into a scratch prefix, then the installed program used from
# another folder as a person would: `hirsute` on the PATH draws a model (loading its drawing
# module from PREFIX/lib/hirsute, not from the build), `man hirsute` shows every command, and
# bash completes commands, options and model files.
#   tests/cli/install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source_dir=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
prefix=$scratch/prefix
fail() { echo "install test: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" >/dev/null
[ -x "$prefix/bin/hirsute" ] || fail "no $prefix/bin/hirsute"
for module in libhirsute-drawing.so libhirsute-trace.so libhirsute-meshes.so libhirsute-gltf.so; do
  [ -f "$prefix/lib/hirsute/$module" ] || fail "no $prefix/lib/hirsute/$module"
done

mkdir "$scratch/work"
cd "$scratch/work"
export PATH="$prefix/bin:$PATH"
[ "$(command -v hirsute)" = "$prefix/bin/hirsute" ] || fail "hirsute is not the installed one"
hirsute --version | grep -q '^hirsute ' || fail "hirsute --version"
hirsute --help | grep -q '^Usage: hirsute ' || fail "the usage line does not say hirsute"

hirsute render "$source_dir/models/herb/herb.l" "$source_dir/models/herb/herb.v" -o herb.png \
  --size 32x24
[ -s herb.png ] || fail "the installed hirsute drew no herb.png"
# The drawing module comes from the prefix: the dynamic loader's log names each file it loads.
# (The log's variables reach the C preprocessor too, whose output they spoil, so this second
# run's outcome is not looked at; the module is loaded before the model is read.)
LD_DEBUG=files LD_DEBUG_OUTPUT="$scratch/loader" hirsute render \
  "$source_dir/models/herb/herb.l" "$source_dir/models/herb/herb.v" -o herb2.png --size 32x24 \
  >/dev/null 2>&1 || true
grep -q "file=$prefix/lib/hirsute/libhirsute-drawing.so" "$scratch"/loader.* ||
  fail "the drawing module was not loaded from $prefix/lib/hirsute"

# The man page.
if [ -f "$prefix/share/man/man1/hirsute.1" ]; then
  page=$(MANPATH="$prefix/share/man" MANWIDTH=100 man hirsute 2>/dev/null) || fail "man hirsute"
  for command in derive render export view simulate render-frames feather-scan; do
    grep -q "hirsute $command" <<<"$page" || fail "man hirsute has no section of $command"
  done
  grep -q -- '--no-hairs' <<<"$page" || fail "man hirsute lacks render's --no-hairs"
  ! grep -q 'build/release' <<<"$page" || fail "man hirsute shows a build path"
else
  command -v help2man >/dev/null && fail "help2man is installed, but no man page was made"
  echo "install test: no help2man, so no man page to check" >&2
fi

# Bash completion, through bash-completion's own set-up as an interactive shell has it.
completions=/usr/share/bash-completion/bash_completion
if [ ! -f "$completions" ]; then
  echo "install test: skipped the completion (bash-completion is not installed)" >&2
  exit 0
fi
touch tree.l tree.v tree.a notes.txt
complete_words() {
  bash -c '
    source "$1"; source "$2"; shift 2
    COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); COMP_LINE="$*"; COMP_POINT=${#COMP_LINE}
    _hirsute hirsute "${COMP_WORDS[-1]}" "${COMP_WORDS[-2]}"
    printf "%s\n" "${COMPREPLY[@]}" | sort | tr "\n" " "' \
    sh "$completions" "$prefix/share/bash-completion/completions/hirsute" "$@"
}
got=$(complete_words hirsute ren)
[ "$got" = "render render-frames " ] || fail "hirsute ren<TAB> gave '$got'"
got=$(complete_words hirsute render --no-h)
[ "$got" = "--no-hairs " ] || fail "hirsute render --no-h<TAB> gave '$got'"
got=$(complete_words hirsute render "")
[ "$got" = "tree.a tree.l tree.v " ] || fail "hirsute render <TAB> gave '$got'"
echo "install test: installed in $prefix; program, modules, man page and completion work"
