#!/bin/sh
# Run every fuzz target in turn for $1 seconds each (default 600), one at a time, keeping
# the corpus in fuzz/corpus/<target>/ and each target's final statistics in
# fuzz/logs/<target>.log. Run from the repository root.
set -u
SECONDS_EACH=${1:-600}
mkdir -p fuzz/logs
for t in ${TARGETS:-mcap_read record case_toml}; do
    mkdir -p "fuzz/corpus/$t"
    cargo +nightly fuzz run "$t" "fuzz/corpus/$t" -- \
        -max_total_time="$SECONDS_EACH" -rss_limit_mb=2048 -malloc_limit_mb=1024 \
        -timeout=10 -max_len=65536 -print_final_stats=1 \
        > "fuzz/logs/$t.log" 2>&1
    echo "$t: exit $?" >> fuzz/logs/summary.txt
done
