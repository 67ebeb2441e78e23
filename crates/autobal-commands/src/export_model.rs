//! `autobal export-model`: a linear rotor written as a config plus Matrix Market files
//! (`STEM.toml`, `STEM_{M,C,G,K}.mtx`, `STEM_M_rot.mtx` for inertia fixed to the rotor and
//! `STEM_KST.mtx` for an angular-acceleration stiffness,
//! [`autobal::linear_rotor::config::export`]): a linear rotor config's rotor (reduced where it
//! sets `linear_rotor.modes`, the model the other commands run), a spatial config's rotor of
//! papers 000/003 as its linear preset ([`LinearRotor::from_spatial`]), or without a config
//! paper 004's rotor with its race centred as a Jeffcott rotor ([`linear_rotor::preset`]).
//! Every file is checked before any is written, and each is written under a temporary name and
//! renamed ([`crate::outfile`]).

use crate::command::{self, ConfigSource};
use crate::linear_rotor;
use anyhow::{bail, Result};
use autobal::control::Control;
use autobal::linear_rotor::LinearRotor;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// `autobal export-model`'s arguments.
#[derive(Debug, Clone)]
pub struct Args {
    /// The config (a `[linear_rotor]` config, or a spatial one: its linear preset); `File`
    /// without a path: paper 004's rotor ([`linear_rotor::preset`]).
    pub config: ConfigSource,
    /// `--out`: the folder the files go into (created if missing).
    pub out: PathBuf,
    /// `--stem`: the files' name stem.
    pub stem: String,
}

impl Default for Args {
    fn default() -> Self {
        Args { config: ConfigSource::default(), out: PathBuf::from("model"), stem: "rotor".into() }
    }
}

/// The files `export-model` wrote: `STEM.toml` first, then the matrices.
pub struct Output {
    /// The paths written.
    pub written: Vec<PathBuf>,
}

impl command::Command for Args {
    const NAME: &'static str = "export-model";
    type Output = Output;

    fn run(&self, _control: &Control) -> Result<Output> {
        if self.stem.trim().is_empty() {
            bail!("--stem {:?}: is empty: give a file name stem such as `rotor` (the folder is --out)", self.stem);
        }
        if self.stem.contains(['/', '\\']) {
            bail!("--stem {:?}: a file name stem without a folder (the folder is --out)", self.stem);
        }
        // (`.` wrote the hidden `..toml` and `._M.mtx`, `..` wrote `...toml`: a folder's name,
        // not a file's stem)
        if self.stem.chars().all(|c| c == '.') {
            bail!("--stem {:?}: names a folder (`.`, `..`), not a file: give a file name stem such as `rotor` (the folder is --out)", self.stem);
        }
        // (a newline in the stem wrote files whose names break every listing and message)
        if self.stem.chars().any(char::is_control) {
            bail!("--stem {:?}: has a control character (a line break, a tab, …): give a file name stem of printable characters", self.stem);
        }
        let (rotor, root) = match &self.config {
            ConfigSource::File { path: None, sets } => {
                if let Some(s) = sets.first() {
                    bail!("--set {s}: needs --config (without one, export-model writes paper 004's rotor as it is)");
                }
                (linear_rotor::preset()?, None)
            }
            ConfigSource::File { path: Some(p), sets } => {
                let (root, source) = linear_rotor::read_set(Some(p), sets)?;
                (rotor_of(&root, self.config.dir(), &source)?, Some(root))
            }
            ConfigSource::Tables { .. } => {
                let (root, source) = self.config.read()?;
                (rotor_of(&root, self.config.dir(), &source)?, Some(root))
            }
        };
        // the config and the files it names are inputs: never overwritten by the export
        let inputs = (self.config.path(), root.as_ref().map(|r| (r, self.config.dir())));
        Ok(Output { written: linear_rotor::export_model(&rotor, inputs, &self.out, &self.stem)? })
    }
}

/// The rotor a config describes: a linear rotor config's, reduced where it sets
/// `linear_rotor.modes` (the model the commands run), or a spatial config's rotor of papers
/// 000/003 as the linear preset ([`LinearRotor::from_spatial`], its inertia that turns with the
/// rotor in `rotor_fixed_mass`; in the config's units: SI, or the papers' dimensionless ones).
fn rotor_of(root: &toml::Table, dir: &Path, source: &str) -> Result<LinearRotor> {
    if linear_rotor::is_linear(root) {
        return Ok(linear_rotor::model(&linear_rotor::from_table(root, dir)?)?.0);
    }
    if autobal::config::is_spatial(root) {
        return Ok(LinearRotor::from_spatial(&autobal::config::spatial_simulation(root)?.rotor)?);
    }
    bail!("config {source}: neither a linear rotor config (a [linear_rotor] table) nor a spatial one (papers 000/003: [rotor] ... or [dimensionless])")
}

impl command::Output for Output {
    /// `{"files": [...]}`: the paths written.
    fn json(&self) -> Result<Value> {
        Ok(json!({ "files": self.written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>() }))
    }
    /// `wrote PATH, PATH, ...`.
    fn table(&self) -> Result<String> {
        Ok(format!("wrote {}\n", self.written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::{Command as _, Output as _};

    /// Without a config the preset is written: the config and the four matrices, and the config
    /// read back through the linear rotor route is the preset's rotor (the same matrices,
    /// entry for entry: Matrix Market text of shortest round-trip floats).
    #[test]
    fn the_preset_round_trips() {
        let d = std::env::temp_dir().join(format!("autobal-export-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        let o = Args { out: d.clone(), ..Default::default() }.run(&Control::none()).unwrap();
        let names: Vec<String> = o.written.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
        assert_eq!(names, ["rotor.toml", "rotor_M.mtx", "rotor_C.mtx", "rotor_G.mtx", "rotor_K.mtx"]);
        assert_eq!(o.table().unwrap(), format!("wrote {}\n", o.written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")));
        let back = linear_rotor::load(&d.join("rotor.toml"), &[]).unwrap().rotor;
        let want = linear_rotor::preset().unwrap();
        assert_eq!((back.m, back.c, back.g, back.k), (want.m, want.c, want.g, want.k));
        // a stem with a folder in it is refused before anything is written
        let e = Args { out: d.join("other"), stem: "a/b".into(), ..Default::default() }.run(&Control::none()).err().unwrap();
        assert!(format!("{e:#}").starts_with("--stem \"a/b\""), "{e:#}");
        assert!(!d.join("other").exists());
        // `.` and `..` name folders: they wrote the hidden `..toml`, `._M.mtx` and `...toml`
        for stem in [".", "..", ""] {
            let e = Args { out: d.join("other"), stem: stem.into(), ..Default::default() }.run(&Control::none()).err().unwrap();
            assert!(format!("{e:#}").starts_with(&format!("--stem {stem:?}: ")) && !format!("{e:#}").contains('\n'), "{e:#}");
        }
        assert!(!d.join("other").exists());
        let _ = std::fs::remove_dir_all(&d);
    }

    /// A spatial config (papers 000/003, SI, with a couple and unequal supports) is written as
    /// its linear preset ([`LinearRotor::from_spatial`]), the inertia that turns with the rotor
    /// (its unbalance masses') as `STEM_M_rot.mtx`, its tilt chart as `STEM_chart.mtx`; read back through the linear rotor route it
    /// is the preset bit for bit, and export-model of the written config writes the same files
    /// byte for byte.
    #[test]
    fn a_spatial_config_is_written_as_its_preset() {
        let d = std::env::temp_dir().join(format!("autobal-export-spatial-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        let cfg = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/spatial_two_plane.toml");
        let args = |config: &Path, out: PathBuf| Args { config: ConfigSource::File { path: Some(config.to_path_buf()), sets: vec![] }, out, stem: "s".into() };
        let o = args(&cfg, d.join("a")).run(&Control::none()).unwrap();
        let names: Vec<String> = o.written.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
        assert_eq!(names, ["s.toml", "s_M.mtx", "s_C.mtx", "s_G.mtx", "s_K.mtx", "s_chart.mtx", "s_M_rot.mtx"]);
        let (root, _) = linear_rotor::read_set(Some(&cfg), &[]).unwrap();
        let want = LinearRotor::from_spatial(&autobal::config::spatial_simulation(&root).unwrap().rotor).unwrap();
        assert!(!want.rotor_fixed_mass.is_empty());
        let back = linear_rotor::load(&d.join("a/s.toml"), &[]).unwrap().rotor;
        assert_eq!(back, want);
        let again = args(&d.join("a/s.toml"), d.join("b")).run(&Control::none()).unwrap();
        for (p, q) in o.written.iter().zip(&again.written) {
            assert_eq!(std::fs::read(p).unwrap(), std::fs::read(q).unwrap(), "{}", p.display());
        }
        // neither a linear rotor nor a spatial config: one line naming the config
        let planar = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/planar.toml");
        let e = format!("{:#}", args(&planar, d.join("c")).run(&Control::none()).err().unwrap());
        assert!(e.contains("neither a linear rotor config") && !e.contains('\n'), "{e}");
        assert!(!d.join("c").exists());
        let _ = std::fs::remove_dir_all(&d);
    }
}
