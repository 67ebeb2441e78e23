//! What the end-to-end test binaries share: the examples' paths, scratch folders and running
//! the binary under a wall-clock limit (a hang fails the test instead of hanging the suite).
//! (Each test binary compiles this module and uses part of it.)
#![allow(dead_code)]

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The path of `examples/NAME` in the repository.
pub fn examples(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// A fresh, empty folder `autobal-PREFIX-NAME-PID` in the temporary folder.
pub fn scratch_in(prefix: &str, name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("autobal-{prefix}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Wait for `child` at most `limit` (killed and failing the test past it).
pub fn wait_for(mut child: std::process::Child, limit: Duration, what: &str) -> std::process::ExitStatus {
    let t0 = Instant::now();
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return s;
        }
        if t0.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("autobal {what} ran longer than {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Run the binary in `dir` with `args` for at most `limit`: `(exit code, stdout, stderr)`.
pub fn run_in(dir: &std::path::Path, limit: Duration, args: &[&str]) -> (i32, String, String) {
    let mut child =
        Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).current_dir(dir).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("binary runs");
    let (mut out, mut err) = (child.stdout.take().unwrap(), child.stderr.take().unwrap());
    let o = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = out.read_to_string(&mut s);
        s
    });
    let e = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    let status = wait_for(child, limit, &args.join(" "));
    (status.code().unwrap_or(-1), o.join().unwrap(), e.join().unwrap())
}

/// Run the binary with `args` in the current folder, for at most 10 minutes (a hang fails the
/// test): `(exit code, stdout, stderr)`.
pub fn autobal(args: &[&str]) -> (i32, String, String) {
    run_in(std::path::Path::new("."), Duration::from_secs(600), args)
}

/// Standard output of a run that must succeed (exit 0).
pub fn text(args: &[&str]) -> String {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

/// Standard output of a run that must succeed, parsed as JSON.
pub fn json(args: &[&str]) -> serde_json::Value {
    let out = text(args);
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}\n{out}"))
}
