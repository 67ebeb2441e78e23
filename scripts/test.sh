#!/usr/bin/env sh
# The project's test command (README, CI): a Python virtual environment in .venv with what the
# cross-checks need (requirements-test.txt), then the whole Rust test suite with those
# cross-checks required (AUTOBAL_REQUIRE_PYTHON=1: a missing tool fails the test instead of
# skipping it).
set -eu
cd "$(dirname "$0")/.."
say() { echo "scripts/test.sh: $*" >&2; }
if ! command -v cargo >/dev/null 2>&1; then
    say "cargo not found; install Rust (rust-version in Cargo.toml, or newer) with rustup: https://rustup.rs"
    exit 1
fi
if ! command -v python3 >/dev/null 2>&1; then
    say "python3 not found; install Python >= 3.9 with venv (Debian/Ubuntu: sudo apt-get install python3 python3-venv)"
    exit 1
fi
if [ ! -x .venv/bin/python ]; then
    if ! python3 -m venv .venv >/dev/null 2>&1; then
        rm -rf .venv
        if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
            # Debian/Ubuntu ship venv (ensurepip) separately from python3
            say "installing python3-venv with apt-get"
            apt-get update -qq && apt-get install -y -qq python3-venv
            python3 -m venv .venv
        else
            say "'python3 -m venv' failed: the venv module (ensurepip) is missing; on Debian/Ubuntu install it with: sudo apt-get install python3-venv"
            exit 1
        fi
    fi
fi
if ! .venv/bin/python -m pip install --quiet --disable-pip-version-check -r requirements-test.txt; then
    say "pip could not install requirements-test.txt into .venv (no network to PyPI?); the cross-checks need them"
    exit 1
fi
export AUTOBAL_PYTHON="$PWD/.venv/bin/python"
export AUTOBAL_REQUIRE_PYTHON=1

# ROSS, for the cross-checks of autobal.from_ross and the shaft builder against it, in a venv of
# its own (.venv-ross: ROSS 2.3.0 needs plotly<6, .venv has plotly 7): ROSS and ccp-performance
# without their declared dependencies (requirements-ross.txt), what their import needs
# (requirements-ross-deps.txt). Measured into a fresh venv (docs/guide/your-own-rotor.md). Where it
# installs, its tests are required (AUTOBAL_REQUIRE_ROSS=1); AUTOBAL_SKIP_ROSS=1 leaves it out.
ross=""
if [ "${AUTOBAL_SKIP_ROSS:-}" != 1 ]; then
    if { [ -x .venv-ross/bin/python ] || python3 -m venv .venv-ross >/dev/null 2>&1; } &&
        .venv-ross/bin/python -m pip install --quiet --disable-pip-version-check -r requirements-ross-deps.txt &&
        .venv-ross/bin/python -m pip install --quiet --disable-pip-version-check --no-deps -r requirements-ross.txt &&
        .venv-ross/bin/python -c "import ross" >/dev/null 2>&1; then
        ross=1
    else
        say "ROSS could not be installed into .venv-ross (no network to PyPI?): its cross-checks will be skipped"
    fi
fi

# The report's browser test: Debian's Chromium driven by playwright-core (npm, pinned in
# crates/autobal-cli/tests/browser/package-lock.json; it never downloads a browser of its own).
# Installed here when run as root; otherwise the test says what to install and is skipped,
# unless AUTOBAL_REQUIRE_BROWSER or CI is set.
browser_dir=crates/autobal-cli/tests/browser
chromium="${AUTOBAL_CHROMIUM:-/usr/bin/chromium}"
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    missing=""
    [ -x "$chromium" ] || missing="chromium"
    command -v npm >/dev/null 2>&1 || missing="$missing nodejs npm"
    if [ -n "$missing" ]; then
        apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing >/dev/null
        apt-get clean
    fi
fi
if command -v npm >/dev/null 2>&1; then
    (cd "$browser_dir" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
if [ -x "$chromium" ] && [ -d "$browser_dir/node_modules/playwright-core" ]; then
    export AUTOBAL_REQUIRE_BROWSER=1
else
    echo "scripts/test.sh: the report's browser test will be skipped: it needs Chromium (sudo apt-get install chromium) and Node.js with npm (sudo apt-get install nodejs npm)" >&2
fi
# With ROSS installed, the Rust tests against it (the shaft builder's Timoshenko elements, a second
# example rotor's Campbell diagram) are required too, with ROSS's Python.
if [ -n "$ross" ]; then
    AUTOBAL_ROSS_PYTHON="$PWD/.venv-ross/bin/python" AUTOBAL_REQUIRE_ROSS=1 cargo test --workspace "$@"
else
    cargo test --workspace "$@"
fi

# The Python package: its wheel built by maturin with the workspace's dev profile (reusing the
# build above), installed into .venv (with the `autobal` command), and its tests (pytest) on the installed wheel, including
# results equal to the CLI's JSON (the binary just built) and a sweep on a local Dask cluster.
rm -rf target/wheels
.venv/bin/maturin build --quiet --profile dev -m crates/autobal-py/Cargo.toml -i .venv/bin/python -o target/wheels
.venv/bin/python -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/wheels/autobal-*.whl
AUTOBAL_BIN="$PWD/target/debug/autobal" .venv/bin/python -m pytest -q -p no:cacheprovider crates/autobal-py/tests

# The ROSS cross-checks, with ROSS required, on the same wheel in .venv-ross.
if [ -n "$ross" ]; then
    .venv-ross/bin/python -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/wheels/autobal-*.whl
    AUTOBAL_REQUIRE_ROSS=1 AUTOBAL_BIN="$PWD/target/debug/autobal" .venv-ross/bin/python -m pytest -q -p no:cacheprovider crates/autobal-py/tests/test_linear_rotor_ross.py
fi

# The wheel's `autobal` command (the console script into the same Rust front end) passes the CLI's
# end-to-end tests: one test binary again, with AUTOBAL_BIN pointing at the installed script.
AUTOBAL_BIN="$PWD/.venv/bin/autobal" cargo test -p autobal-cli --test cli

# The README's Python quick start, now that the wheel is installed (the cargo run above skipped it:
# the wheel did not exist yet).
cargo test -p autobal-cli --test readme -- the_readme_python_quick_start_runs_as_printed
