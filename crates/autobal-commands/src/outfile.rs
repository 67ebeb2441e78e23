//! The one way every command opens its output files.
//!
//! 1. **Resolve and check before any work** ([`Outputs`]): `--out DIR/` or an existing folder
//!    becomes the command's default name inside it (`DIR/simulation.csv`, never the hidden,
//!    nameless `DIR/.csv`); a missing parent folder is created; the folder must be writable
//!    (probed by creating and removing a file in it); an existing path must be a regular file
//!    (never a folder, a device such as `/dev/null`, a FIFO); and no output may be the same file
//!    as an input (the config, a shard being merged: compared by file identity, device and
//!    inode, so links and `./` spellings are caught). A bad `--out` fails at once, not after
//!    the grid was computed.
//! 2. **Write to a temporary name, rename on success** ([`Staged`], [`write_atomic`]): the bytes
//!    go to `NAME.PID.part` in the same folder, which is renamed onto `NAME` (atomic on one file
//!    system) only when the command commits it. An error, or a value dropped without commit,
//!    removes the temporary file: a truncated, empty or footer-less file never appears under a
//!    final name. A streaming output stopped by Ctrl-C is committed by the command after its
//!    last complete row (and Parquet footer), and the command says so on standard error.

use anyhow::{anyhow, bail, Context, Result};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The file names of an `--out` stem: `STEM.ext` for each `exts`.
pub fn stem_files(stem: &Path, exts: &[&str]) -> Vec<PathBuf> {
    exts.iter().map(|e| crate::term::with_suffix(stem, e)).collect()
}

/// Whether `p` was written as a folder: it ends with a path separator (`runs/`), is `.`/`..`,
/// or names an existing folder.
pub fn names_folder(p: &Path) -> bool {
    let s = p.as_os_str().to_string_lossy();
    s.ends_with('/') || s.ends_with(std::path::MAIN_SEPARATOR) || p.file_name().is_none() || p.is_dir()
}

/// `--out` as given, or `DIR/default` when it names a folder ([`names_folder`]).
pub fn resolve(out: &Path, default: &str) -> PathBuf {
    if names_folder(out) {
        out.join(default)
    } else {
        out.to_path_buf()
    }
}

/// The temporary name beside `path`: `NAME.PID.part`.
fn temp_for(path: &Path) -> PathBuf {
    let mut name = path.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(format!(".{}.part", std::process::id()));
    path.with_file_name(name)
}

/// The folder a file goes into (`.` for a bare name).
fn parent(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Whether `a` and `b` are the same file: same device and inode when both exist (links,
/// `./x`, `../d/x` all compare equal), else the same canonical folder and name.
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            return ma.dev() == mb.dev() && ma.ino() == mb.ino();
        }
    }
    let canon = |p: &Path| -> Option<PathBuf> {
        if let Ok(c) = p.canonicalize() {
            return Some(c);
        }
        Some(parent(p).canonicalize().ok()?.join(p.file_name()?))
    };
    match (canon(a), canon(b)) {
        (Some(x), Some(y)) => x == y,
        _ => false,
    }
}

/// The inputs and outputs of one run, checked together before any work starts.
#[derive(Default)]
pub struct Outputs {
    /// `(option, path)` of every file the run reads.
    inputs: Vec<(String, PathBuf)>,
    /// `(option, path)` of every file the run will write.
    outputs: Vec<(String, PathBuf)>,
}

impl Outputs {
    /// No inputs or outputs yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// A file the run reads (`--config x.toml`, a shard): no output may be this file.
    pub fn input(&mut self, option: &str, path: &Path) -> &mut Self {
        self.inputs.push((option.to_string(), path.to_path_buf()));
        self
    }

    /// The `--config` file, when one is given (the embedded default is no file).
    pub fn inputs(&mut self, config: Option<&Path>) -> &mut Self {
        if let Some(c) = config {
            self.input("--config", c);
        }
        self
    }

    /// A file the run will write, named by `option` in errors.
    pub fn output(&mut self, option: &str, path: &Path) -> &mut Self {
        self.outputs.push((option.to_string(), path.to_path_buf()));
        self
    }

    /// Check every output: its folder exists (created if missing) and is writable, the path is
    /// not a folder nor anything but a regular file, and it is not one of the inputs. The first
    /// failure is one line naming the option.
    pub fn check(&self) -> Result<()> {
        let mut probed: Vec<PathBuf> = vec![];
        for (opt, p) in &self.outputs {
            if p.file_name().is_none() {
                bail!("{opt}: {} names no file", p.display());
            }
            match std::fs::metadata(p) {
                Ok(m) if m.is_dir() => bail!("{opt}: {} is a folder, not a file", p.display()),
                Ok(m) if !m.is_file() => bail!("{opt}: {} exists and is not a regular file (a device or pipe); give a file name", p.display()),
                _ => {}
            }
            for (iopt, ip) in &self.inputs {
                if same_file(p, ip) {
                    bail!("{opt}: {} is the input {iopt} {}; refusing to overwrite an input, give another name", p.display(), ip.display());
                }
            }
            for (oopt, op) in self.outputs.iter().take_while(|(_, q)| !std::ptr::eq(q, p)) {
                if same_file(p, op) {
                    bail!("{opt}: {} is also the output of {oopt}", p.display());
                }
            }
            let dir = parent(p);
            if probed.contains(&dir) {
                continue;
            }
            if !dir.exists() {
                std::fs::create_dir_all(&dir).map_err(|e| anyhow!("{opt}: cannot create the folder {}: {e}", dir.display()))?;
            } else if !dir.is_dir() {
                bail!("{opt}: {} is not a folder", dir.display());
            }
            let probe = temp_for(&dir.join(".autobal-probe"));
            File::options().write(true).create_new(true).open(&probe).map_err(|e| anyhow!("{opt}: cannot write in the folder {}: {e}", dir.display()))?;
            let _ = std::fs::remove_file(&probe);
            probed.push(dir);
        }
        Ok(())
    }
}

/// A file being written under a temporary name (`temp_for`); [`Staged::commit`] renames it
/// into place, dropping it uncommitted removes it.
pub struct Staged {
    option: String,
    path: PathBuf,
    tmp: PathBuf,
    file: Option<BufWriter<File>>,
}

impl Staged {
    /// Create the temporary file for `path` (the option names it in errors).
    pub fn create(option: &str, path: &Path) -> Result<Self> {
        let tmp = temp_for(path);
        let f = File::options().write(true).create(true).truncate(true).open(&tmp).with_context(|| format!("{option}: cannot create {}", tmp.display()))?;
        Ok(Staged { option: option.to_string(), path: path.to_path_buf(), tmp, file: Some(BufWriter::with_capacity(1 << 16, f)) })
    }

    /// The temporary name the bytes go to until the commit.
    #[cfg(test)]
    pub fn temp_path(&self) -> &Path {
        &self.tmp
    }

    /// Flush and rename onto the final name; returns it.
    pub fn commit(mut self) -> Result<PathBuf> {
        let w = self.file.take().ok_or_else(|| anyhow!("{}: already committed", self.path.display()))?;
        let f = w.into_inner().map_err(|e| anyhow!("{}: cannot write {}: {}", self.option, self.path.display(), e.error()))?;
        drop(f);
        std::fs::rename(&self.tmp, &self.path).with_context(|| format!("{}: cannot rename {} to {}", self.option, self.tmp.display(), self.path.display()))?;
        Ok(self.path.clone())
    }
}

impl Write for Staged {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file.as_mut().ok_or_else(|| std::io::Error::other("committed"))?.write(buf)
    }
    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        self.file.as_mut().ok_or_else(|| std::io::Error::other("committed"))?.write_all(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file.as_mut().map_or(Ok(()), |f| f.flush())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if self.file.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Write `bytes` to `path` through a temporary file and a rename: the file appears whole or
/// not at all.
pub fn write_atomic(option: &str, path: &Path, bytes: impl AsRef<[u8]>) -> Result<()> {
    let mut s = Staged::create(option, path)?;
    s.write_all(bytes.as_ref()).with_context(|| format!("{option}: cannot write {}", path.display()))?;
    s.commit()?;
    Ok(())
}

/// A temporary name for a file whose writer owns the handle (Parquet): removed on drop unless
/// [`TempName::rename`]d into place.
pub struct TempName {
    option: String,
    path: PathBuf,
    tmp: PathBuf,
    done: bool,
}

impl TempName {
    /// Create the temporary file for `path`; returns it and its open handle.
    pub fn create(option: &str, path: &Path) -> Result<(Self, File)> {
        let tmp = temp_for(path);
        let f = File::create(&tmp).with_context(|| format!("{option}: cannot create {}", tmp.display()))?;
        Ok((TempName { option: option.to_string(), path: path.to_path_buf(), tmp, done: false }, f))
    }

    /// Rename the (closed, complete) temporary file onto the final name.
    pub fn rename(mut self) -> Result<PathBuf> {
        std::fs::rename(&self.tmp, &self.path).with_context(|| format!("{}: cannot rename {} to {}", self.option, self.tmp.display(), self.path.display()))?;
        self.done = true;
        Ok(self.path.clone())
    }
}

impl Drop for TempName {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("autobal-outfile-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn dropped_uncommitted_leaves_nothing_and_commit_renames() {
        let d = scratch("stage");
        let p = d.join("a.csv");
        {
            let mut s = Staged::create("--out", &p).unwrap();
            writeln!(s, "x,y").unwrap();
            assert!(s.temp_path().exists());
        }
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0, "an uncommitted file left something");
        let mut s = Staged::create("--out", &p).unwrap();
        writeln!(s, "x,y").unwrap();
        s.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "x,y\n");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn outputs_equal_to_inputs_folders_and_devices_are_refused() {
        let d = scratch("check");
        let cfg = d.join("c.toml");
        std::fs::write(&cfg, "x").unwrap();
        // the same file spelled another way
        let other = d.join(".").join("c.toml");
        let e = Outputs::new().input("--config", &cfg).output("--out", &other).check().unwrap_err().to_string();
        assert!(e.starts_with("--out: ") && e.contains("--config"), "{e}");
        let e = Outputs::new().output("--out", &d).check().unwrap_err().to_string();
        assert!(e.contains("is a folder"), "{e}");
        #[cfg(unix)]
        {
            let e = Outputs::new().output("--out", Path::new("/dev/null")).check().unwrap_err().to_string();
            assert!(e.contains("not a regular file"), "{e}");
        }
        // a missing parent is created, a fresh name accepted
        Outputs::new().input("--config", &cfg).output("--out", &d.join("sub/x.csv")).check().unwrap();
        assert!(d.join("sub").is_dir());
        assert_eq!(resolve(Path::new("runs/"), "simulation.csv"), PathBuf::from("runs/simulation.csv"));
        assert_eq!(resolve(&d, "s.csv"), d.join("s.csv"));
        assert_eq!(resolve(Path::new("x"), "s.csv"), PathBuf::from("x"));
        std::fs::remove_dir_all(&d).unwrap();
    }
}
