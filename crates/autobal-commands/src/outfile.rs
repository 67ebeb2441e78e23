//! The one way every command opens its output files.
//!
//! 1. **Resolve and check before any work** ([`Outputs`]): `--out DIR/` or an existing folder
//!    becomes the command's default name inside it (`DIR/simulation.csv`, never the hidden,
//!    nameless `DIR/.csv`); the folder must be writable (probed by creating and removing a file
//!    in it, a missing folder created for the probe and removed with it, or by creating the
//!    staged file of the first output, [`Outputs::check_and_stage_first`]: a check writes
//!    nothing, and a missing folder is made when its first file is written, removed again if
//!    that file is dropped unfinished); an existing path must be a regular file (never a folder,
//!    a device such as `/dev/null`, a FIFO); no output may be named after a device, FIFO or
//!    socket (`--out /dev/full` as a stem would write `/dev/full.csv` beside it) nor go into
//!    the kernel's folders `/dev`, `/proc`, `/sys` (`/dev/shm` excepted); and no output may be
//!    the same file as an input (the config, a shard being merged: compared by file identity, device and
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

/// A `--svg` name whose extension is not `.svg` (any case) is refused: the figures are SVG
/// text only (`stability --svg st.png` wrote SVG under a .png name, silently). A name without
/// an extension is taken as it is; `prefix`: the name is the prefix of the figures'
/// names (`campbell`: `PREFIX.svg`, `PREFIX_rotating.svg`), which may still end in `.svg`.
///
/// ```
/// use autobal_commands::outfile::check_svg_name;
/// use std::path::Path;
/// assert!(check_svg_name("--svg", Path::new("m.svg"), false).is_ok());
/// assert!(check_svg_name("--svg", Path::new("runs/m"), false).is_ok());
/// let e = check_svg_name("--svg", Path::new("st.png"), false).unwrap_err().to_string();
/// assert!(e.starts_with("--svg: st.png: the figure is written as SVG only"), "{e}");
/// ```
pub fn check_svg_name(flag: &str, path: &Path, prefix: bool) -> Result<()> {
    let Some(ext) = path.extension().map(|e| e.to_string_lossy().to_string()) else { return Ok(()) };
    if ext.eq_ignore_ascii_case("svg") {
        return Ok(());
    }
    let name = path.display();
    if prefix {
        bail!("{flag}: {name}: the figures are written as SVG only (PREFIX.svg), and a prefix ending in .{ext} names another format: give the prefix without .{ext}");
    }
    bail!("{flag}: {name}: the figure is written as SVG only, and a .{ext} name would hold SVG text: give a name ending in .svg");
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

/// The longest file name (bytes) the usual file systems take (Linux's `NAME_MAX`: ext4, XFS,
/// Btrfs, tmpfs; APFS and NTFS count 255 characters). A smaller limit is still caught where the
/// file is created.
const NAME_MAX: usize = 255;

/// The folder a file goes into (`.` for a bare name).
fn parent(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Whether `dir` names a folder that does not exist and then `..` (`q/..` with `q` missing):
/// creating it only to step out of it again would leave a folder nobody asked for. A leading
/// `..` (`../runs`) steps out of the working folder, which exists.
fn steps_out_of_missing(dir: &Path) -> bool {
    let mut prefix = PathBuf::new();
    for c in dir.components() {
        if c == std::path::Component::ParentDir && !prefix.as_os_str().is_empty() && !prefix.is_dir() {
            return true;
        }
        prefix.push(c);
    }
    false
}

/// The canonical form of a path that does not exist (yet): its nearest existing folder
/// canonicalised, then the rest of its parts (`.` dropped, `..` stepping back), so that two
/// spellings of one file in folders not created yet compare equal.
fn canon_missing(p: &Path) -> Option<PathBuf> {
    let mut rest = vec![];
    let mut base = p;
    let root = loop {
        let probe = if base.as_os_str().is_empty() { Path::new(".") } else { base };
        if let Ok(c) = probe.canonicalize() {
            break c;
        }
        rest.push(base.components().next_back()?);
        base = base.parent()?;
    };
    let mut out = root;
    for c in rest.into_iter().rev() {
        match c {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir => {
                out.pop();
            }
            c => out.push(c),
        }
    }
    Some(out)
}

/// Create `dir` and the folders above it that are missing; returns those created, deepest
/// first (for [`remove_folders`]). On an error, none is left.
fn make_folders(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut missing = vec![];
    let mut d = dir;
    while !d.as_os_str().is_empty() && std::fs::symlink_metadata(d).is_err() {
        missing.push(d.to_path_buf());
        match d.parent() {
            Some(p) => d = p,
            None => break,
        }
    }
    if missing.is_empty() {
        return Ok(missing);
    }
    if let Err(e) = std::fs::create_dir_all(dir) {
        remove_folders(&missing);
        return Err(e);
    }
    Ok(missing)
}

/// Remove the folders [`make_folders`] created (those still empty), deepest first.
fn remove_folders(made: &[PathBuf]) {
    for d in made {
        let _ = std::fs::remove_dir(d);
    }
}

/// What an existing path is when it is neither a regular file nor a folder: `a device`, `a
/// FIFO`, `a socket` (`None` for a file or a folder).
fn special_kind(m: &std::fs::Metadata) -> Option<&'static str> {
    if m.is_file() || m.is_dir() {
        return None;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = m.file_type();
        if t.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    Some("a device")
}

/// The kernel's folders where no output belongs (`/dev`, `/proc`, `/sys`: devices and kernel
/// state; as root a file can be created in `/dev`, where it would sit among the devices and
/// vanish at the next boot). `/dev/shm`, the shared-memory file system meant for files, is
/// allowed. Returns the system folder `dir` is in (looked up through its nearest existing
/// folder, canonicalised, so `/tmp/../dev` and links into `/dev` are caught; a relative `dir`
/// is looked up from the current folder, so `zz/m` run in `/dev` is caught though `zz` is
/// missing).
fn system_folder(dir: &Path) -> Option<&'static str> {
    if !cfg!(unix) {
        return None;
    }
    let abs;
    let mut d = if dir.is_relative() {
        abs = std::env::current_dir().ok()?.join(dir);
        abs.as_path()
    } else {
        dir
    };
    let canon = loop {
        if let Ok(c) = d.canonicalize() {
            break c;
        }
        d = match d.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => return None,
        };
    };
    if canon.starts_with("/dev/shm") {
        return None;
    }
    ["/dev", "/proc", "/sys"].into_iter().find(|s| canon.starts_with(s))
}

/// The first name with a control character among those a run would create for `p`: its file
/// name, and the folders on its way that do not exist yet (made with the first file); an existing
/// folder is the user's.
fn control_name(p: &Path) -> Option<&std::ffi::OsStr> {
    let bad = |n: &std::ffi::OsStr| n.to_string_lossy().chars().any(char::is_control);
    let mut q = p;
    loop {
        match q.file_name() {
            Some(n) if bad(n) => return Some(n),
            _ => {}
        }
        q = q.parent().filter(|d| !d.as_os_str().is_empty() && std::fs::symlink_metadata(d).is_err())?;
    }
}

/// Whether `a` and `b` are the same file: same device and inode when both exist (links,
/// `./x`, `../d/x` all compare equal), else the same canonical folder and name.
pub fn same_file(a: &Path, b: &Path) -> bool {
    Ident::of(a, std::fs::metadata(a).ok().as_ref()).same(&Ident::of(b, std::fs::metadata(b).ok().as_ref()))
}

/// What [`same_file`] compares of one path, each part looked up once: its device and inode
/// (where it exists), and, only when asked, its canonical folder and name. `Outputs::check`
/// compares every output with every input and every other output: with the parts kept, that
/// is one `stat` a path (and one canonicalisation of a missing one) instead of two a pair.
struct Ident<'a> {
    path: &'a Path,
    node: Option<(u64, u64)>,
    /// Kept once found: a lookup that failed (a folder not created yet) is tried again.
    canon: std::cell::OnceCell<PathBuf>,
}

impl<'a> Ident<'a> {
    /// `path`, with its metadata when it exists.
    fn of(path: &'a Path, meta: Option<&std::fs::Metadata>) -> Self {
        #[cfg(unix)]
        let node = {
            use std::os::unix::fs::MetadataExt;
            meta.map(|m| (m.dev(), m.ino()))
        };
        #[cfg(not(unix))]
        let node = {
            let _ = meta;
            None
        };
        Ident { path, node, canon: std::cell::OnceCell::new() }
    }

    /// The canonical path, or the canonical folder and the name of a missing file.
    fn canon(&self) -> Option<&PathBuf> {
        if let Some(c) = self.canon.get() {
            return Some(c);
        }
        let p = self.path;
        let c = match p.canonicalize() {
            Ok(c) => c,
            Err(_) => canon_missing(p)?,
        };
        Some(self.canon.get_or_init(|| c))
    }

    /// [`same_file`] of the two paths.
    fn same(&self, other: &Ident) -> bool {
        if let (Some(a), Some(b)) = (self.node, other.node) {
            return a == b;
        }
        match (self.canon(), other.canon()) {
            (Some(x), Some(y)) => x == y,
            _ => false,
        }
    }
}

/// The inputs and outputs of one run, checked together before any work starts.
#[derive(Default)]
pub struct Outputs {
    /// `(option, path)` of every file the run reads.
    inputs: Vec<(String, PathBuf)>,
    /// `(option, path)` of every file the run will write.
    outputs: Vec<(String, PathBuf)>,
    /// `(option, stem)` of each `--out` the run adds extensions to ([`Outputs::stem`]).
    stems: Vec<(String, PathBuf)>,
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

    /// [`Outputs::config_inputs`] of a command's config as given (`--config` and `--set`, or
    /// Python's tables): the files the config names *after* its overrides are inputs (hunt 27:
    /// `--set 'linear_rotor.kst="kst.svg"' --svg kst.svg` overwrote the matrix file, which only
    /// the file on disk was searched for). A config that cannot be read or set here adds only
    /// itself (the command reports that error where it reads the config).
    pub fn source_inputs(&mut self, config: &crate::command::ConfigSource) -> &mut Self {
        use crate::command::ConfigSource;
        match config {
            ConfigSource::File { path, sets } if !sets.is_empty() => match config.read_any() {
                Ok((root, _)) => self.config_inputs(path.as_deref(), Some((&root, config.dir()))),
                Err(_) => self.config_inputs(path.as_deref(), None),
            },
            ConfigSource::File { path, .. } => self.config_inputs(path.as_deref(), None),
            ConfigSource::Tables { root, dir, .. } => self.config_inputs(None, Some((root, dir))),
        }
    }

    /// The `--config` file, when one is given (the embedded default is no file), and the files
    /// a linear rotor config names (its matrices: [`autobal::linear_rotor::config::file_names`],
    /// relative to the config's folder), so that no output overwrites them; with the tables the command read (after `--set`, or Python's tables)
    /// and the folder their files are read from, where it has them: the files they name are
    /// the inputs (not those of the file on disk), and the file is not read again. Without
    /// them, a config file that cannot be read or parsed here adds only itself (the command
    /// reports that error where it reads the config).
    pub fn config_inputs(&mut self, config: Option<&Path>, tables: Option<(&toml::Table, &Path)>) -> &mut Self {
        if let Some(c) = config {
            self.input("--config", c);
        }
        let read;
        let tables = match (tables, config) {
            (Some(t), _) => Some(t),
            (None, Some(c)) => {
                read = crate::config::read_limited(c).ok().and_then(|t| t.parse::<toml::Table>().ok());
                read.as_ref().map(|r| (r, c.parent().unwrap_or(Path::new(""))))
            }
            (None, None) => None,
        };
        if let Some((root, dir)) = tables {
            for (key, name) in autobal::linear_rotor::config::file_names(root) {
                self.input(&format!("--config's {key}"), &dir.join(name));
            }
        }
        self
    }

    /// A file the run will write, named by `option` in errors.
    pub fn output(&mut self, option: &str, path: &Path) -> &mut Self {
        self.outputs.push((option.to_string(), path.to_path_buf()));
        self
    }

    /// The user's `--out` (`given`, as [`resolve`]d) and the stem the command writes its files
    /// beside (`STEM.csv`, `STEM.json`, ...): when the command adds the extensions to the name
    /// as given (`stem == given`), the name must not be an existing device, FIFO or socket
    /// (`--out /dev/full` or `--out pipe` would write `/dev/full.csv`, `pipe.csv` beside it,
    /// not into it). A name given with its extension (`--out pipe.csv`, `--svg ff.svg`) is the
    /// file itself, whatever sits at its stem.
    pub fn stem(&mut self, option: &str, given: &Path, stem: &Path) -> &mut Self {
        if given == stem {
            self.stems.push((option.to_string(), stem.to_path_buf()));
        }
        self
    }

    /// Check every output: its folder exists (created if missing) and is writable, the path is
    /// not a folder nor anything but a regular file, and it is not one of the inputs. The first
    /// failure is one line naming the option.
    pub fn check(&self) -> Result<()> {
        self.check_with(None).map(|_| ())
    }

    /// [`Outputs::check`], and the first output's file created, staged ([`Staged::create`]):
    /// for a command that writes it as it runs, its folder's probe is that file itself (one file
    /// created instead of a probe created and removed, then the file; the same error when the
    /// folder is not writable). Dropped uncommitted, it is removed as any staged file.
    pub fn check_and_stage_first(&self) -> Result<Staged> {
        self.check_with(self.outputs.first().map(|(o, p)| (o.as_str(), p.as_path())))?.ok_or_else(|| anyhow!("no output to stage"))
    }

    fn check_with(&self, first: Option<(&str, &Path)>) -> Result<Option<Staged>> {
        let mut staged = None;
        let mut probed: Vec<PathBuf> = vec![];
        let inputs: Vec<Ident> = self.inputs.iter().map(|(_, ip)| Ident::of(ip, std::fs::metadata(ip).ok().as_ref())).collect();
        let mut outputs: Vec<Ident> = Vec::with_capacity(self.outputs.len());
        for (opt, stem) in &self.stems {
            if let Some(kind) = std::fs::metadata(stem).ok().and_then(|m| special_kind(&m)) {
                bail!(
                    "{opt}: {} is {kind}, not a file or folder name (outputs would go beside it, as {}); give a file name or a folder",
                    stem.display(),
                    crate::term::with_suffix(stem, "csv").display()
                );
            }
        }
        for (opt, p) in &self.outputs {
            if p.file_name().is_none() {
                bail!("{opt}: {} names no file", p.display());
            }
            // `--out $'a\nb'` wrote `a<line break>b.csv` and its figures: names a shell lists
            // across lines and a batch script cannot quote back (export-model's `--stem` refuses
            // them the same way)
            if let Some(n) = control_name(p) {
                bail!("{opt}: the name {n:?} has a control character (a line break, a tab, ...): give a name of printable characters");
            }
            // every output's own temporary name, not only the first in its folder (the probe's
            // is short): a plot's longer name must fail before the work, not after it
            let temp = temp_for(p);
            let long = temp.file_name().map_or(0, |n| n.len());
            if long > NAME_MAX {
                bail!(
                    "{opt}: the file name {:?} is too long: {long} bytes with the temporary suffix {:?} (file names may have {NAME_MAX})",
                    p.file_name().unwrap_or_default(),
                    format!(".{}.part", std::process::id())
                );
            }
            let meta = std::fs::metadata(p).ok();
            if let Some(kind) = meta.as_ref().and_then(special_kind) {
                bail!("{opt}: {} is {kind}, not a regular file: the output is renamed onto its name, which would replace it; give a file name", p.display());
            }
            match &meta {
                Some(m) if m.is_dir() => bail!("{opt}: {} is a folder, not a file", p.display()),
                _ => {}
            }
            let id = Ident::of(p, meta.as_ref());
            for ((iopt, ip), iid) in self.inputs.iter().zip(&inputs) {
                if id.same(iid) {
                    bail!("{opt}: {} is the input {iopt} {}; refusing to overwrite an input, give another name", p.display(), ip.display());
                }
            }
            for ((oopt, _), oid) in self.outputs.iter().zip(&outputs) {
                if id.same(oid) {
                    bail!("{opt}: {} is also the output of {oopt}", p.display());
                }
            }
            outputs.push(id);
            let dir = parent(p);
            if probed.contains(&dir) {
                continue;
            }
            let system = |sys: &str| {
                anyhow!("{opt}: {} is in the system folder {sys} (devices, kernel state), not a place for outputs; give another folder", p.display())
            };
            let missing = match std::fs::metadata(&dir) {
                Ok(m) if m.is_dir() => {
                    if let Some(sys) = system_folder(&dir) {
                        return Err(system(sys));
                    }
                    false
                }
                Ok(_) => bail!("{opt}: {} is not a folder", dir.display()),
                Err(_) if system_folder(&dir).is_some() => return Err(system(system_folder(&dir).unwrap_or_default())),
                // `q/..` with `q` missing: creating `q` only to step out of it again would leave
                // a folder nobody asked for
                Err(_) if steps_out_of_missing(&dir) => {
                    bail!("{opt}: the folder {} steps out of a folder that does not exist (`..`); give the folder itself", dir.display())
                }
                Err(_) => true,
            };
            let cannot = |e: std::io::Error| {
                if e.kind() == std::io::ErrorKind::InvalidFilename {
                    let what = if cfg!(unix) { "too long" } else { "too long or not allowed" };
                    anyhow!(
                        "{opt}: the file name {:?} (with the temporary suffix) is {what} for the folder {} ({e})",
                        p.file_name().unwrap_or_default(),
                        dir.display()
                    )
                } else {
                    anyhow!("{opt}: cannot write in the folder {}: {e}", dir.display())
                }
            };
            match first {
                Some((fopt, fp)) if staged.is_none() && parent(fp) == dir => staged = Some(Staged::open(fopt, fp).map_err(cannot)?),
                _ => {
                    // a missing folder is created for the probe and removed with it: a check
                    // writes nothing (a run that fails after it leaves no empty folder); the
                    // folder is made again when the output is written
                    let made =
                        if missing { make_folders(&dir).map_err(|e| anyhow!("{opt}: cannot create the folder {}: {e}", dir.display()))? } else { vec![] };
                    let probe = temp_for(&dir.join(".autobal-probe"));
                    let opened = File::options().write(true).create_new(true).open(&probe);
                    let _ = std::fs::remove_file(&probe);
                    remove_folders(&made);
                    opened.map_err(cannot)?;
                }
            }
            probed.push(dir);
        }
        Ok(staged)
    }
}

/// The temporary files being written now (every [`Staged`] and [`TempName`] not yet committed
/// or dropped), for [`remove_unfinished`].
static UNFINISHED: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

fn track_unfinished(p: &Path) {
    UNFINISHED.lock().unwrap_or_else(|e| e.into_inner()).push(p.to_path_buf());
}

fn untrack_unfinished(p: &Path) {
    let mut u = UNFINISHED.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(i) = u.iter().rposition(|q| q == p) {
        u.swap_remove(i);
    }
}

/// Remove every temporary file still being written (a process ending at once, as on a second
/// Ctrl-C, runs no destructor: the CLI's handler calls this before it exits, so that no
/// `NAME.PID.part` is left beside the outputs). Returns how many were removed.
pub fn remove_unfinished() -> usize {
    remove_unfinished_under(Path::new(""))
}

/// [`remove_unfinished`] for the temporary files under `dir` only (`""`: all).
fn remove_unfinished_under(dir: &Path) -> usize {
    let mut u = UNFINISHED.lock().unwrap_or_else(|e| e.into_inner());
    let mut n = 0;
    u.retain(|p| {
        if !p.starts_with(dir) {
            return true;
        }
        n += usize::from(std::fs::remove_file(p).is_ok());
        false
    });
    n
}

/// A file being written under a temporary name (`temp_for`); [`Staged::commit`] renames it
/// into place, dropping it uncommitted removes it.
pub struct Staged {
    option: String,
    path: PathBuf,
    tmp: PathBuf,
    /// The folders created for it, removed (when empty) if it is dropped uncommitted.
    made: Vec<PathBuf>,
    file: Option<BufWriter<File>>,
}

impl Staged {
    /// Create the temporary file for `path` (the option names it in errors).
    pub fn create(option: &str, path: &Path) -> Result<Self> {
        Self::open(option, path).with_context(|| format!("{option}: cannot create {}", temp_for(path).display()))
    }

    fn open(option: &str, path: &Path) -> std::io::Result<Self> {
        let tmp = temp_for(path);
        let made = make_folders(&parent(path))?;
        let f = match File::options().write(true).create(true).truncate(true).open(&tmp) {
            Ok(f) => f,
            Err(e) => {
                remove_folders(&made);
                return Err(e);
            }
        };
        track_unfinished(&tmp);
        Ok(Staged { option: option.to_string(), path: path.to_path_buf(), tmp, made, file: Some(BufWriter::with_capacity(1 << 16, f)) })
    }

    /// The temporary name the bytes go to until the commit.
    #[cfg(test)]
    pub fn temp_path(&self) -> &Path {
        &self.tmp
    }

    /// Flush and rename onto the final name; returns it.
    pub fn commit(mut self) -> Result<PathBuf> {
        let w = self.file.take().ok_or_else(|| anyhow!("{}: already committed", self.path.display()))?;
        // a failed last flush (disk full) leaves no temporary file behind: the handle is taken
        // out of `self` already, so `Drop` would not remove it
        let f = match w.into_inner() {
            Ok(f) => f,
            Err(e) => {
                let err = anyhow!("{}: cannot write {}: {}", self.option, self.path.display(), e.error());
                drop(e);
                let _ = std::fs::remove_file(&self.tmp);
                untrack_unfinished(&self.tmp);
                remove_folders(&self.made);
                return Err(err);
            }
        };
        drop(f);
        let renamed = std::fs::rename(&self.tmp, &self.path);
        untrack_unfinished(&self.tmp);
        if renamed.is_err() {
            let _ = std::fs::remove_file(&self.tmp);
            remove_folders(&self.made);
        }
        renamed.with_context(|| format!("{}: cannot rename {} to {}", self.option, self.tmp.display(), self.path.display()))?;
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
            untrack_unfinished(&self.tmp);
            remove_folders(&self.made);
        }
    }
}

/// Write every `(path, bytes)` whole, or none of them: each is written and flushed under its
/// temporary name first, and only when all are written are they renamed into place; on an
/// error the temporary files and the folders made for them are removed. (A full disk at the
/// third file of `export-model` left the first two: a model folder without its config.)
pub fn write_all_or_none(option: &str, files: &[(PathBuf, Vec<u8>)]) -> Result<Vec<PathBuf>> {
    let mut staged: Vec<Staged> = Vec::with_capacity(files.len());
    let result = (|| -> Result<()> {
        for (p, bytes) in files {
            let mut s = Staged::create(option, p)?;
            s.write_all(bytes).and_then(|_| s.flush()).with_context(|| format!("{option}: cannot write {}", p.display()))?;
            staged.push(s);
        }
        Ok(())
    })();
    if let Err(e) = result {
        // the last made first: a folder the first file made is empty when its turn comes
        while let Some(s) = staged.pop() {
            drop(s);
        }
        return Err(e);
    }
    staged.into_iter().map(Staged::commit).collect()
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
        let _ = make_folders(&parent(path));
        let f = File::create(&tmp).with_context(|| format!("{option}: cannot create {}", tmp.display()))?;
        track_unfinished(&tmp);
        Ok((TempName { option: option.to_string(), path: path.to_path_buf(), tmp, done: false }, f))
    }

    /// Rename the (closed, complete) temporary file onto the final name.
    pub fn rename(mut self) -> Result<PathBuf> {
        std::fs::rename(&self.tmp, &self.path).with_context(|| format!("{}: cannot rename {} to {}", self.option, self.tmp.display(), self.path.display()))?;
        self.done = true;
        untrack_unfinished(&self.tmp);
        Ok(self.path.clone())
    }
}

impl Drop for TempName {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_file(&self.tmp);
            untrack_unfinished(&self.tmp);
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

    /// `--svg st.png` wrote SVG text under a .png name (session 28's hunt): a name or prefix
    /// with another extension than `.svg` (any case) is refused naming the flag; a name without
    /// an extension is taken, as a folder's default name is.
    #[test]
    fn an_svg_name_with_another_extension_is_refused() {
        for (name, prefix) in [("st.svg", false), ("st.SVG", false), ("runs/st", false), ("c", true), ("c.svg", true), ("runs/", false)] {
            check_svg_name("--svg", &resolve(Path::new(name), "stability.svg"), prefix).unwrap();
        }
        for (name, prefix) in [("st.png", false), ("st.pdf", false), ("c.png", true), ("runs/c.jpeg", true)] {
            let e = check_svg_name("--svg", Path::new(name), prefix).unwrap_err().to_string();
            assert!(e.starts_with(&format!("--svg: {name}: the figure")) && e.contains("SVG only") && !e.contains('\n'), "{e}");
        }
    }

    /// A set of files written whole or not at all: the third cannot be created (its folder is
    /// a file), so neither of the first two appears, nor their temporary files, nor the folder
    /// made for them; with all three writable all three appear, byte for byte.
    #[test]
    fn an_output_name_with_a_control_character_is_refused_before_anything_is_written() {
        let d = scratch("control");
        for name in ["a\nb.csv", "tab\there.csv", "bell\u{7}.json"] {
            let e = Outputs::new().output("--out", &d.join(name)).check().unwrap_err().to_string();
            assert!(e.starts_with("--out: the name") && e.contains("control character"), "{e}");
        }
        // a folder the run would make (the report's `--out`), not one that exists
        let e = Outputs::new().output("--out", &d.join("new\nfolder").join("index.html")).check().unwrap_err().to_string();
        assert!(e.contains("\"new\\nfolder\"") && e.contains("control character"), "{e}");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0, "nothing written");
        // printable names, unicode included, still pass
        Outputs::new().output("--out", &d.join("räder ø.csv")).check().unwrap();
        std::fs::remove_dir_all(&d).ok();
    }

    #[test]
    fn all_or_none_leaves_nothing_when_one_fails() {
        let d = scratch("all-or-none");
        std::fs::write(d.join("blocker"), "a file where a folder is needed").unwrap();
        let out = d.join("model");
        let files =
            |third: PathBuf| vec![(out.join("m.toml"), b"[linear_rotor]\n".to_vec()), (out.join("m_M.mtx"), vec![b'x'; 100_000]), (third, b"k".to_vec())];
        let e = write_all_or_none("--out", &files(d.join("blocker").join("m_K.mtx"))).unwrap_err().to_string();
        assert!(e.starts_with("--out: cannot create"), "{e}");
        assert!(!out.exists(), "the folder made for the set is removed: {:?}", std::fs::read_dir(&out).map(|r| r.count()));
        let ok = files(out.join("m_K.mtx"));
        let written = write_all_or_none("--out", &ok).unwrap();
        assert_eq!(written, ok.iter().map(|f| f.0.clone()).collect::<Vec<_>>());
        for (p, bytes) in &ok {
            assert_eq!(&std::fs::read(p).unwrap(), bytes);
        }
        assert_eq!(std::fs::read_dir(&out).unwrap().count(), 3, "no temporary file left");
        std::fs::remove_dir_all(&d).ok();
    }

    #[test]
    fn remove_unfinished_removes_what_is_being_written_and_nothing_else() {
        // what a second Ctrl-C's handler does before the process exits: the staged files still
        // open are removed, the committed and the dropped ones are not its business
        let d = scratch("unfinished");
        let (a, b, c) = (d.join("a.csv"), d.join("b.csv"), d.join("c.parquet"));
        let done = Staged::create("--out", &a).unwrap();
        done.commit().unwrap();
        let open = Staged::create("--out", &b).unwrap();
        let (name, _file) = TempName::create("--parquet", &c).unwrap();
        let (tb, tc) = (open.temp_path().to_path_buf(), temp_for(&c));
        assert!(tb.exists() && tc.exists());
        // only this test's folder: the other tests of this process write files at the same time
        assert_eq!(remove_unfinished_under(&d), 2);
        assert!(!tb.exists() && !tc.exists() && a.exists());
        std::mem::forget(open);
        std::mem::forget(name);
        let _ = std::fs::remove_dir_all(&d);
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
    fn a_missing_folder_and_back_a_too_long_name_and_two_outputs_in_a_new_folder() {
        let d = scratch("edges");
        // `q/..` with `q` missing: refused, and `q` not created
        let e = Outputs::new().output("--out", &resolve(&d.join("q/.."), "s.csv")).check().unwrap_err().to_string();
        assert!(e.starts_with("--out: ") && e.contains("`..`"), "{e}");
        assert!(!d.join("q").exists(), "a folder was created for `q/..`");
        // a missing folder reached through an existing one's `..` is created as before
        let sub = d.join("e");
        std::fs::create_dir(&sub).unwrap();
        Outputs::new().output("--out", &sub.join("../made/x.csv")).check().unwrap();
        assert!(!d.join("made").exists(), "a check made a folder");
        let s = Outputs::new().output("--out", &sub.join("../made/x.csv")).check_and_stage_first().unwrap();
        assert!(d.join("made").is_dir());
        drop(s);
        assert!(!d.join("made").exists(), "a staged file dropped uncommitted left its folder");
        let mut s = Staged::create("--out", &d.join("made/x.csv")).unwrap();
        writeln!(s, "x").unwrap();
        s.commit().unwrap();
        assert!(steps_out_of_missing(&d.join("q/r/../x")) && !steps_out_of_missing(Path::new("../x/y")));
        // a name longer than the file system allows names the name, not the folder
        let long = d.join("n".repeat(300));
        let e = Outputs::new().output("--out", &long).check_and_stage_first().err().expect("too long").to_string();
        assert!(e.starts_with("--out: ") && e.contains("too long") && !e.contains("cannot write in the folder"), "{e}");
        // a second output in the same folder whose name is too long only with its suffix: caught
        // before any work (its folder was probed with a short name)
        let e = Outputs::new().output("--out", &d.join("a.csv")).output("--svg", &d.join("s".repeat(250))).check().unwrap_err().to_string();
        assert!(e.starts_with("--svg: ") && e.contains("too long") && e.contains(".part"), "{e}");
        let left: Vec<_> =
            std::fs::read_dir(&d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).filter(|n| n != "e" && n != "made").collect();
        assert!(left.is_empty(), "a check left {left:?}");
        // the same file twice in a folder that does not exist yet: the first output's folder
        // lookup failed before the folder was created, and is tried again for the second
        // (compared with an existing input first, while the folder is still missing)
        let cfg = d.join("c.toml");
        std::fs::write(&cfg, "x").unwrap();
        let mut o = Outputs::new();
        o.input("--config", &cfg).output("--out", &d.join("new/a.csv")).output("--svg", &d.join("new/./a.csv"));
        let e = o.check().unwrap_err().to_string();
        assert!(e.contains("also the output of --out"), "{e}");
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
            assert!(e.contains("is a device, not a regular file"), "{e}");
            // named after a device: `--out /dev/full` as a stem
            let null = Path::new("/dev/null");
            let e = Outputs::new().stem("--out", null, null).output("--out", Path::new("/dev/null.csv")).check().unwrap_err().to_string();
            assert!(e.starts_with("--out: /dev/null is a device, not a file or folder name"), "{e}");
            // into /dev, /proc, /sys (also through `..`), but /dev/shm is a file system for files
            for p in ["/dev/autobal-x.csv", "/tmp/../dev/a/b.csv", "/proc/x.csv", "/sys/q/x.csv"] {
                let e = Outputs::new().output("--out", Path::new(p)).check().unwrap_err().to_string();
                assert!(e.contains("is in the system folder /"), "{p}: {e}");
                assert!(!Path::new(p).exists());
            }
            assert_eq!(system_folder(Path::new("/dev/shm/a")), None);
            assert_eq!(system_folder(Path::new("/tmp")), None);
            assert_eq!(system_folder(Path::new("/device")), None);
        }
        // a missing parent is accepted (and made when the file is written, not by the check)
        Outputs::new().input("--config", &cfg).output("--out", &d.join("sub/deeper/x.csv")).check().unwrap();
        assert!(!d.join("sub").exists());
        assert_eq!(resolve(Path::new("runs/"), "simulation.csv"), PathBuf::from("runs/simulation.csv"));
        assert_eq!(resolve(&d, "s.csv"), d.join("s.csv"));
        assert_eq!(resolve(Path::new("x"), "s.csv"), PathBuf::from("x"));
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// A FIFO is refused as a stem the command adds extensions to (`--out pipe` would write
    /// `pipe.csv` beside it), but not when the user named the file with its extension
    /// (`--svg pipe.svg`, `--out pipe.csv`): that file is the output, the FIFO is not used.
    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_as_a_stem_only_when_extensions_are_added_to_it() {
        let d = scratch("fifo-stem");
        let fifo = d.join("pipe");
        if !std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
            return;
        }
        let (csv, svg) = (d.join("pipe.csv"), d.join("pipe.svg"));
        Outputs::new().output("--svg", &svg).check().unwrap();
        Outputs::new().stem("--out", &csv, &fifo).output("--out", &csv).output("--out", &svg).check().unwrap();
        let e = Outputs::new().stem("--out", &fifo, &fifo).output("--out", &csv).check().unwrap_err().to_string();
        assert!(e.starts_with(&format!("--out: {} is a FIFO (named pipe), not a file or folder name", fifo.display())), "{e}");
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// `check_and_stage_first` checks as `check` does and leaves exactly the first output's
    /// staged file in its folder (no probe file): committed it becomes the output, dropped it
    /// goes; a later output that fails the check leaves nothing behind.
    #[test]
    fn the_first_output_staged_is_its_folder_s_probe() {
        let d = scratch("first");
        let (a, b) = (d.join("sub/a.csv"), d.join("sub/a.svg"));
        let mut s = Outputs::new().output("--out", &a).output("--out", &b).check_and_stage_first().unwrap();
        let names = |dir: &Path| {
            let mut n: Vec<String> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
            n.sort();
            n
        };
        assert_eq!(names(&d.join("sub")), [format!("a.csv.{}.part", std::process::id())]);
        writeln!(s, "x").unwrap();
        assert_eq!(s.commit().unwrap(), a);
        assert_eq!(names(&d.join("sub")), ["a.csv"]);
        drop(Outputs::new().output("--out", &b).check_and_stage_first().unwrap());
        assert_eq!(names(&d.join("sub")), ["a.csv"]);
        let e = Outputs::new().output("--out", &b).output("--svg", &d.join("sub/./a.svg")).check_and_stage_first().err().expect("twice").to_string();
        assert!(e.ends_with("is also the output of --out"), "{e}");
        assert_eq!(names(&d.join("sub")), ["a.csv"]);
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// One file named twice among the outputs is refused whether it exists yet or not (by
    /// device and inode, or by canonical folder and name), through a `./` spelling, a `..`
    /// spelling and a hard link; distinct files, existing or not, pass; `same_file` says the
    /// same pair by pair.
    #[test]
    fn an_output_named_twice_is_refused_existing_or_not() {
        let d = scratch("twice");
        std::fs::create_dir_all(d.join("sub")).unwrap();
        let (a, b) = (d.join("a.csv"), d.join("b.csv"));
        let dot = d.join(".").join("a.csv");
        let up = d.join("sub").join("..").join("a.csv");
        for exists in [false, true] {
            if exists {
                std::fs::write(&a, "x").unwrap();
                std::fs::write(&b, "y").unwrap();
            }
            for other in [&dot, &up] {
                let e = Outputs::new().output("--out", &a).output("--svg", &b).output("--png", other).check().unwrap_err().to_string();
                assert!(e.starts_with("--png: ") && e.ends_with("is also the output of --out"), "{e}");
                assert!(same_file(&a, other) && !same_file(&b, other));
            }
            Outputs::new().output("--out", &a).output("--svg", &b).check().unwrap();
            assert!(!same_file(&a, &b));
        }
        #[cfg(unix)]
        {
            let link = d.join("link.csv");
            std::fs::hard_link(&a, &link).unwrap();
            let e = Outputs::new().output("--out", &a).output("--svg", &link).check().unwrap_err().to_string();
            assert!(e.ends_with("is also the output of --out"), "{e}");
        }
        // an existing file and a missing one are not the same
        assert!(!same_file(&a, &d.join("c.csv")));
        std::fs::remove_dir_all(&d).unwrap();
    }
}
