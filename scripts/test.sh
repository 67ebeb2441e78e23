#!/usr/bin/env sh
# The project's test command (README, CI): a Python virtual environment in .venv with what the
# cross-checks need (requirements-test.txt), then the whole Rust test suite with those
# cross-checks required (AUTOBAL_REQUIRE_PYTHON=1: a missing tool fails the test instead of
# skipping it).
set -eu
cd "$(dirname "$0")/.."
if ! command -v cargo >/dev/null 2>&1; then
    echo "scripts/test.sh: cargo not found; install Rust (rust-version in Cargo.toml) with rustup: https://rustup.rs" >&2
    exit 1
fi
if [ ! -x .venv/bin/python ]; then
    if ! python3 -m venv .venv; then
        rm -rf .venv
        if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
            # Debian/Ubuntu ship venv separately from python3
            apt-get update -qq && apt-get install -y -qq python3-venv
            python3 -m venv .venv
        else
            echo "scripts/test.sh: 'python3 -m venv' failed; on Debian/Ubuntu install it with: sudo apt-get install python3-venv" >&2
            exit 1
        fi
    fi
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check -r requirements-test.txt
export AUTOBAL_PYTHON="$PWD/.venv/bin/python"
export AUTOBAL_REQUIRE_PYTHON=1
cargo test --workspace "$@"
