#!/bin/sh
# Makes the seed corpora of the targets in fuzz/corpus/ (which git ignores), from the
# repository's own files: the programs under tests/cases/ for parse, canonical, lower and
# compensate (and lsp_edits, after its two bytes that choose the reading and the chunk
# size), the CSV files under tests/cases/ and examples/ for readers (one copy per reader,
# its first byte choosing it), and random structured inputs (0xFF first) for lower,
# compensate and readers.
# The third-party corpus is not copied: give its folder to the run as a second corpus, read
# in place (fuzz/README.md). Run from the repository root.
set -eu
for target in parse canonical lsp_edits lower compensate readers; do mkdir -p "fuzz/corpus/$target"; done
find tests/cases -type f \( -name '*.nc' -o -name '*.NC' -o -name '*.min' -o -name '*.MIN' -o -name '*.ssb' -o -name '*.sub' \) |
    while read -r file; do
        name=$(echo "$file" | tr '/' '_')
        for target in parse canonical lower compensate; do cp "$file" "fuzz/corpus/$target/$name"; done
        { printf '\000\020'; head -c 4000 "$file"; } > "fuzz/corpus/lsp_edits/$name"
    done
find tests/cases examples -type f -name '*.csv' | while read -r file; do
    name=$(echo "$file" | tr '/' '_')
    for reader in 0 1 2 3 4; do
        { printf "\\00$reader"; head -c 60000 "$file"; } > "fuzz/corpus/readers/$reader-$name"
    done
done
# Structured inputs: 0xFF, a byte that chooses the machine (or reader), random bytes.
i=0
while [ $i -lt 200 ]; do
    for target in lower compensate readers; do
        { printf '\377'; printf "\\$(printf '%03o' $((i % 256)))"; head -c $((64 + i * 9)) /dev/urandom; } \
            > "fuzz/corpus/$target/structured-$i"
    done
    i=$((i + 1))
done
