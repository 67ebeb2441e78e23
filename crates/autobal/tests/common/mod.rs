//! Helpers shared by the integration tests.

/// SplitMix64: a tiny seeded generator, so failures reproduce.
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
}

/// A Python interpreter that can import `modules`: `$AUTOBAL_PYTHON`, the repository's `.venv`
/// (made by scripts/test.sh), or `python3`. Without one the cross-check is skipped with a
/// message, unless `AUTOBAL_REQUIRE_PYTHON` is set (scripts/test.sh sets it), where it fails.
#[allow(dead_code)]
pub fn python_with(modules: &[&str]) -> Option<String> {
    let venv = format!("{}/../../.venv/bin/python", env!("CARGO_MANIFEST_DIR"));
    let candidates = std::env::var("AUTOBAL_PYTHON").into_iter().chain([venv, "python3".to_string()]);
    let import = format!("import {}", modules.join(", "));
    for py in candidates {
        if std::process::Command::new(&py).args(["-c", &import]).output().is_ok_and(|o| o.status.success()) {
            return Some(py);
        }
    }
    let msg = format!(
        "this cross-check needs Python with {}: run scripts/test.sh (it creates .venv with them), or set AUTOBAL_PYTHON to a python that has them",
        modules.join(", ")
    );
    assert!(std::env::var_os("AUTOBAL_REQUIRE_PYTHON").is_none(), "{msg}");
    eprintln!("skipped: {msg}");
    None
}
