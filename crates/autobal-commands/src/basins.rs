//! `autobal basins`: where runs of the spatial rotor end over an `n × n` grid of the first two
//! balls' initial angles (the rest of the initial state from the config), in parallel
//! ([`autobal::spatial::dynamics::basins`]).

use crate::command::{self, ConfigSource};
use crate::plot::{ColorScale, Heatmap, Plot};
use anyhow::Result;
use autobal::control::Control;
use autobal::spatial::dynamics::basins::{angle_grid, basins, check_angle_grid};
use autobal::spatial::dynamics::Summary;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// `--n` when none is given (Python's `basins(n=16)` keeps its smaller default).
pub const DEFAULT_N: usize = 24;

/// `autobal basins`' arguments.
#[derive(Debug, Clone)]
pub struct Args {
    /// The config (the spatial rotor's tables plus `[drive]`).
    pub config: ConfigSource,
    /// Grid points per angle (`n × n` runs).
    pub n: usize,
}

impl Default for Args {
    fn default() -> Self {
        Args { config: ConfigSource::default(), n: DEFAULT_N }
    }
}

/// The figure's file beside the CSV `csv` (`basins.csv` -> `basins.svg`; a name without
/// `.csv`, `b` -> `b.svg`): [`Output::plot`] as SVG, what the CLI writes.
pub fn figure_path(csv: &Path) -> PathBuf {
    crate::term::with_suffix(&crate::term::out_stem(csv, &["csv"]), "svg")
}

/// `basins`' result: each run's initial angles and end (`None`: not run, the grid was stopped).
pub struct Output {
    /// The first two balls' initial angles of each run, `psi_2` outer.
    pub angles: Vec<[f64; 2]>,
    /// Each run's end.
    pub ends: Vec<Option<Summary>>,
    /// Wall time of the grid (s).
    pub wall: f64,
    /// Where the front end wrote the CSV ([`Output::csv`]), named in the JSON and the table.
    pub written: Option<PathBuf>,
    /// Where the front end wrote the figure ([`Output::plot`] as SVG, [`figure_path`]), named
    /// in the JSON (`svg`) and the table.
    pub svg: Option<PathBuf>,
    /// A linear rotor config's ends (`ends` is then empty): the runs of [`autobal::linear_rotor::basins`].
    pub linear: Option<Vec<Option<autobal::linear_rotor::basins::BasinEnd>>>,
    /// The runs' relative tolerance: each end is that at this tolerance, not checked against a
    /// tighter one (the table's line and the JSON's `tolerance_check`, as `simulate`'s:
    /// [`crate::tolerance::unchecked_runs`]; issue 18 item 4: near a basin boundary, which is
    /// what this grid maps, an end can depend on the tolerance). `None` where the runs have no
    /// tolerance check (a linear rotor's, as `simulate`'s: review 26a).
    pub rtol: Option<f64>,
}

impl command::Command for Args {
    const NAME: &'static str = "basins";
    type Output = Output;

    fn run(&self, control: &Control) -> Result<Output> {
        let (root, source) = self.config.read_any()?;
        if crate::linear_rotor::is_linear(&root) {
            return linear(&root, self.config.dir(), self.n, control);
        }
        let sim = crate::spatial_sim::build(&root, &source)?;
        crate::config::check_entries_with(&root, "basins", &[crate::config::Model::Spatial], crate::config::FromLinear::RunUp)?;
        check_angle_grid(&sim.rotor, self.n, "--n")?;
        let cases = angle_grid(&sim.initial, &sim.drive, self.n, self.n);
        let t0 = std::time::Instant::now();
        let ends = basins(&sim.rotor, &cases, &sim.settings, control)?.value;
        let wall = t0.elapsed().as_secs_f64();
        Ok(Output {
            angles: cases.iter().map(|c| [c.initial.psi[0], c.initial.psi[1]]).collect(),
            ends,
            wall,
            written: None,
            svg: None,
            linear: None,
            rtol: Some(sim.settings.rtol),
        })
    }
}

impl Output {
    /// The basins' figure (the report's `basins`, `autobal basins`' and Python's): a cell of
    /// an `n × n` heatmap per run at its first two balls' initial angles (ψ1 the column, ψ2
    /// the row, °), -1 (green) where it ends balanced, +1 (orange) where not, NaN (grey) not
    /// run; a linear rotor config's is [`crate::linear_rotor::basins_plot`]. An interrupted
    /// grid's title begins `INCOMPLETE:` (as `stability`'s and `campbell`'s figures:
    /// `stability::mark_stopped`; the runs not done are the grey cells).
    pub fn plot(&self) -> Plot {
        crate::stability::mark_stopped(self.unmarked_plot(), &command::Output::stopped(self), None)
    }

    /// [`Output::plot`] without the mark of an interrupted grid.
    fn unmarked_plot(&self) -> Plot {
        if let Some(l) = &self.linear {
            return crate::linear_rotor::basins_plot(&self.angles, l);
        }
        let tau = std::f64::consts::TAU;
        let n = ((self.angles.len() as f64).sqrt().round() as usize).max(1);
        let xs: Vec<f64> = (0..n).map(|i| (tau * i as f64 / n as f64).to_degrees()).collect();
        let mut z = vec![vec![f64::NAN; n]; n];
        let cell = |psi: f64| ((psi / tau * n as f64).round() as usize).min(n - 1);
        for (a, r) in self.angles.iter().zip(&self.ends) {
            if let Some(r) = r {
                z[cell(a[1])][cell(a[0])] = if r.balanced { -1.0 } else { 1.0 };
            }
        }
        let step = 360.0 / n as f64;
        Plot {
            title: "Where the balls end, by their initial angles".into(),
            x_label: "initial angle of ball 1 (°)".into(),
            y_label: "initial angle of ball 2 (°)".into(),
            x_range: Some((-step / 2.0, 360.0 - step / 2.0)),
            y_range: Some((-step / 2.0, 360.0 - step / 2.0)),
            heatmap: Some(Heatmap { x: xs.clone(), y: xs, z, scale: ColorScale::Verdict, label: "end (stable = balanced)".into() }),
            ..Default::default()
        }
    }

    /// The CSV of the complete runs: `psi_1,psi_2,balanced,residual_unbalance,final_amplitude`.
    pub fn csv(&self) -> String {
        if let Some(l) = &self.linear {
            return crate::linear_rotor::basins_csv(l);
        }
        let mut csv = String::from("psi_1,psi_2,balanced,residual_unbalance,final_amplitude\n");
        for (a, r) in self.angles.iter().zip(&self.ends) {
            if let Some(s) = r {
                csv.push_str(&format!(
                    "{},{},{},{},{}\n",
                    crate::num::Csv(a[0]),
                    crate::num::Csv(a[1]),
                    s.balanced as u8,
                    crate::num::Csv(s.residual_unbalance),
                    crate::num::Csv(s.final_amplitude)
                ));
            }
        }
        csv
    }
}

impl command::Output for Output {
    fn json(&self) -> Result<Value> {
        let mut v = match &self.linear {
            Some(l) => crate::linear_rotor::basins_json(l, self.wall),
            None => autobal::reports::basins(&self.ends, self.wall),
        };
        if let Some(p) = &self.written {
            v["csv"] = json!(p.display().to_string());
        }
        if let Some(p) = &self.svg {
            v["svg"] = json!(p.display().to_string());
        }
        if let Some(r) = self.rtol {
            v["tolerance_check"] = crate::tolerance::unchecked_runs(Some(r)).0;
        }
        Ok(v)
    }
    fn table(&self) -> Result<String> {
        let (runs, done, balanced) = match &self.linear {
            Some(l) => (l.len(), l.iter().flatten().count(), l.iter().flatten().filter(|s| s.balanced).count()),
            None => (self.ends.len(), self.ends.iter().flatten().count(), self.ends.iter().flatten().filter(|s| s.balanced).count()),
        };
        // an interrupted grid: the share is of the runs completed, and says so (hunt 27: "38 of
        // 10000 runs balanced (76.0 %)" after 50 runs)
        let share = 100.0 * balanced as f64 / done.max(1) as f64;
        let head = if done < runs {
            format!("{balanced} of the {done} runs completed balanced ({share:.1} %; interrupted: {done} of {runs} runs)")
        } else {
            format!("{balanced} of {runs} runs balanced ({share:.1} %)")
        };
        Ok(format!(
            "{head}, {:.2} s{}\n{}",
            self.wall,
            match (&self.written, &self.svg) {
                (Some(c), Some(f)) => format!("; wrote {} and {}", c.display(), f.display()),
                (Some(p), None) | (None, Some(p)) => format!("; wrote {}", p.display()),
                (None, None) => String::new(),
            },
            self.rtol.map_or(String::new(), |r| crate::tolerance::unchecked_runs(Some(r)).1 + "\n")
        ))
    }
    /// `basins`: [`Output::plot`].
    fn figures(&self) -> Result<Vec<command::Figure>> {
        Ok(vec![command::Figure { id: "basins".into(), plot: self.plot() }])
    }
    fn stopped(&self) -> Option<String> {
        let (runs, done) = match &self.linear {
            Some(l) => (l.len(), l.iter().flatten().count()),
            None => (self.ends.len(), self.ends.iter().flatten().count()),
        };
        (done < runs).then(|| {
            format!("interrupted: {done} of {runs} runs complete{}", self.written.as_ref().map_or(String::new(), |p| format!(", kept in {}", p.display())))
        })
    }
}

/// `basins` on a linear rotor config: the runs of `simulate` (its drive, its reduction) from an
/// `n × n` grid of the first two balls' initial angles ([`autobal::linear_rotor::basins`]),
/// matrix files read relative to `dir`.
fn linear(root: &toml::Table, dir: &std::path::Path, n: usize, control: &Control) -> Result<Output> {
    use autobal::linear_rotor::basins::{angle_grid, basins};
    let cfg = crate::linear_rotor::from_table(root, dir)?;
    let run = autobal::linear_rotor::spec::run_of(&cfg)?;
    let starts = angle_grid(&run.rotor, n, "--n")?;
    let t0 = std::time::Instant::now();
    let ends = basins(&run, &starts, control)?.value;
    Ok(Output {
        angles: starts.iter().map(|p| [p[0], p[1]]).collect(),
        ends: vec![],
        wall: t0.elapsed().as_secs_f64(),
        written: None,
        svg: None,
        linear: Some(ends),
        rtol: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::{Command as _, Output as _};

    /// `basins` on a linear rotor config through the command: stopped before any run, it keeps
    /// nothing and says so; the CSV has the linear rotor's columns.
    #[test]
    fn basins_on_a_linear_config_say_what_they_kept() {
        use crate::command::ConfigSource;
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/linear_rotor_shaft.toml");
        let control = autobal::control::Control::new();
        control.cancel();
        let o = Args { config: ConfigSource::file(Some(&path), &[]), n: 2 }.run(&control).unwrap();
        assert_eq!(o.angles.len(), 4);
        assert!(o.csv().starts_with("psi_1,psi_2,balanced,residual_unbalance,final_amplitude,completed"));
        assert_eq!(o.json().unwrap()["model"], json!("linear"));
        assert_eq!(o.stopped().unwrap(), "interrupted: 0 of 4 runs complete");
        assert!(o.plot().title.starts_with("INCOMPLETE: "), "{}", o.plot().title);
        let e = Args { config: ConfigSource::file(Some(&path), &[]), n: 1 }.run(&control).err().unwrap().to_string();
        assert!(e.starts_with("--n"), "{e}");
    }

    /// A grid stopped before any run ends keeps nothing, and says so: no CSV rows, the JSON
    /// counts no completed run, `stopped` names the count (and the file, once written).
    #[test]
    fn a_stopped_grid_says_what_it_kept() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/spatial.toml");
        let control = Control::new();
        control.cancel();
        let mut o = Args { config: ConfigSource::file(Some(&path), &[]), n: 2 }.run(&control).unwrap();
        assert_eq!(o.ends.len(), 4);
        let done = o.ends.iter().flatten().count();
        assert_eq!(o.csv().lines().count(), 1 + done);
        assert_eq!(o.json().unwrap()["completed"], json!(done));
        assert!(done < 4);
        assert_eq!(o.stopped().unwrap(), format!("interrupted: {done} of 4 runs complete"));
        o.written = Some("b.csv".into());
        assert!(o.stopped().unwrap().ends_with(", kept in b.csv"));
        // its figure says so, as stability's and campbell's (hunt 28: it had no mark), the
        // CLI's SVG (`plot`) and the figure of `figures` alike
        for title in [o.plot().title, o.figures().unwrap()[0].plot.title.clone()] {
            assert_eq!(title, "INCOMPLETE: Where the balls end, by their initial angles");
        }
        let table = o.table().unwrap();
        assert!(table.lines().next().unwrap().ends_with("; wrote b.csv"), "{table}");
        // the share is of the runs completed, named as such (hunt 27)
        let balanced = o.ends.iter().flatten().filter(|e| e.balanced).count();
        assert!(
            table.starts_with(&format!("{balanced} of the {done} runs completed balanced (")) && table.contains(&format!("; interrupted: {done} of 4 runs)")),
            "{table}"
        );
        // each run's end at the config's tolerance, said (issue 18 item 4; audit 25)
        assert!(table.lines().nth(1).unwrap().starts_with("tolerance: each run's end is that at rtol 1e-8, none checked"), "{table}");
        assert_eq!(o.json().unwrap()["tolerance_check"]["checked"], json!(false));
    }
}
