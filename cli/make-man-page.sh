#!/usr/bin/env bash
# Makes the man page hirsute(1) from the program's own help, so that it never says other than
# `hirsute --help` does: help2man for the synopsis and the program's options, and a COMMANDS
# section with each command's help, as `hirsute COMMAND --help` prints it.
#   cli/make-man-page.sh PROGRAM OUT
set -euo pipefail
program=$1
out=$2
include=$(mktemp)
trap 'rm -f "$include"' EXIT

# roff: a backslash is an escape, and a line that starts with . or ' is a request.
roff_text() { sed -e 's/\\/\\e/g' -e "s/^\\([.']\\)/\\\\\\&\\1/"; }

commands=$("$program" --help | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && /^  [a-z]/ { print $1 }')
{
  echo '[DESCRIPTION]'
  echo 'Hirsute derives L-systems written in the language of cpfg, draws them with cpfg'"'"'s turtle,'
  echo 'covers them with plant hairs, feathers and fur, previews them headless or in a window, traces'
  echo 'stills, simulates feather coats and exports them to POV-Ray and OBJ. A model is a .l file'
  echo 'with, optionally, a .v view file and the colour, material, function, contour, surface and'
  echo 'feather files the view file names; every file a model names is read beneath its folder.'
  echo '[COMMANDS]'
  for command in $commands; do
    echo ".SS \"hirsute $command\""
    "$program" "$command" --help | sed -n '1p' | roff_text
    echo '.PP'
    echo '.nf'
    "$program" "$command" --help | sed -n '2,$p' | roff_text
    echo '.fi'
  done
  echo '[EXIT STATUS]'
  echo '0 on success; 2 for bad input (a mistake in the model or on the command line, with a'
  echo 'file:line:col message); 1 for a failure of the system (a file that cannot be written, a'
  echo 'program that failed).'
  echo '[FILES]'
  echo 'The modules loaded when first needed (drawing, tracing, mesh files) lie in'
  echo '\fIPREFIX\fR/lib/hirsute; bash completion in'
  echo '\fIPREFIX\fR/share/bash-completion/completions/hirsute.'
  echo '[SEE ALSO]'
  echo 'The documentation in the docs folder of the source: docs/tutorial.md, docs/cli.md,'
  echo 'docs/language.md.'
} >"$include"

help2man --no-info --no-discard-stderr --section 1 --source "Hirsute" \
  --name "an L-system plant modelling environment that reads cpfg models" \
  --include "$include" --output "$out.tmp" "$program"
mv -f "$out.tmp" "$out"
