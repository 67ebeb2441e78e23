//! The terminal and file names: how a command's result is printed (the table or its JSON),
//! notes on standard error, and the output paths derived from `--out`. Used by every command
//! module and the front ends; imports nothing of the crate.

use serde_json::Value;

/// How a command's result is printed: the text table, or its JSON (the same JSON as Python's
/// `autobal.run`).
#[derive(Clone, Copy, Debug, clap::ValueEnum, PartialEq, Eq)]
pub enum Format {
    Table,
    Json,
}

/// Prints a command's result on stdout in the chosen format.
pub fn emit(format: Format, json: Value, table: String) -> anyhow::Result<()> {
    match format {
        Format::Json => print(&format!("{}\n", serde_json::to_string_pretty(&json)?)),
        Format::Table => print(&table),
    }
}

/// Write `text` to standard output. A reader that closed the pipe early (`autobal critical |
/// head -1`) is not an error of ours: the error it gives is [`is_broken_pipe`], on which `main`
/// ends quietly.
pub fn print(text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes()).and_then(|_| out.flush())?;
    Ok(())
}

/// Write a line to standard error, ignoring a closed one (warnings must not end a run).
pub fn note(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// Whether the error comes from a closed standard output (broken pipe).
pub fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| c.downcast_ref::<std::io::Error>().is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe))
}

/// The stem of an `--out` path: only one of the command's own extensions (`exts`, e.g. `csv`) is
/// taken off, so a dot inside a name stays (`--out slow0.05` → `slow0.05.csv`, not `slow0.csv`).
pub fn out_stem(out: &std::path::Path, exts: &[&str]) -> std::path::PathBuf {
    match out.extension().and_then(|e| e.to_str()) {
        Some(e) if exts.iter().any(|x| x.eq_ignore_ascii_case(e)) => out.with_extension(""),
        _ => out.to_path_buf(),
    }
}

/// `STEM.ext`: the extension appended to the stem (never replacing a dotted part of its name).
pub fn with_suffix(stem: &std::path::Path, ext: &str) -> std::path::PathBuf {
    let mut s = stem.as_os_str().to_os_string();
    s.push(".");
    s.push(ext);
    s.into()
}

/// A progress bar on standard error when it is a terminal: `control` with the bar as its
/// progress observer (the same flag and budget), and the bar to clear when the work ends.
pub fn progress_bar(control: &autobal::control::Control) -> (autobal::control::Control, Option<indicatif::ProgressBar>) {
    if !std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        return (control.clone(), None);
    }
    let bar = indicatif::ProgressBar::new(0);
    let b = bar.clone();
    let shown = control.clone().with_progress(move |p| {
        b.set_length(p.total);
        b.set_position(p.done);
    });
    (shown, Some(bar))
}
