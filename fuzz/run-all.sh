#!/bin/sh
# Run every fuzz target in turn for $1 seconds each (default 600), one at a time, keeping
# the corpus in fuzz/corpus/<target>/ and each target's final statistics in
# fuzz/logs/<target>.log. Run from the repository root. FUZZ_FLAGS (default -O: optimised,
# the build `cargo +nightly fuzz build -O` makes) is passed to `cargo fuzz run`; set it to
# -a for debug assertions and overflow checks (a separate, slower sanitizer build).
set -u
SECONDS_EACH=${1:-600}
mkdir -p fuzz/logs
# a station file holds three channels' headers: its seeds are up to 75 KB
max_len() { case $1 in station) echo 131072 ;; *) echo 65536 ;; esac; }
for t in ${TARGETS:-mcap_read record case_toml study_grid external_results calculix_dat station python_references python_case_dict}; do
    mkdir -p "fuzz/corpus/$t"
    # shellcheck disable=SC2086
    cargo +nightly fuzz run ${FUZZ_FLAGS--O} "$t" "fuzz/corpus/$t" -- \
        -max_total_time="$SECONDS_EACH" -rss_limit_mb=2048 -malloc_limit_mb=1024 \
        -timeout=10 -max_len="$(max_len "$t")" -print_final_stats=1 \
        > "fuzz/logs/$t.log" 2>&1
    echo "$t: exit $?" >> fuzz/logs/summary.txt
done
