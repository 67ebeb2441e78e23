//! `autobal map`: stability margin over two parameters (Ω and/or config fields), in parallel,
//! with a progress bar, written as CSV (row by row, so an interrupted run keeps what it has
//! computed), SVG and PNG.

use crate::config::{self, Config};
use anyhow::{anyhow, bail, Context, Result};
use autobal::spatial::linear_model::Balls;
use autobal::spatial::linear_model::StateSpace;
use autobal::spatial::stability::{counts_as_stable, margin_at, strictly_stable_at};
use rayon::prelude::*;
use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use toml::Table;

/// Set by Ctrl-C: rows not yet started are skipped, rows written so far are kept.
pub static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// One axis: `key=lo:hi:n`, key `omega` or a config field.
#[derive(Debug, Clone)]
pub struct Axis {
    pub key: String,
    pub lo: f64,
    pub hi: f64,
    pub n: usize,
}

impl Axis {
    pub fn parse(flag: &str, spec: &str) -> Result<Self> {
        let (key, range) = spec.split_once('=').ok_or_else(|| anyhow!("{flag} {spec}: expected KEY=LO:HI:N, e.g. {flag} omega=0.1:6:400"))?;
        let parts: Vec<&str> = range.split(':').collect();
        if parts.len() != 3 {
            bail!("{flag} {spec}: expected KEY=LO:HI:N");
        }
        let num = |s: &str, what: &str| -> Result<f64> {
            let v: f64 = s.trim().parse().map_err(|_| anyhow!("{flag} {spec}: {what} `{s}` is not a number"))?;
            if !v.is_finite() {
                bail!("{flag} {spec}: {what} must be finite");
            }
            Ok(v)
        };
        let (lo, hi) = (num(parts[0], "LO")?, num(parts[1], "HI")?);
        let n: usize = parts[2].trim().parse().map_err(|_| anyhow!("{flag} {spec}: N `{}` is not a whole number", parts[2]))?;
        if !(2..=5000).contains(&n) {
            bail!("{flag} {spec}: N must lie between 2 and 5000, got {n}");
        }
        if hi <= lo {
            bail!("{flag} {spec}: HI must exceed LO");
        }
        let key = key.trim().to_string();
        if key == "omega" && lo < 0.0 {
            bail!("{flag} {spec}: the speed Ω must not be negative");
        }
        Ok(Axis { key, lo, hi, n })
    }
    /// The `i`-th grid value, rounded to 12 significant digits so that printed values read as
    /// typed (0.4, not 0.39999999999999997); the ends are exact.
    pub fn value(&self, i: usize) -> f64 {
        if i + 1 >= self.n {
            return self.hi;
        }
        let v = self.lo + (self.hi - self.lo) * i as f64 / (self.n - 1) as f64;
        if v == 0.0 {
            return 0.0;
        }
        let mag = 10f64.powi(11 - v.abs().log10().floor() as i32);
        (v * mag).round() / mag
    }
    fn is_omega(&self) -> bool {
        self.key == "omega"
    }
}

/// What each point stores.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Spectral abscissa from the eigenvalues (default).
    Margin,
    /// Routh–Hurwitz verdict only (faster; no margin).
    Verdict,
}

#[derive(Debug, Clone, Copy)]
pub struct Cell {
    pub margin: f64,
    pub stable: bool,
    pub necessary: bool,
}

pub struct MapResult {
    pub x: Axis,
    pub y: Axis,
    /// `rows[j][i]` at `(x_i, y_j)`; `None` for rows skipped by an interruption.
    pub rows: Vec<Option<Vec<Cell>>>,
    pub quantity: Quantity,
}

struct Point<'a> {
    base: &'a Table,
    source: &'a str,
    x: &'a Axis,
    y: &'a Axis,

}

impl Point<'_> {
    fn config(&self, xv: Option<f64>, yv: f64) -> Result<Config> {
        let mut t = self.base.clone();
        if let Some(xv) = xv {
            config::set_number(&mut t, &self.x.key, xv)?;
        }
        if !self.y.is_omega() {
            config::set_number(&mut t, &self.y.key, yv)?;
        }
        config::build(&t, self.source).with_context(|| format!("at {} = {}", self.y.key, yv))
    }
}

fn cell(ss: &StateSpace, nec: &[autobal::spatial::ranges::SpeedRange], omega: f64, q: Quantity, balls: Balls) -> Result<Cell> {
    let necessary = nec.iter().any(|r| r.contains(omega));
    Ok(match q {
        Quantity::Margin => {
            let a = margin_at(ss, omega)?;
            Cell { margin: a, stable: counts_as_stable(a, balls), necessary }
        }
        Quantity::Verdict => Cell { margin: f64::NAN, stable: strictly_stable_at(ss, omega), necessary },
    })
}

/// Compute the map; each finished row is appended to `csv` at once.
#[allow(clippy::too_many_arguments)]
pub fn compute(
    base: &Table,
    source: &str,
    x: Axis,
    y: Axis,
    omega: Option<f64>,
    balls: Balls,
    quantity: Quantity,
    csv: &mut (dyn Write + Send),
    progress: bool,
) -> Result<MapResult> {
    for a in [&x, &y] {
        if !a.is_omega() {
            let mut t = base.clone();
            config::set_number(&mut t, &a.key, a.lo).map_err(|e| anyhow!("--{}: {e:#}", if std::ptr::eq(a, &x) { "x" } else { "y" }))?;
        }
    }
    if x.is_omega() && y.is_omega() {
        bail!("--x, --y: only one axis can be omega");
    }
    if !x.is_omega() && !y.is_omega() && omega.is_none() {
        bail!("--omega: required when neither axis is omega (the speed at which to map)");
    }
    writeln!(csv, "{},{},max_real_part,stable,necessary", x.key, y.key)?;
    let pt = Point { base, source, x: &x, y: &y };
    // fail early on a bad base config
    pt.config(if x.is_omega() { None } else { Some(x.lo) }, y.lo)?;
    let bar = if progress {
        let b = indicatif::ProgressBar::new(y.n as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} rows  {elapsed_precise} (eta {eta})")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        Some(b)
    } else {
        None
    };
    let sink = Mutex::new(csv);
    // one model per value of the non-Ω axis, built once (the Ω axis reuses it)
    type Built = (StateSpace, Vec<autobal::spatial::ranges::SpeedRange>);
    let build = |xv: Option<f64>, yv: f64| -> Result<Built> {
        let c = pt.config(xv, yv)?;
        let nec = autobal::spatial::ranges::autobalancing_ranges(&c.model).ranges;
        Ok((StateSpace::new(&c.model, balls)?, nec))
    };
    let columns: Vec<Built> = if y.is_omega() {
        (0..x.n).into_par_iter().map(|i| build(Some(x.value(i)), y.lo)).collect::<Result<_>>()?
    } else {
        vec![]
    };
    let rows: Vec<Result<Option<Vec<Cell>>>> = (0..y.n)
        .into_par_iter()
        .map(|j| {
            if INTERRUPTED.load(Ordering::Relaxed) {
                return Ok(None);
            }
            let yv = y.value(j);
            let row: Option<Built> = if x.is_omega() { Some(build(None, yv)?) } else { None };
            let mut cells = Vec::with_capacity(x.n);
            for i in 0..x.n {
                let xv = x.value(i);
                let c = if let Some((c, nec)) = &row {
                    cell(c, nec, xv.max(1e-9), quantity, balls)?
                } else if let Some((c, nec)) = columns.get(i) {
                    cell(c, nec, yv.max(1e-9), quantity, balls)?
                } else {
                    let (c, nec) = build(Some(xv), yv)?;
                    cell(&c, &nec, omega.unwrap_or(1.0).max(1e-9), quantity, balls)?
                };
                cells.push(c);
            }
            {
                let mut out = sink.lock().map_err(|_| anyhow!("CSV writer poisoned"))?;
                let mut text = String::with_capacity(cells.len() * 48);
                for (i, c) in cells.iter().enumerate() {
                    text.push_str(&format!("{},{},{},{},{}\n", x.value(i), yv, c.margin, c.stable as u8, c.necessary as u8));
                }
                out.write_all(text.as_bytes())?;
                out.flush()?;
            }
            if let Some(b) = &bar {
                b.inc(1);
            }
            Ok(Some(cells))
        })
        .collect();
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let rows = rows.into_iter().collect::<Result<Vec<_>>>()?;
    Ok(MapResult { x, y, rows, quantity })
}

/// Write `<stem>.svg` and `<stem>.png` (drawn by `mapfig`).
pub fn write_plots(r: &MapResult, stem: &Path, title: &str) -> Result<()> {
    crate::mapfig::write_plots(r, stem, title)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_values_read_as_typed() {
        let a = Axis::parse("--x", "planar.c_psi=0.01:0.4:4").unwrap();
        let v: Vec<f64> = (0..4).map(|i| a.value(i)).collect();
        assert_eq!(v, vec![0.01, 0.14, 0.27, 0.4]);
        let a = Axis::parse("--x", "omega=0:6:401").unwrap();
        assert_eq!(a.value(0), 0.0);
        assert!((a.value(123) - 6.0 * 123.0 / 400.0).abs() < 1e-11);
    }

    #[test]
    fn bad_axis_specs_are_rejected_with_the_flag() {
        for spec in ["omega", "omega=1:2", "omega=2:1:5", "omega=0:1:1", "omega=a:1:3", "omega=-1:1:3", "x=0:1:9999999"] {
            let e = Axis::parse("--y", spec).unwrap_err().to_string();
            assert!(e.starts_with("--y"), "{e}");
        }
    }
}
