//! Running a Python script that uses ROSS (`ross-rotordynamics`) for the cross-checks against it.
//!
//! ROSS is not in requirements-test.txt (about 1.2 GB of dependencies; docs/guide/your-own-rotor.md), so
//! these checks skip without it, and fail instead when `AUTOBAL_REQUIRE_ROSS` is set. The
//! interpreter is `$AUTOBAL_ROSS_PYTHON`, else `$AUTOBAL_PYTHON`, the repository's `.venv`,
//! `.venv-bench` (made by bench/ for the peer comparisons, which has ROSS), or `python3`: the
//! first that imports `ross`.

use std::process::Command;

/// A Python interpreter that imports ROSS, or `None` (the caller skips; panics when
/// `AUTOBAL_REQUIRE_ROSS` is set).
pub fn ross_python() -> Option<String> {
    let root = format!("{}/../..", env!("CARGO_MANIFEST_DIR"));
    let candidates = ["AUTOBAL_ROSS_PYTHON", "AUTOBAL_PYTHON"].iter().filter_map(|k| std::env::var(k).ok()).chain([
        format!("{root}/.venv/bin/python"),
        format!("{root}/.venv-bench/bin/python"),
        "python3".to_string(),
    ]);
    for py in candidates {
        let ok = Command::new(&py).args(["-c", "import ross"]).output().map(|o| o.status.success()).unwrap_or(false);
        if ok {
            return Some(py);
        }
    }
    let msg = "this cross-check needs Python with ROSS (pip install ross-rotordynamics 'plotly<6'): set AUTOBAL_ROSS_PYTHON to such a python";
    assert!(std::env::var_os("AUTOBAL_REQUIRE_ROSS").is_none(), "{msg}");
    eprintln!("skipped: {msg}");
    None
}

/// Run `script` with ROSS's Python and return the last line of its standard output (the
/// script prints its JSON there; ROSS may print notices before it). `None`: skipped.
pub fn run_ross(script: &str) -> Option<String> {
    let py = ross_python()?;
    let out = Command::new(&py).args(["-c", script]).output().expect("run python");
    assert!(out.status.success(), "python failed: {}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).expect("utf-8");
    Some(text.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("").to_string())
}
