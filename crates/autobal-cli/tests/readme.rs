//! The README stays true (issue 21 §7): its commands are run as printed, its links resolve.
//!
//! - The first ```` ```sh ```` block is the two set-up commands, exactly
//!   (`cargo run --release -p autobal-cli -- report` and `scripts/test.sh`).
//! - Every line of the README's ```` ```sh ```` blocks that starts with `autobal` is run by `sh -c`
//!   with the binary under test first on `PATH`, in a fresh folder holding a copy of
//!   `examples/` (what a user has after cloning), and must exit with status 0. The set-up line
//!   `cargo run --release -p autobal-cli -- ARGS` is run as `autobal ARGS` (the same binary,
//!   built by this test's profile); `scripts/test.sh` (the test suite itself, run by CI) and
//!   `pip install` (the wheel, tested by the Python package's own suite) are not run. Any other
//!   line fails the test, so a new kind of command cannot slip in untested.
//! - One rule keeps it fast: `autobal report` runs with `--quick` added (the same sections and
//!   figures, paper 004's passages ten times shorter): the full report takes minutes of CPU in
//!   the dev profile. Nothing else is changed; the quick start's other commands take seconds.
//! - The Python quick start (the ```` ```python ```` blocks before the `## Python` section) runs as
//!   a doctest with `$AUTOBAL_PYTHON` (else the repository's `.venv`) only when that Python can
//!   `import autobal`; otherwise it is skipped with a message, also under
//!   `AUTOBAL_REQUIRE_PYTHON`, because `scripts/test.sh` builds and installs the wheel after
//!   `cargo test`. (With a wheel left from an earlier build this checks the README against that
//!   build.) The longer session under `## Python` is run by the Python package's tests
//!   (`test_the_readme_session_runs_as_printed`), on the wheel just built.
//! - Every relative link and image of the README, the top-level pages and every page of docs/
//!   names a file of the repository, and a link to a heading (`FILE.md#anchor`) names one of its
//!   headings.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn readme() -> String {
    std::fs::read_to_string(root().join("README.md")).expect("README.md readable")
}

/// The README's fenced blocks as `(language, body, before_python_section)`, in order;
/// `before_python_section`: the block comes before the `## Python` heading.
fn blocks(text: &str) -> Vec<(String, String, bool)> {
    let mut out = Vec::new();
    let mut open: Option<(String, String)> = None;
    let mut before = true;
    for line in text.lines() {
        match &mut open {
            None if line.starts_with("```") => open = Some((line.trim_start_matches('`').trim().to_string(), String::new())),
            None => {
                if line.trim_end() == "## Python" {
                    before = false;
                }
            }
            Some(_) if line.trim_end() == "```" => {
                let (lang, body) = open.take().expect("open block");
                out.push((lang, body, before));
            }
            Some((_, body)) => {
                body.push_str(line);
                body.push('\n');
            }
        }
    }
    assert!(open.is_none(), "README.md: a code block is not closed");
    out
}

/// `line` without its shell comment: from the first `#` that begins a word outside quotes.
fn strip_comment(line: &str) -> &str {
    let (mut single, mut double, mut prev_space) = (false, false, true);
    for (i, c) in line.char_indices() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            '#' if !single && !double && prev_space => return line[..i].trim_end(),
            _ => {}
        }
        prev_space = c.is_whitespace();
    }
    line.trim_end()
}

/// A fresh folder named `name` under the system's temporary folder, with a copy of `examples/`.
fn workdir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("autobal-readme-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("examples")).expect("temporary folder");
    for e in std::fs::read_dir(root().join("examples")).expect("examples/") {
        let p = e.expect("examples/ entry").path();
        if p.is_file() {
            std::fs::copy(&p, dir.join("examples").join(p.file_name().expect("file name"))).expect("copy an example");
        }
    }
    dir
}

/// The command this test runs for a README line, or `None` for a set-up line it leaves to others.
fn command_for(line: &str) -> Option<String> {
    let cmd = strip_comment(line);
    let cmd = match cmd.strip_prefix("cargo run --release -p autobal-cli -- ") {
        Some(args) => format!("autobal {args}"),
        None if cmd.starts_with("autobal ") || cmd == "autobal" => cmd.to_string(),
        None if cmd == "scripts/test.sh" || cmd.starts_with("pip install ") => return None,
        None => {
            panic!("README.md: `{line}` is neither an autobal command nor a set-up line this test knows; run it here or list it in command_for with the reason")
        }
    };
    // the report's one rule (see the crate docs above)
    let report = cmd.split_whitespace().nth(1) == Some("report");
    Some(if report && !cmd.split_whitespace().any(|w| w == "--quick") { format!("{cmd} --quick") } else { cmd })
}

#[test]
fn the_readme_commands_run_as_printed() {
    let dir = workdir("sh");
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_autobal"));
    let path = format!("{}:{}", bin.parent().expect("binary's folder").display(), std::env::var("PATH").unwrap_or_default());
    let all = blocks(&readme());
    // the two set-up commands come first, as they are (users and the closing checks type them)
    let first = all.iter().find(|b| b.0 == "sh").expect("README.md: no sh block");
    let setup: Vec<&str> = first.1.lines().map(strip_comment).filter(|l| !l.is_empty()).collect();
    assert_eq!(setup, ["cargo run --release -p autobal-cli -- report", "scripts/test.sh"], "README.md: the first sh block must be the two set-up commands");
    let mut ran = Vec::new();
    for (lang, body, _) in all {
        if lang != "sh" {
            continue;
        }
        for line in body.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')) {
            let Some(cmd) = command_for(line) else { continue };
            let out = Command::new("sh").arg("-c").arg(&cmd).current_dir(&dir).env("PATH", &path).output().expect("sh runs");
            assert!(
                out.status.success(),
                "README.md: `{cmd}` exited with {:?}\nstdout:\n{}\nstderr:\n{}",
                out.status.code(),
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
            ran.push(cmd);
        }
    }
    // the set-up block's report and the quick start's five commands at least: a README whose
    // blocks this test no longer finds must not pass by running nothing
    assert!(ran.len() >= 6, "README.md: only {} commands found: {ran:?}", ran.len());
    // what the quick start says it writes
    for f in ["washer_stability.svg", "washer_campbell.svg", "washer_runup.csv", "washer-report/index.html"] {
        assert!(dir.join(f).is_file(), "README.md: the quick start did not write {f}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_readme_python_quick_start_runs_as_printed() {
    let quick: String =
        blocks(&readme()).into_iter().filter(|(lang, body, before)| lang == "python" && *before && body.contains(">>> ")).map(|b| b.1).collect();
    assert!(quick.matches(">>> ").count() >= 3, "README.md: no Python quick start (a ```python block with >>> lines before ## Python)");
    let venv = root().join(".venv/bin/python").display().to_string();
    let python = std::env::var("AUTOBAL_PYTHON")
        .into_iter()
        .chain([venv])
        .find(|py| Command::new(py).args(["-c", "import autobal"]).output().is_ok_and(|o| o.status.success()));
    let Some(python) = python else {
        eprintln!(
            "skipped: the README's Python quick start needs the autobal wheel installed in $AUTOBAL_PYTHON or .venv \
             (scripts/test.sh installs it after cargo test; the pytest suite runs the README's Python session)"
        );
        return;
    };
    let dir = workdir("py");
    std::fs::write(dir.join("quickstart.txt"), &quick).expect("write the quick start");
    let out = Command::new(&python)
        .args(["-m", "doctest", "-o", "ELLIPSIS", "-o", "NORMALIZE_WHITESPACE", "quickstart.txt"])
        .current_dir(&dir)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "README.md's Python quick start failed ({python}):\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Targets being written on other branches of this round, allowed to be missing until they are
/// merged: once a target exists the entry is harmless, and should then be removed.
const PENDING: &[&str] = &[];

/// The markdown files whose links are checked: the README, the top-level pages and every page of
/// docs/ (guide/, reference/, notes/ and the index).
fn markdown_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = ["README.md", "ARCHITECTURE.md", "CONTRIBUTING.md", "CHANGELOG.md"].iter().map(|f| root().join(f)).collect();
    let mut dirs = vec![root().join("docs")];
    while let Some(d) = dirs.pop() {
        for e in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let p = e.expect("a directory entry").path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "md") {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}

/// A markdown text without its fenced code blocks (they hold no links, and `](` can occur in
/// code).
fn prose(md: &str) -> String {
    let mut text = String::new();
    let mut code = false;
    for line in md.lines() {
        if line.trim_start().starts_with("```") {
            code = !code;
        } else if !code {
            text.push_str(line);
            text.push('\n');
        }
    }
    text
}

/// GitHub's anchors of a markdown file's headings: lower case, letters, digits, `-` and `_`
/// kept, spaces to `-`, everything else dropped; a repeated anchor gets `-1`, `-2`, ...
fn anchors(md: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for line in prose(md).lines() {
        let Some(h) = line.strip_prefix('#') else { continue };
        let h = h.trim_start_matches('#');
        if !h.starts_with(' ') {
            continue;
        }
        let slug: String = h
            .trim()
            .to_lowercase()
            .chars()
            .filter_map(|c| {
                if c == ' ' {
                    Some('-')
                } else if c.is_alphanumeric() || c == '-' || c == '_' {
                    Some(c)
                } else {
                    None
                }
            })
            .collect();
        let n = out.iter().filter(|a| **a == slug || a.strip_prefix(&slug).is_some_and(|r| r.starts_with('-') && r[1..].parse::<u32>().is_ok())).count();
        out.push(if n == 0 { slug } else { format!("{slug}-{n}") });
    }
    out
}

#[test]
fn the_readme_links_resolve() {
    // every page, each link relative to its file's folder; a link with an anchor into a
    // markdown file must name one of its headings
    let files = markdown_files();
    assert!(files.len() >= 20, "only {} markdown files found", files.len());
    for path in files {
        let name = path.strip_prefix(root()).map(|p| p.display().to_string()).unwrap_or_default();
        let md = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let folder = path.parent().expect("a file's folder");
        let text = prose(&md);
        let mut targets = Vec::new();
        for (i, _) in text.match_indices("](") {
            let rest = &text[i + 2..];
            let Some(end) = rest.find(')') else { continue };
            targets.push(rest[..end].to_string());
        }
        if name == "README.md" || name == "docs/README.md" {
            assert!(targets.len() >= 10, "{name}: only {} links found", targets.len());
        }
        for t in targets {
            if t.starts_with("http://") || t.starts_with("https://") || t.starts_with("mailto:") || t.contains(' ') || t.is_empty() {
                continue;
            }
            let (file, anchor) = t.split_once('#').unwrap_or((&t, ""));
            let target = if file.is_empty() { path.clone() } else { folder.join(file) };
            if !target.exists() {
                let from_root = target.strip_prefix(root()).map(|p| p.display().to_string()).unwrap_or_default();
                let pending = PENDING.iter().any(|p| root().join(p) == target || from_root == *p);
                assert!(pending, "{name} links to {t}, which is not in the repository");
                eprintln!("note: {name} links to {t}, written on another branch (PENDING)");
                continue;
            }
            if !anchor.is_empty() && target.extension().is_some_and(|x| x == "md") {
                let heads = anchors(&std::fs::read_to_string(&target).expect("a linked markdown file"));
                assert!(heads.iter().any(|h| h == anchor), "{name} links to {t}: no heading with that anchor in {}", target.display());
            }
        }
    }
}

#[test]
fn anchors_are_githubs() {
    let md = "# Title\n## The general route: every rotor (`autobal::analysis`)\n## Repeat\n## Repeat\n```\n# not a heading\n```\n";
    assert_eq!(anchors(md), ["title", "the-general-route-every-rotor-autobalanalysis", "repeat", "repeat-1"]);
}

#[test]
fn comments_are_stripped_outside_quotes_only() {
    assert_eq!(strip_comment("autobal critical   # table"), "autobal critical");
    assert_eq!(strip_comment("autobal simulate --set 'drive.x=[1, 2]' # c"), "autobal simulate --set 'drive.x=[1, 2]'");
    assert_eq!(strip_comment("autobal x --set 'a=#b'"), "autobal x --set 'a=#b'");
    assert_eq!(strip_comment("autobal map --x 'drive.psi0[1]=0:3:4'"), "autobal map --x 'drive.psi0[1]=0:3:4'");
    assert_eq!(command_for("cargo run --release -p autobal-cli -- report      # the default"), Some("autobal report --quick".to_string()));
    assert_eq!(command_for("autobal report --quick --out r"), Some("autobal report --quick --out r".to_string()));
    assert_eq!(command_for("scripts/test.sh    # all"), None);
}
