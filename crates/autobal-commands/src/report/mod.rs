//! The HTML report: one self-contained folder (`index.html`, the vendored plotting library,
//! every figure as SVG and PNG), readable offline.
//!
//! Two reports: about the user's rotor ([`Kind::User`], `--config`: [`USER_SECTIONS`], with a
//! summary at the top) and the papers' reproductions ([`Kind::Papers`], `--papers` and the
//! default without `--config`: [`PAPER_SECTIONS`]). Each section is a module with one function
//! `build(&Ctx) -> Result<Option<Section>>`; a section that does not apply returns
//! [`Section::not_applicable`] with the reason in one line (shown on the page and in the
//! progress). Sections run in parallel and report their progress one line each; adding a
//! section is adding a module and one line to a list.
//!
//! Every figure is a [`Plot`]: the page embeds its data as Plotly JSON and draws it
//! interactively with the vendored Plotly (zoom, hover values, curves toggled in the legend);
//! the static SVG (also the page's fallback when scripts are off) and a PNG rasterised from it
//! are written beside.
//!
//! A Ctrl-C stops the long computations; the page is still written, says which sections are
//! incomplete, and the command exits with an error. A stopped report never replaces a complete
//! one: where `--out` holds one, it goes to `--out/incomplete/` ([`INCOMPLETE_FOLDER`]). A
//! report that replaces an earlier one removes the earlier figures it does not write.

mod basins;
mod design;
mod friction;
mod html;
mod linear_rotor;
mod paper000;
mod paper003;
mod paper004;
mod paper004_torque;
mod passage;
mod rotor;
mod spatial_run;
mod stability;

use crate::command::{self, ConfigSource};
use crate::config::{self, Config, PlanarConfig};
use crate::plot::Plot;
use anyhow::{bail, Context, Result};
use html::esc;
use rayon::prelude::*;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// Plotly (cartesian bundle, minified), vendored: see `assets/README.md`.
const PLOTLY_JS: &str = include_str!("../../assets/plotly-cartesian.min.js");
const PLOTLY_LICENSE: &str = include_str!("../../assets/plotly-LICENSE.txt");
/// The page's own script: draws each figure from its embedded JSON.
const REPORT_JS: &str = include_str!("../../assets/report.js");
const REPORT_CSS: &str = include_str!("../../assets/report.css");

/// Which report: about the config's rotor, or the papers' reproductions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// The config's rotor only ([`USER_SECTIONS`]).
    User,
    /// The papers' figures with their own parameters ([`PAPER_SECTIONS`]).
    Papers,
}

/// What the sections analyse.
pub struct Ctx {
    /// Which report is written.
    pub kind: Kind,
    /// The config's spatial rotor (papers 000/003 model), if it describes one.
    pub spatial: Option<Config>,
    /// The config's planar rotor (paper 004 model), if it has `[planar]`.
    pub planar: Option<PlanarConfig>,
    /// The config's linear rotor, if it has `[linear_rotor]` ([`LINEAR_SECTIONS`]).
    pub linear: Option<autobal::linear_rotor::config::LinearRotorConfig>,
    /// Shorter simulations (tests, a first look).
    pub quick: bool,
    /// The config file's name and the `--set` overrides, for the page.
    pub source: String,
    /// The merged config text.
    pub text: String,
    /// The config as a table (the overrides applied), for runs derived from it.
    pub root: toml::Table,
    /// What every section's long computations run under (the front end's Ctrl-C flag).
    pub control: autobal::control::Control,
}

/// A figure of the report.
pub struct Figure {
    /// File stem and HTML anchor (`fig000_5a_critical_vs_c_sigma`).
    pub id: String,
    pub plot: Plot,
    /// HTML (already escaped where needed).
    pub caption: String,
}

/// A piece of a section: HTML, a subsection heading (listed in the contents) or a figure.
pub enum Block {
    Html(String),
    Heading { id: String, title: String },
    Figure(Box<Figure>),
}

/// One section of the report.
pub struct Section {
    pub id: &'static str,
    pub title: String,
    pub blocks: Vec<Block>,
    /// False when an interruption cut the section short.
    pub complete: bool,
    /// What failed in a complete section (one line: a run whose integrator could not reach its
    /// end), said in the progress line instead of "done"; the section says why.
    pub failed: Option<String>,
    /// Why the section does not apply to this config (one line), if it does not.
    pub not_applicable: Option<String>,
    /// Lines (HTML) for the summary at the top of the page, in section order.
    pub summary: Vec<String>,
}

impl Section {
    pub fn new(id: &'static str, title: impl Into<String>) -> Self {
        Section { id, title: title.into(), blocks: vec![], complete: true, failed: None, not_applicable: None, summary: vec![] }
    }
    /// A section that does not apply, with the reason in one line (plain text).
    pub fn not_applicable(id: &'static str, title: impl Into<String>, why: impl Into<String>) -> Self {
        let why = why.into();
        let mut s = Section::new(id, title);
        s.p(format!("Not applicable: {}.", esc(&why)));
        s.not_applicable = Some(why);
        s
    }
    /// Raw HTML.
    pub fn html(&mut self, s: impl Into<String>) {
        self.blocks.push(Block::Html(s.into()));
    }
    /// A paragraph of HTML.
    pub fn p(&mut self, s: impl AsRef<str>) {
        self.html(format!("<p>{}</p>\n", s.as_ref()));
    }
    /// A subsection heading, listed in the table of contents.
    pub fn h3(&mut self, id: impl Into<String>, title: impl Into<String>) {
        self.blocks.push(Block::Heading { id: id.into(), title: title.into() });
    }
    /// A table with a unit in every column head.
    pub fn table(&mut self, head: &[&str], rows: &[Vec<String>]) {
        self.html(html::table(head, rows));
    }
    pub fn figure(&mut self, id: impl Into<String>, plot: Plot, caption: impl Into<String>) {
        self.blocks.push(Block::Figure(Box::new(Figure { id: id.into(), plot, caption: caption.into() })));
    }
    pub fn figures(&self) -> impl Iterator<Item = &Figure> {
        self.blocks.iter().filter_map(|b| if let Block::Figure(f) = b { Some(&**f) } else { None })
    }
}

type Builder = fn(&Ctx) -> Result<Option<Section>>;

/// The report about the config's rotor, in page order. Each is one module.
pub const USER_SECTIONS: &[(&str, Builder)] = &[
    ("your rotor", rotor::build),
    ("stability over speed", stability::build_user),
    ("design maps", design::build),
    ("run-up", spatial_run::build),
    ("the rotor's passage", passage::build),
    ("the balls' basins", basins::build),
];

/// The report about a linear rotor config (`[linear_rotor]`).
pub const LINEAR_SECTIONS: &[(&str, Builder)] = &[("your linear rotor", linear_rotor::build)];

/// The papers' reproductions, in page order (the exact stability of paper 000's base case,
/// the embedded default example, with 003's maps beside the papers' own figures).
pub const PAPER_SECTIONS: &[(&str, Builder)] = &[
    ("paper 000", paper000::build),
    ("paper 003", paper003::build),
    ("exact stability of the base case", stability::build),
    ("paper 004", paper004::build),
    ("paper 004, torque", paper004_torque::build),
    ("rolling resistance", friction::build),
];

/// `autobal report`'s arguments (`Default`: the CLI's defaults).
#[derive(Debug, Clone)]
pub struct Args {
    /// The config; [`ConfigSource::File`] without a path (no `--config`): the papers' report.
    pub config: ConfigSource,
    /// The folder written (created if missing).
    pub out: PathBuf,
    /// Shorter runs in time.
    pub quick: bool,
    /// The papers' reproductions instead of a report about the config's rotor.
    pub papers: bool,
}

impl Default for Args {
    fn default() -> Self {
        Args { config: ConfigSource::default(), out: PathBuf::from("autobal-report"), quick: false, papers: false }
    }
}

impl Args {
    /// Which report: the papers' with `papers` or without a config.
    pub fn kind(&self) -> Kind {
        match self.papers || matches!(&self.config, ConfigSource::File { path: None, .. }) {
            true => Kind::Papers,
            false => Kind::User,
        }
    }
}

/// The report written: its `index.html`, and why it is incomplete where it is.
pub struct Output {
    /// The page.
    pub index: PathBuf,
    /// Sections and figures on the page.
    pub sections: usize,
    pub figures: usize,
    /// Why the page is incomplete (Ctrl-C), or `None`.
    pub incomplete: Option<String>,
    /// What failed in a section that is otherwise complete (a run-up whose integrator could not
    /// reach its end), or `None`: the page is written and says why, and the command exits 2
    /// so that a script sees it (review 23: exit 0 hid it; `simulate` exits 2 on the same run).
    pub failed: Option<String>,
}

impl command::Command for Args {
    const NAME: &'static str = "report";
    type Output = Output;

    /// Check the folder (created and checked before any section runs), read the config once,
    /// build every section in parallel under `control`, write the folder (also when
    /// interrupted: the page says which sections were cut short).
    fn run(&self, control: &autobal::control::Control) -> Result<Output> {
        crate::outfile::Outputs::new().source_inputs(&self.config).output("--out", &self.out.join("index.html")).check()?;
        check_inputs_outside(&self.out, &self.config)?;
        check_folder(&self.out)?;
        let ctx = context(&self.config, self.quick, self.kind(), control)?;
        write(&ctx, &self.out)
    }
}

impl command::Output for Output {
    fn json(&self) -> Result<serde_json::Value> {
        Ok(
            serde_json::json!({"index": self.index.display().to_string(), "sections": self.sections, "figures": self.figures, "complete": self.incomplete.is_none(), "failed": self.failed}),
        )
    }
    fn table(&self) -> Result<String> {
        Ok(format!("report written to {}\n", self.index.display()))
    }
    fn stopped(&self) -> Option<String> {
        self.incomplete.clone().or_else(|| self.failed.clone())
    }
}

/// Read the config (spatial and/or planar, or a linear rotor) once and check its entries: what
/// the sections analyse.
fn context(cs: &ConfigSource, quick: bool, kind: Kind, control: &autobal::control::Control) -> Result<Ctx> {
    // a linear rotor config reads its `--set`s and matrix files its own way
    let (root, source) = cs.read_any()?;
    let linear = match crate::linear_rotor::is_linear(&root) {
        true => Some(crate::linear_rotor::from_table(&root, cs.dir())?),
        false => None,
    };
    let spatial = if autobal::config::is_spatial(&root) { Some(config::build(&root, &source)?) } else { None };
    let planar = if root.contains_key("planar") { Some(config::build_planar(&root, &source)?) } else { None };
    if spatial.is_none() && planar.is_none() && linear.is_none() {
        bail!("config: describes no rotor: give [dimensionless] or [rotor], [supports], [unbalance], [balancer] (papers 000/003), or [planar] (paper 004), or [linear_rotor] (your own rotor-bearing model)");
    }
    // the linear sections, the spatial simulation's (stability by the general route, run-up),
    // the planar rotor's
    let mut models = vec![];
    if spatial.is_some() {
        models.extend([config::Model::Linear, config::Model::Spatial]);
    }
    if planar.is_some() {
        models.push(config::Model::Planar);
    }
    if linear.is_none() {
        config::check_entries(&root, "report", &models)?;
    }
    // the comparison with eq (17) stays in the report's inertia section (and `inertia`)
    for w in spatial.iter().flat_map(|c| autobal::reports::actionable_warnings(&c.model.anisotropy)) {
        crate::term::note(&format!("warning: {w}"));
    }
    let mut source_line = source.clone();
    if let ConfigSource::File { sets, .. } = cs {
        for s in sets {
            source_line.push_str(&format!(" --set {s}"));
        }
    }
    Ok(Ctx { kind, spatial, planar, linear, quick, source: source_line, text: toml::to_string(&root).unwrap_or_default(), root, control: control.clone() })
}

/// Build every section and write the folder (also when interrupted: the page says which
/// sections were cut short, and the output why).
pub fn write(ctx: &Ctx, dir: &Path) -> Result<Output> {
    let existed = dir.is_dir();
    std::fs::create_dir_all(dir).with_context(|| format!("--out {}: cannot create the folder", dir.display()))?;
    let written = write_in(ctx, dir);
    if written.is_err() && !existed {
        // (only when empty: the folder this run made, nothing of the user's)
        let _ = std::fs::remove_dir(dir);
    }
    written
}

/// [`write`] into the folder `dir`, which exists: every file is built in memory and written
/// all or none ([`crate::outfile::write_all_or_none`], `index.html` last), so that a full disk
/// or a failed figure leaves a previous report in `dir` as it was, not its page beside some of
/// the new figures.
fn write_in(ctx: &Ctx, dir: &Path) -> Result<Output> {
    let t0 = Instant::now();
    let done = AtomicUsize::new(0);
    let list = match ctx.kind {
        Kind::User if ctx.linear.is_some() => LINEAR_SECTIONS,
        Kind::User => USER_SECTIONS,
        Kind::Papers => PAPER_SECTIONS,
    };
    let n = list.len();
    crate::term::note(&format!(
        "report: {} with {n} sections on {} threads{}",
        if ctx.kind == Kind::User { "about the config's rotor" } else { "the papers' reproductions" },
        rayon::current_num_threads(),
        if ctx.quick { " (quick)" } else { "" }
    ));
    let built: Vec<Result<Option<Section>>> = list
        .par_iter()
        .map(|(name, build)| {
            let t = Instant::now();
            let r = build(ctx).or_else(|e| no_linearisation(name, e)).with_context(|| format!("report section {name}"));
            let k = done.fetch_add(1, Ordering::Relaxed) + 1;
            let what = match &r {
                Ok(Some(s)) if !s.complete => "interrupted".to_string(),
                Ok(Some(Section { not_applicable: Some(why), .. })) => format!("not applicable ({why})"),
                Ok(Some(Section { failed: Some(what), .. })) => format!("done, but {what}"),
                Ok(Some(_)) => "done".to_string(),
                Ok(None) => "not applicable".to_string(),
                Err(_) => "failed".to_string(),
            };
            crate::term::note(&format!("report: [{k}/{n}] {name}: {what} in {:.1} s", t.elapsed().as_secs_f64()));
            r
        })
        .collect();
    let sections: Vec<Section> = built.into_iter().collect::<Result<Vec<_>>>()?.into_iter().flatten().collect();
    write_sections(ctx, dir, &sections, t0)
}

/// Write the report of `sections` (built from `t0` on) into the folder `dir` ([`write_in`]).
fn write_sections(ctx: &Ctx, dir: &Path, sections: &[Section], t0: Instant) -> Result<Output> {
    let compute_s = t0.elapsed().as_secs_f64();
    for line in summary_lines(sections) {
        crate::term::note(&format!("report: summary: {}", html::strip(line)));
    }
    // what was cut short is what the sections say: figures and the page never ask the control,
    // so a stop that came after the last section (while the figures were rendered) leaves every
    // file complete (review 24c: it said "incomplete (stopped while writing)")
    let incomplete: Vec<&str> = sections.iter().filter(|s| !s.complete).map(|s| s.title.as_str()).collect();
    let interrupted = !incomplete.is_empty();
    // a stopped run never replaces a complete report (`simulate`'s stopped CSV does, a file of
    // its complete rows; a report's page is many files): it goes to `DIR/incomplete/`, the
    // complete one left byte for byte (review 24c: the incomplete page replaced it)
    let kept = interrupted && holds_complete_report(dir);
    let out_dir = if kept { dir.join(INCOMPLETE_FOLDER) } else { dir.to_path_buf() };
    if kept {
        if out_dir.exists() && !out_dir.is_dir() {
            bail!(
                "--out {}: is not a folder; a stopped report goes there when {} holds a complete one (which is left as it was): move it away",
                out_dir.display(),
                dir.display()
            );
        }
        check_folder(&out_dir)?;
    }
    // the page in the folder written to, if it is autobal's: read once
    let before = report_page(&out_dir);
    let previous = before.as_deref().map_or(vec![], |p| figure_files(&out_dir, p));
    // figure files, in parallel (rasterising is the slow part)
    let figs: Vec<&Figure> = sections.iter().flat_map(|s| s.figures()).collect();
    let mut files: Vec<(PathBuf, Vec<u8>)> = figs
        .par_iter()
        .map(|f| -> Result<[(PathBuf, Vec<u8>); 2]> {
            let svg = f.plot.to_svg();
            let png = crate::plot::svg_to_png(&svg, 1.5)?;
            Ok([(out_dir.join(format!("{}.svg", f.id)), svg.into_bytes()), (out_dir.join(format!("{}.png", f.id)), png)])
        })
        .collect::<Result<Vec<_>>>()?
        .into_iter()
        .flatten()
        .collect();
    for (name, text) in ASSETS.into_iter().zip([PLOTLY_JS, PLOTLY_LICENSE, REPORT_JS]) {
        files.push((out_dir.join(name), text.as_bytes().to_vec()));
    }
    // a folder with no report page: no file of the user's is replaced by a figure of the same
    // name (review 26a: `ID.png` of the user's was overwritten)
    if before.is_none() {
        if let Some((p, _)) = files.iter().find(|(p, _)| p.exists()) {
            bail!(
                "--out {}: holds a file {} that no autobal report page links, which the report would replace: give a new or empty folder",
                out_dir.display(),
                p.display()
            );
        }
    }
    let page = page(ctx, sections, interrupted, &incomplete, t0.elapsed().as_secs_f64());
    let index = out_dir.join("index.html");
    files.push((index.clone(), page.into_bytes()));
    crate::outfile::write_all_or_none("--out", &files)?;
    remove_stale(&previous, &files);
    if !interrupted {
        remove_stopped_report(&dir.join(INCOMPLETE_FOLDER));
    }
    if !interrupted && ctx.control.should_stop().is_some() {
        crate::term::note("report: the stop came after every section had completed: the report is complete");
    }
    crate::term::note(&format!(
        "report: {} sections, {} figures in {:.1} s (computing {:.1} s, figures {:.1} s)",
        sections.len(),
        figs.len(),
        t0.elapsed().as_secs_f64(),
        compute_s,
        t0.elapsed().as_secs_f64() - compute_s
    ));
    let incomplete = interrupted.then(|| {
        let kept = if kept { format!("; the complete report in {} is left as it was", dir.join("index.html").display()) } else { String::new() };
        format!("interrupted: the report in {} is incomplete ({}){kept}", index.display(), incomplete.join(", "))
    });
    let failed: Vec<String> = sections.iter().filter_map(|s| s.failed.as_ref().map(|w| format!("in its section \"{}\" {w}", s.title))).collect();
    let failed = (!failed.is_empty()).then(|| format!("the report in {} is written, but {} (its section says why)", index.display(), failed.join("; ")));
    Ok(Output { index, sections: sections.len(), figures: figs.len(), incomplete, failed })
}

/// The opening of an incomplete page's warning ([`page`]).
const INTERRUPTED_DIV: &str = "<div class=\"warn\" id=\"interrupted\">";

/// Where a stopped report goes when `--out` holds a complete report (its page without the
/// interruption's warning): the complete one is left as it was.
pub const INCOMPLETE_FOLDER: &str = "incomplete";

/// Whether `dir` holds a complete report of autobal: its `index.html` is a report's page
/// without the interruption's warning.
fn holds_complete_report(dir: &Path) -> bool {
    report_page(dir).is_some_and(|p| !p.contains(INTERRUPTED_DIV))
}

/// The `index.html` of `dir` if it is a report's page of autobal (any version's: its title).
fn report_page(dir: &Path) -> Option<String> {
    std::fs::read_to_string(dir.join("index.html")).ok().filter(|p| p.contains("<title>autobal report"))
}

/// The files a report writes whatever its sections (beside `index.html` and the figures).
const ASSETS: [&str; 3] = ["plotly-cartesian.min.js", "plotly-LICENSE.txt", "report.js"];

/// Refuse a folder that holds files of the user's own where the report would write: an
/// `index.html` that is not a report's page of autobal, or, with no page at all, a file named as
/// one of the report's [`ASSETS`] (review 25a: a user's own `index.html` in `--out` was
/// replaced). Checked before any section runs; a folder holding autobal's report is the
/// report's to replace.
fn check_folder(dir: &Path) -> Result<()> {
    if dir.join("index.html").exists() {
        if report_page(dir).is_none() {
            bail!("--out {}: holds an index.html that is not an autobal report, which the report would replace: give a new or empty folder", dir.display());
        }
        return Ok(());
    }
    if let Some(a) = ASSETS.iter().find(|a| dir.join(a).exists()) {
        bail!("--out {}: holds a file {a} that no autobal report page links, which the report would replace: give a new or empty folder", dir.display());
    }
    Ok(())
}

/// Refuse an input of the run (the config file, the files a linear rotor config names) that
/// lies in `dir` or its stopped report's folder under a name the report writes or removes
/// there: `index.html`, one of the [`ASSETS`], a figure's `.svg` or `.png` (hunt 27: `--config
/// rep/stability_margin.svg --out rep` overwrote the config, `rep/basins.svg` was removed as a
/// stale figure). Checked before any section runs; any other name is safe there.
fn check_inputs_outside(dir: &Path, config: &command::ConfigSource) -> Result<()> {
    let mut inputs: Vec<PathBuf> = config.path().map(Path::to_path_buf).into_iter().collect();
    if let Ok((root, _)) = config.read_any() {
        inputs.extend(autobal::linear_rotor::config::file_names(&root).into_iter().map(|(_, name)| config.dir().join(name)));
    }
    let folders: Vec<PathBuf> = [dir.to_path_buf(), dir.join(INCOMPLETE_FOLDER)].iter().filter_map(|d| std::fs::canonicalize(d).ok()).collect();
    for f in &inputs {
        let (Some(name), Some(parent)) = (f.file_name().and_then(|n| n.to_str()), f.parent()) else { continue };
        let parent = if parent.as_os_str().is_empty() { Path::new(".") } else { parent };
        let Ok(parent) = std::fs::canonicalize(parent) else { continue };
        let ours = name == "index.html" || ASSETS.contains(&name) || name.ends_with(".svg") || name.ends_with(".png");
        if ours && folders.contains(&parent) {
            bail!(
                "--out {}: holds the run's input {}, under a name the report writes or removes there: give another folder, or keep the input elsewhere",
                dir.display(),
                f.display()
            );
        }
    }
    Ok(())
}

/// Remove the stopped report that an earlier run left in `dir` (`--out/incomplete/`) once a
/// complete report is written beside it: its page, the figures it links and the [`ASSETS`],
/// then the folder if nothing else is left in it (review 25a: the stale stopped page stayed
/// after a complete rerun). Nothing that is not a report's file is removed.
fn remove_stopped_report(dir: &Path) {
    // a real folder (not a link to another), holding a stopped report's page (not a complete
    // one a user wrote there with `--out DIR/incomplete`): review 26a
    if !std::fs::symlink_metadata(dir).is_ok_and(|m| m.is_dir()) {
        return;
    }
    let Some(page) = report_page(dir).filter(|p| p.contains(INTERRUPTED_DIV)) else { return };
    let mut ours = figure_files(dir, &page);
    ours.extend(ASSETS.iter().map(|a| dir.join(a)));
    ours.push(dir.join("index.html"));
    for p in &ours {
        let _ = std::fs::remove_file(p);
    }
    if std::fs::remove_dir(dir).is_ok() {
        crate::term::note(&format!("report: removed the earlier stopped report in {}", dir.display()));
    }
}

/// The figure files (`ID.svg`, `ID.png`) in `dir` that its report page `page` links
/// ([`report_page`]): read before a new report replaces the page, so that those the new one
/// does not write can be removed ([`remove_stale`]). Only names made of the report's figure
/// ids' characters.
fn figure_files(dir: &Path, page: &str) -> Vec<PathBuf> {
    page.split("data-fig=\"")
        .skip(1)
        .filter_map(|rest| rest.split_once('"').map(|(id, _)| id))
        .filter(|id| !id.is_empty() && id.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-'))
        .flat_map(|id| [dir.join(format!("{id}.svg")), dir.join(format!("{id}.png"))])
        .collect()
}

/// Remove the previous report's figure files (`previous`) that the report just written
/// (`written`) does not have: a figure of an earlier run, linked by no page, would read as
/// this run's (review 24c: a stopped rerun left the earlier Campbell diagrams).
fn remove_stale(previous: &[PathBuf], written: &[(PathBuf, Vec<u8>)]) {
    for p in previous {
        if !written.iter().any(|(w, _)| w == p) {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// A section whose analysis needs the linearisation of a stationary state the config's rotor
/// does not have (real balls: `autobal::Error::NoLinearisation`) says so in one line instead
/// of failing the report; any other error stays an error.
fn no_linearisation(name: &str, e: anyhow::Error) -> Result<Option<Section>> {
    let why = e.chain().find_map(|c| match (c.downcast_ref::<autobal::Error>(), c.downcast_ref::<autobal::analysis::AnalysisError>()) {
        (Some(l @ autobal::Error::NoLinearisation { .. }), _)
        | (_, Some(autobal::analysis::AnalysisError::Model(l @ autobal::Error::NoLinearisation { .. }))) => Some(l.to_string()),
        // carried as text by a layer that formats its errors (the typed error's message)
        _ => {
            let m = c.to_string();
            m.find("no linearisation: ").map(|i| m[i..].to_string())
        }
    });
    let Some(why) = why else { return Err(e) };
    let id = match name {
        "your rotor" => "rotor",
        "stability over speed" => "stability",
        "design maps" => "design",
        _ => "no-linearisation",
    };
    let mut title = name.to_string();
    title[..1].make_ascii_uppercase();
    Ok(Some(Section::not_applicable(id, title, why)))
}

/// The summary's lines: the verdict at the operating speed (section `stability`) first, then
/// the others in page order.
fn summary_lines(sections: &[Section]) -> impl Iterator<Item = &String> {
    let first = sections.iter().filter(|s| s.id == "stability");
    first.chain(sections.iter().filter(|s| s.id != "stability")).flat_map(|s| &s.summary)
}

/// Assemble `index.html`.
fn page(ctx: &Ctx, sections: &[Section], interrupted: bool, incomplete: &[&str], secs: f64) -> String {
    let mut h = String::new();
    let title = match ctx.kind {
        Kind::User => "autobal report: your rotor",
        Kind::Papers => "autobal report: the papers' reproductions",
    };
    let _ = write!(
        h,
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{title}</title>\n<style>\n{REPORT_CSS}</style>\n</head><body>\n<header><h1>{title}</h1>\n"
    );
    let _ = writeln!(
        h,
        "<p class=\"meta\">Config: <code>{}</code> · autobal {} · computed in {} s. Figures: drag to zoom, double-click to reset, hover to read values, click a legend entry to hide or show a curve; each figure also as SVG and PNG (links under it).</p>",
        esc(&ctx.source),
        env!("CARGO_PKG_VERSION"),
        crate::num::fmt(secs, 2)
    );
    if interrupted {
        let _ = writeln!(
            h,
            "{INTERRUPTED_DIV}<b>Interrupted.</b> This report is incomplete: sections cut short: {}. Numbers of runs cut short are marked as such.</div>",
            esc(&incomplete.join(", "))
        );
    }
    match ctx.kind {
        Kind::User => {
            h.push_str("<div id=\"summary\" class=\"summary\"><h2>Summary</h2>\n<ul>\n");
            for line in summary_lines(sections) {
                let _ = writeln!(h, "<li>{line}</li>");
            }
            h.push_str("</ul>\n<p>The papers' reproductions are a report of their own: <code>autobal report --papers</code>.</p></div>\n");
        }
        Kind::Papers => h.push_str(
            "<p class=\"meta\">The papers' figures, each with the parameters the paper states (whatever the config). A report about your own rotor: <code>autobal report --config FILE</code>.</p>\n",
        ),
    }
    h.push_str("</header>\n");
    // contents
    h.push_str("<nav id=\"toc\"><h2>Contents</h2>\n<ol>\n");
    let mut fig_no = 0;
    for s in sections {
        let _ = write!(h, "<li><a href=\"#{}\">{}</a>", s.id, esc(&s.title));
        let subs: Vec<&Block> = s.blocks.iter().filter(|b| matches!(b, Block::Heading { .. } | Block::Figure(_))).collect();
        if !subs.is_empty() {
            h.push_str("<ol>");
            for b in subs {
                match b {
                    Block::Heading { id, title } => {
                        let _ = write!(h, "<li><a href=\"#{id}\">{}</a></li>", esc(title));
                    }
                    Block::Figure(f) => {
                        fig_no += 1;
                        let _ = write!(h, "<li class=\"figlink\"><a href=\"#{}\">Figure {fig_no}: {}</a></li>", f.id, esc(&f.plot.title));
                    }
                    Block::Html(_) => {}
                }
            }
            h.push_str("</ol>");
        }
        h.push_str("</li>\n");
    }
    h.push_str("<li><a href=\"#config\">Config as used</a></li>\n</ol></nav>\n<main>\n");
    let mut fig_no = 0;
    for s in sections {
        let _ = writeln!(h, "<section id=\"{}\"><h2>{}</h2>", s.id, esc(&s.title));
        if !s.complete {
            h.push_str("<div class=\"warn\">This section was cut short by an interruption.</div>\n");
        }
        for b in &s.blocks {
            match b {
                Block::Html(x) => h.push_str(x),
                Block::Heading { id, title } => {
                    let _ = writeln!(h, "<h3 id=\"{id}\">{}</h3>", esc(title));
                }
                Block::Figure(f) => {
                    fig_no += 1;
                    h.push_str(&figure_html(f, fig_no));
                }
            }
        }
        h.push_str("</section>\n");
    }
    let _ = writeln!(h, "<section id=\"config\"><h2>Config as used</h2>\n<pre>{}</pre></section>\n</main>", esc(&ctx.text));
    h.push_str("<footer>Interactive figures drawn by <a href=\"plotly-cartesian.min.js\">Plotly.js</a> (MIT licence, <a href=\"plotly-LICENSE.txt\">text</a>), shipped in this folder: no network needed.</footer>\n");
    h.push_str("<script src=\"plotly-cartesian.min.js\"></script>\n<script src=\"report.js\"></script>\n</body></html>\n");
    h
}

/// One figure: the interactive plot (static SVG inside until the script draws it), its data as
/// JSON, the caption and the links to the static files.
fn figure_html(f: &Figure, no: usize) -> String {
    let json = serde_json::to_string(&f.plot.to_plotly()).unwrap_or_else(|_| "{}".into()).replace("</", "<\\/");
    format!(
        "<figure id=\"{id}\">\n<div class=\"plot\" data-fig=\"{id}\" data-points=\"{pts}\"><img class=\"fallback\" src=\"{id}.svg\" alt=\"{alt}\"></div>\n<script type=\"application/json\" id=\"data-{id}\">{json}</script>\n<figcaption><b>Figure {no}.</b> {cap} <span class=\"files\">[<a href=\"{id}.svg\">SVG</a> · <a href=\"{id}.png\">PNG</a>]</span></figcaption>\n</figure>\n",
        id = f.id,
        pts = f.plot.point_count(),
        alt = esc(&f.plot.title),
        cap = f.caption,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use autobal::control::Control;

    /// The user report's context of examples/planar.toml under `control` (no section is run:
    /// the tests write sections they make).
    fn ctx(control: &Control) -> Ctx {
        let root = crate::config::parse_text(include_str!("../../../../examples/planar.toml"), "planar.toml").unwrap();
        context(&ConfigSource::tables(root, "planar.toml"), true, Kind::User, control).unwrap()
    }

    /// A section with one figure per id, complete or cut short.
    fn section(ids: &[&str], complete: bool) -> Section {
        let mut s = Section::new("test", "Test section");
        for id in ids {
            let plot =
                Plot { title: format!("figure {id}"), series: vec![crate::plot::Series::new("a", vec![(0.0, 1.0), (1.0, 2.0)], "#000")], ..Default::default() };
            s.figure(*id, plot, "caption");
        }
        s.complete = complete;
        s
    }

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("autobal-report-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// Every file of `dir` with its bytes, sorted (a folder's listing, to compare before/after).
    fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
        let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.is_file())
            .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read(&p).unwrap()))
            .collect();
        v.sort();
        v
    }

    /// A stop that comes after every section completed (while the figures are rendered: the
    /// control stopped before [`write_sections`]) leaves every file whole: the report is
    /// complete and says so (review 24c: "incomplete (stopped while writing)", exit 2); a
    /// section cut short makes it incomplete, naming that section.
    #[test]
    fn a_stop_after_the_sections_leaves_a_complete_report() {
        let d = scratch("stop-after");
        let control = Control::new();
        control.cancel();
        let out = write_sections(&ctx(&control), &d, &[section(&["f1"], true)], Instant::now()).unwrap();
        assert_eq!(out.incomplete, None);
        assert!(command::Output::stopped(&out).is_none());
        assert!(!std::fs::read_to_string(&out.index).unwrap().contains("id=\"interrupted\""));
        let e = d.join("e");
        let out = write_sections(&ctx(&control), &e, &[section(&["f1"], false)], Instant::now()).unwrap();
        assert_eq!(out.incomplete.unwrap(), format!("interrupted: the report in {} is incomplete (Test section)", e.join("index.html").display()));
        let _ = std::fs::remove_dir_all(&d);
    }

    /// A stopped report into a folder that holds a complete one leaves it byte for byte and
    /// goes to `incomplete/` (review 24c: it replaced the complete page, the earlier figures
    /// left beside it); a report that replaces one (complete over anything, a stopped one over
    /// a stopped one) removes the earlier figures it does not write, and nothing else.
    #[test]
    fn a_stop_never_replaces_a_complete_report_and_no_stale_figure_stays() {
        let d = scratch("kept");
        let c = ctx(&Control::none());
        write_sections(&c, &d, &[section(&["f1", "campbell"], true)], Instant::now()).unwrap();
        std::fs::write(d.join("notes.txt"), "the user's").unwrap();
        let before = files(&d);
        assert_eq!(before.len(), 9);
        let out = write_sections(&c, &d, &[section(&["f1"], false)], Instant::now()).unwrap();
        assert_eq!(files(&d), before, "the complete report is left as it was");
        let inc = d.join(INCOMPLETE_FOLDER);
        assert_eq!(out.index, inc.join("index.html"));
        assert!(out.incomplete.unwrap().ends_with(&format!("; the complete report in {} is left as it was", d.join("index.html").display())));
        assert!(std::fs::read_to_string(inc.join("index.html")).unwrap().contains(INTERRUPTED_DIV));
        assert!(inc.join("f1.svg").is_file() && inc.join("f1.png").is_file() && !inc.join("campbell.svg").exists());
        // a stopped one again: it replaces the stopped one there, and its stale figure goes
        write_sections(&c, &d, &[section(&["f2"], false)], Instant::now()).unwrap();
        assert!(inc.join("f2.svg").is_file() && !inc.join("f1.svg").exists() && !inc.join("f1.png").exists());
        assert_eq!(files(&d), before);
        // a complete rerun replaces the complete report; the earlier Campbell figures go, the
        // user's file stays
        let out = write_sections(&c, &d, &[section(&["f1"], true)], Instant::now()).unwrap();
        assert_eq!(out.index, d.join("index.html"));
        let names: Vec<String> = files(&d).into_iter().map(|(n, _)| n).collect();
        assert_eq!(names, ["f1.png", "f1.svg", "index.html", "notes.txt", "plotly-LICENSE.txt", "plotly-cartesian.min.js", "report.js"]);
        // and the stopped report of the earlier run is gone with its folder (review 25a: it
        // stayed, a stale page beside the complete one)
        assert!(!inc.exists());
        // a stopped report whose folder also holds a file of the user's: the report's files
        // go, the user's file and so the folder stay
        write_sections(&c, &d, &[section(&["f3"], false)], Instant::now()).unwrap();
        std::fs::write(inc.join("mine.txt"), "the user's").unwrap();
        write_sections(&c, &d, &[section(&["f1"], true)], Instant::now()).unwrap();
        let left: Vec<String> = files(&inc).into_iter().map(|(n, _)| n).collect();
        assert_eq!(left, ["mine.txt"]);
        let _ = std::fs::remove_dir_all(&d);
    }

    /// A folder holding the user's own `index.html`, or a file named as one of the report's
    /// assets with no report page, is refused before anything runs (review 25a: the user's
    /// page was replaced); an empty folder, a new one and one holding autobal's report are
    /// taken. The message names `--out` and the folder.
    #[test]
    fn a_folder_with_the_users_own_page_is_refused() {
        let d = scratch("users-page");
        check_folder(&d).unwrap();
        check_folder(&d.join("new")).unwrap();
        std::fs::write(d.join("index.html"), "<html><title>my notes</title></html>").unwrap();
        let e = check_folder(&d).unwrap_err().to_string();
        assert!(e.starts_with(&format!("--out {}: holds an index.html that is not an autobal report", d.display())), "{e}");
        std::fs::remove_file(d.join("index.html")).unwrap();
        std::fs::write(d.join("report.js"), "// mine").unwrap();
        let e = check_folder(&d).unwrap_err().to_string();
        assert!(e.contains("holds a file report.js"), "{e}");
        std::fs::remove_file(d.join("report.js")).unwrap();
        // autobal's own report: taken (a rerun replaces it)
        write_sections(&ctx(&Control::none()), &d, &[section(&["f1"], true)], Instant::now()).unwrap();
        check_folder(&d).unwrap();
        let _ = std::fs::remove_dir_all(&d);
    }

    /// Review 26a: a complete rerun removes only a stopped report's files from
    /// `DIR/incomplete` (not a complete report the user wrote there, not through a link to
    /// another folder); in a folder with no report page a figure named as a user's file is
    /// refused, the file left as it was.
    #[test]
    fn only_a_stopped_report_is_removed_and_no_users_figure_replaced() {
        let d = scratch("review26a");
        let c = ctx(&Control::none());
        // a complete report in DIR/incomplete (`--out DIR/incomplete`) stays
        write_sections(&c, &d.join(INCOMPLETE_FOLDER), &[section(&["g1"], true)], Instant::now()).unwrap();
        write_sections(&c, &d, &[section(&["f1"], true)], Instant::now()).unwrap();
        assert!(d.join(INCOMPLETE_FOLDER).join("index.html").is_file() && d.join(INCOMPLETE_FOLDER).join("g1.svg").is_file());
        // a link named `incomplete` to another folder holding a stopped report: not followed
        let e = scratch("review26a-other");
        write_sections(&c, &e, &[section(&["h1"], false)], Instant::now()).unwrap();
        let l = scratch("review26a-link");
        std::os::unix::fs::symlink(&e, l.join(INCOMPLETE_FOLDER)).unwrap();
        write_sections(&c, &l, &[section(&["f1"], true)], Instant::now()).unwrap();
        assert!(e.join("index.html").is_file() && e.join("h1.svg").is_file());
        // a user's file named as a figure, no report page: refused, the file kept
        let u = scratch("review26a-users-figure");
        std::fs::write(u.join("f1.png"), "mine").unwrap();
        let err = write_sections(&c, &u, &[section(&["f1"], true)], Instant::now()).err().expect("refused").to_string();
        assert!(err.contains("f1.png") && err.starts_with(&format!("--out {}: holds a file", u.display())), "{err}");
        assert_eq!(std::fs::read_to_string(u.join("f1.png")).unwrap(), "mine");
        for x in [d, e, l, u] {
            let _ = std::fs::remove_dir_all(&x);
        }
    }

    /// A stopped report into a folder holding a complete one, where `incomplete` is a file:
    /// one line naming it, and the complete report left as it was (review 25a: the error named
    /// the staged temporary file inside a folder that could not exist).
    #[test]
    fn an_incomplete_file_in_the_way_is_named() {
        let d = scratch("incomplete-file");
        let c = ctx(&Control::none());
        write_sections(&c, &d, &[section(&["f1"], true)], Instant::now()).unwrap();
        std::fs::write(d.join(INCOMPLETE_FOLDER), "the user's").unwrap();
        let before = files(&d);
        let e = write_sections(&c, &d, &[section(&["f1"], false)], Instant::now()).err().expect("refused").to_string();
        assert!(e.starts_with(&format!("--out {}: is not a folder", d.join(INCOMPLETE_FOLDER).display())), "{e}");
        assert_eq!(files(&d), before);
        let _ = std::fs::remove_dir_all(&d);
    }
}
