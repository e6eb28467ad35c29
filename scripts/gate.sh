#!/usr/bin/env bash
# rockslide as a CI gate in another repository: the steps of the composite action
# (action.yml), runnable anywhere bash and a Rust toolchain are.
#
#   scripts/gate.sh fingerprint   the sources' fingerprint (the install's cache key)
#   scripts/gate.sh install   install rockslide from SOURCE (default: this checkout) into
#                             ROOT/bin (default ~/.cargo/bin), unless the binary there was
#                             built from the same sources (a cached install is reused)
#   scripts/gate.sh check     rockslide check CASES (default: cases) with each EXTERNAL
#                             participant; JUnit XML, the step summary and annotations
#                             (on GitHub Actions); exit 0 pass, 1 gate failed, 2 bad input
#
# Environment (the action's inputs): ROCKSLIDE_CASES (paths, space-separated),
# ROCKSLIDE_EXTERNAL (LABEL=PATH, one a line), ROCKSLIDE_OUT (default reports),
# ROCKSLIDE_JUNIT (default $ROCKSLIDE_OUT/junit.xml), ROCKSLIDE_SOURCE, ROCKSLIDE_ROOT,
# ROCKSLIDE_BIN (a rockslide binary to use instead of ROOT/bin/rockslide).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source_dir="${ROCKSLIDE_SOURCE:-$here}"
root="${ROCKSLIDE_ROOT:-${CARGO_HOME:-$HOME/.cargo}}"
bin="${ROCKSLIDE_BIN:-$root/bin/rockslide}"

# A fingerprint of the sources a build reads (manifests, lock file, Rust sources): the
# cache key of an install, the same for the same sources whether or not they are a git
# checkout (an action's files are not).
fingerprint() {
    (cd "$source_dir" && find Cargo.toml Cargo.lock build.rs src crates -type f \( -name '*.rs' -o -name '*.toml' -o -name '*.lock' -o -name '*.py' \) -print0 \
        | LC_ALL=C sort -z | xargs -0 sha256sum | sha256sum | cut -c1-16)
}

# Whether the binary at $bin was installed by this script from these sources.
installed_is_current() {
    [[ -x "$bin" && -f "$root/rockslide.fingerprint" ]] \
        && [[ "$(cat "$root/rockslide.fingerprint")" == "$(fingerprint)" ]]
}

install() {
    if installed_is_current; then
        echo "rockslide: $("$bin" --version) at $bin, built from these sources (cached)"
    else
        command -v cargo >/dev/null \
            || { echo "rockslide: cargo not found; install Rust (https://rustup.rs) first" >&2; exit 2; }
        local start=$SECONDS
        cargo install --locked --path "$source_dir" --root "$root" --bin rockslide
        fingerprint > "$root/rockslide.fingerprint"
        echo "rockslide: installed $("$bin" --version) at $bin in $((SECONDS - start)) s"
    fi
    if [[ -n "${GITHUB_PATH:-}" ]]; then
        echo "$(dirname "$bin")" >> "$GITHUB_PATH"
    fi
}

check() {
    [[ -x "$bin" ]] || { echo "rockslide: no binary at $bin; run '$0 install' first" >&2; exit 2; }
    local out="${ROCKSLIDE_OUT:-reports}"
    local junit="${ROCKSLIDE_JUNIT:-$out/junit.xml}"
    local args=(check --out "$out" --junit "$junit")
    local external
    while IFS= read -r external; do
        if [[ -n "${external// }" ]]; then
            args+=(--external "$external")
        fi
    done <<< "${ROCKSLIDE_EXTERNAL:-}"
    local cases
    read -r -a cases <<< "${ROCKSLIDE_CASES:-cases}"
    local status=0
    "$bin" "${args[@]}" "${cases[@]}" || status=$?
    if [[ -n "${GITHUB_OUTPUT:-}" ]]; then
        { echo "junit=$junit"; echo "reports=$out"; echo "status=$status"; } >> "$GITHUB_OUTPUT"
    fi
    return "$status"
}

case "${1:-}" in
    fingerprint) fingerprint ;;
    install) install ;;
    check) check ;;
    *) echo "usage: $0 fingerprint|install|check (see the comments at the top)" >&2; exit 2 ;;
esac
