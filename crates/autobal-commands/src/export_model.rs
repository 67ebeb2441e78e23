//! `autobal export-model`: a linear rotor written as a config plus Matrix Market files
//! (`STEM.toml`, `STEM_{M,C,G,K}.mtx`, and `STEM_KST.mtx` where the rotor has an
//! angular-acceleration stiffness, [`autobal::linear_rotor::config::export`]): the config's
//! rotor (reduced where it sets `linear_rotor.modes`, the model the other commands run), or
//! without a config paper 004's rotor with its race centred as a Jeffcott rotor
//! ([`linear_rotor::preset`]). Every file is checked before any is written, and each is written
//! under a temporary name and renamed ([`crate::outfile`]).

use crate::command::{self, ConfigSource};
use crate::linear_rotor;
use anyhow::{bail, Result};
use autobal::control::Control;
use serde_json::{json, Value};
use std::path::PathBuf;

/// `autobal export-model`'s arguments.
#[derive(Debug, Clone)]
pub struct Args {
    /// The config (a `[linear_rotor]` config); `File` without a path: paper 004's rotor
    /// ([`linear_rotor::preset`]).
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
        if self.stem.is_empty() || self.stem.contains(['/', '\\']) {
            bail!("--stem {:?}: a file name stem without a folder (the folder is --out)", self.stem);
        }
        let rotor = match &self.config {
            ConfigSource::File { path: None, sets } => {
                if let Some(s) = sets.first() {
                    bail!("--set {s}: needs --config (without one, export-model writes paper 004's rotor as it is)");
                }
                linear_rotor::preset()?
            }
            // the model the commands run: reduced where the config asks for it
            ConfigSource::File { path: Some(p), sets } => linear_rotor::model(&linear_rotor::load(p, sets)?)?.0,
            ConfigSource::Tables { .. } => {
                let (root, source) = self.config.read()?;
                if !linear_rotor::is_linear(&root) {
                    bail!("config {source}: not a linear rotor config (it has no [linear_rotor] table)");
                }
                linear_rotor::model(&linear_rotor::from_table(&root, self.config.dir())?)?.0
            }
        };
        Ok(Output { written: linear_rotor::export_model(&rotor, &self.out, &self.stem)? })
    }
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
        let _ = std::fs::remove_dir_all(&d);
    }
}
