#!/usr/bin/env bash
# Writes the columns `detected`, `refusal` and `blocks` of tests/data/corpus/expected.tsv anew from
# a kontur binary: the dialect detected from each program; for programs not expected to read, the
# message they stop with (without the directory); for those that read, their number of blocks. Every
# program is read with the corpus's tool table (tools.tbl), as the test reads it.
# Review the diff before committing it.
# Usage: tests/corpus/record.sh build/bin/kontur
set -euo pipefail
kontur="$(realpath "$1")"
cd "$(dirname "$0")/../data/corpus"
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
{
  IFS= read -r _
  printf 'file\tdialect\texpected\tfeature\tdetected\trefusal\tblocks\n'
  # (fields split at \037, not at tabs: read collapses runs of tabs, which would shift empty fields)
  while IFS=$'\037' read -r file dialect expected feature _ _ _ || [ -n "${file:-}" ]; do
    detected="$("$kontur" check --json "$file" 2>/dev/null | sed -n 's/.*"name": "\([a-z0-9]*\)".*/\1/p' | head -1)" || true
    if [ -z "$detected" ]; then  # the program does not read in the detected dialect: ask the reader's choice
      detected="$("$kontur" check --quiet "$file" 2>&1 >/dev/null | sed -n 's/^kontur: dialect: \([a-z0-9]*\) .*/\1/p' | head -1)" || true
    fi
    refusal="" blocks=""
    if [ "$expected" = "read" ]; then
      blocks="$("$kontur" check --quiet --dialect "$dialect" --tool-table tools.tbl "$file" 2>/dev/null |
                sed -n 's/.*: valid, [0-9]* lines, \([0-9]*\) blocks$/\1/p')" || true
    else
      refusal="$("$kontur" check --quiet --dialect "$dialect" --tool-table tools.tbl "$file" 2>&1 >/dev/null | grep -v '^kontur: dialect:' |
                 grep '^kontur: error: ' | head -1 | sed 's/^kontur: error: //')" || true
    fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$file" "$dialect" "$expected" "$feature" "$detected" "$refusal" \
      "$blocks"
    file=""
  done
} < <(tr '\t' '\037' <expected.tsv) >"$out"
cp "$out" expected.tsv
echo "recorded $(($(wc -l <expected.tsv) - 1)) programs in tests/data/corpus/expected.tsv"
