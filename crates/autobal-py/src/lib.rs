//! The `autobal._autobal` extension module: the library's configs, analyses, simulations and
//! sweeps for the Python package (`python/autobal`), which adds the pythonic layer (keyword
//! arguments, pandas, Dask). Every long call runs on a worker thread with the GIL released;
//! the calling thread checks for signals every 50 ms and, on Ctrl-C, cancels the work through
//! the library's cancel callback and raises `KeyboardInterrupt`. Library errors become the
//! exceptions of `autobal.errors`, naming the field.

use autobal::config::{self, Table, Value};
use autobal::control::Control;
use autobal::paths::Parameters;
use autobal::planar::problem::PlanarProblem;
use autobal::spatial::linear_model::Balls;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::time::Duration;

mod linear_rotor;

/// How often the waiting thread looks for signals (Ctrl-C).
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Run `f` on a worker thread with the GIL released, checking for signals meanwhile; on a
/// signal, set the cancel flag `f` polls, wait for `f` to return, and raise the signal's error.
fn interruptible<R: Send>(py: Python<'_>, f: impl FnOnce(&Control) -> R + Send) -> PyResult<R> {
    match interruptible_kept(py, f)? {
        (r, None) => Ok(r),
        (_, Some(e)) => Err(e),
    }
}

/// [`interruptible`], keeping what `f` returned after a signal stopped it: `(f's value, the
/// signal's error)`, the error `None` where no signal came (a command that keeps what it
/// computed until the stop hands it to Python on the `KeyboardInterrupt`, [`with_result`]).
fn interruptible_kept<R: Send>(py: Python<'_>, f: impl FnOnce(&Control) -> R + Send) -> PyResult<(R, Option<PyErr>)> {
    let cancel = Control::new();
    std::thread::scope(|s| {
        let (tx, mut rx) = std::sync::mpsc::channel();
        let cancel = &cancel;
        s.spawn(move || {
            let _ = tx.send(f(cancel));
        });
        loop {
            let (got, back) = py.detach(move || (rx.recv_timeout(SIGNAL_POLL), rx));
            rx = back;
            match got {
                Ok(r) => return Ok((r, None)),
                Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => return Err(PyRuntimeError::new_err("autobal: the worker thread panicked")),
                Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                    if let Err(e) = py.check_signals() {
                        cancel.cancel();
                        return match py.detach(move || rx.recv()) {
                            Ok(r) => Ok((r, Some(e))),
                            Err(_) => Err(e),
                        };
                    }
                }
            }
        }
    })
}

/// The signal's error `e` (`KeyboardInterrupt`) with what the stopped call kept as its
/// `result` attribute, the JSON text the call returns (as `SimulationError.result` holds a
/// stopped run's samples).
fn with_result(py: Python<'_>, e: PyErr, result: String) -> PyErr {
    let _ = e.value(py).setattr("result", result);
    e
}

/// `work` in a pool of `threads` threads (kept for the next call with the same number: building
/// a pool costs more than a short run), or in the global pool (all cores).
fn with_threads<R: Send>(threads: Option<usize>, work: impl FnOnce() -> autobal::Result<R> + Send) -> autobal::Result<R> {
    static POOLS: std::sync::Mutex<Vec<(usize, std::sync::Arc<rayon::ThreadPool>)>> = std::sync::Mutex::new(Vec::new());
    let Some(t) = threads.map(|t| t.max(1)) else { return work() };
    let pool = {
        let mut pools = POOLS.lock().unwrap_or_else(|p| p.into_inner());
        match pools.iter().find(|(n, _)| *n == t) {
            Some((_, p)) => p.clone(),
            None => {
                let p =
                    std::sync::Arc::new(rayon::ThreadPoolBuilder::new().num_threads(t).build().map_err(|e| autobal::Error::invalid("threads", e.to_string()))?);
                pools.push((t, p.clone()));
                p
            }
        }
    };
    pool.install(work)
}

/// A library error as the matching exception of `autobal.errors` (`InvalidParameter` names the
/// field in `.field`).
fn py_err(py: Python<'_>, e: autobal::Error) -> PyErr {
    use autobal::Error as E;
    // the commands name their options as the CLI's flags; Python's are its keywords
    let e = match e {
        E::InvalidParameter { field, reason } if field.starts_with("--") => E::InvalidParameter { field: keyword(&field), reason },
        e => e,
    };
    let (class, field, reason) = match &e {
        E::InvalidParameter { field, reason } => ("InvalidParameter", Some(field.clone()), Some(reason.clone())),
        E::TooLarge { what, .. } => ("TooLarge", Some(what.clone()), None),
        E::NoConvergence { .. } => ("NoConvergence", None, None),
        E::Interrupted { .. } => ("Interrupted", None, None),
        E::SingularMassMatrix { .. } | E::NonFinite { .. } | E::StepTooSmall { .. } | E::TooManySteps { .. } => ("SimulationError", None, None),
        _ => ("AutobalError", None, None),
    };
    let made = (|| -> PyResult<PyErr> {
        let cls = py.import("autobal.errors")?.getattr(class)?;
        let exc = cls.call1((e.to_string(),))?;
        exc.setattr("field", field)?;
        exc.setattr("reason", reason)?;
        Ok(PyErr::from_value(exc))
    })();
    made.unwrap_or_else(|err| err)
}

/// An option named as the CLI's flag (`--omega-max`) as Python's keyword (`omega_max`).
fn keyword(flag: &str) -> String {
    flag.strip_prefix("--").map_or(flag.to_string(), |n| n.replace('-', "_"))
}

/// A message that starts with a CLI flag (`--balls locked: ...`), with Python's keyword.
fn keyword_message(msg: &str) -> String {
    match msg.strip_prefix("--") {
        Some(rest) => {
            let end = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '-')).unwrap_or(rest.len());
            format!("{}{}", rest[..end].replace('-', "_"), &rest[end..])
        }
        None => msg.to_string(),
    }
}

/// An error of the commands crate: a library error as its exception of `autobal.errors`, any
/// other (a file, a Ctrl-C) as `AutobalError` with the CLI's one-line message.
fn any_err(py: Python<'_>, e: anyhow::Error) -> PyErr {
    match e.downcast::<autobal::Error>() {
        Ok(e) => py_err(py, e),
        Err(e) => {
            let msg = keyword_message(&format!("{e:#}").replace('\n', " "));
            match py.import("autobal.errors").and_then(|m| m.getattr("AutobalError")).and_then(|c| c.call1((msg,))) {
                Ok(exc) => PyErr::from_value(exc),
                Err(err) => err,
            }
        }
    }
}

/// Run a computation of the commands crate on a worker thread with the GIL released; Ctrl-C
/// stops it through its [`Control`] and raises `KeyboardInterrupt`.
fn commands_call<R: Send>(py: Python<'_>, f: impl FnOnce(&Control) -> anyhow::Result<R> + Send) -> PyResult<R> {
    interruptible(py, f)?.map_err(|e| any_err(py, e))
}

/// A Python value (dict, list, number, bool, str) as TOML; `at` names it in errors.
fn to_toml(v: &Bound<'_, PyAny>, at: &str) -> PyResult<Value> {
    if v.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(Value::Integer(v.extract()?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(Value::String(v.extract()?));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut t = Table::new();
        for (k, x) in d.iter() {
            let k: String = k.extract().map_err(|_| PyTypeError::new_err(format!("{at}: keys must be strings")))?;
            let inner = if at.is_empty() { k.clone() } else { format!("{at}.{k}") };
            t.insert(k, to_toml(&x, &inner)?);
        }
        return Ok(Value::Table(t));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() || v.hasattr("tolist")? {
        let list = if v.hasattr("tolist")? { v.call_method0("tolist")? } else { v.clone() };
        if let Ok(f) = list.extract::<f64>() {
            return Ok(Value::Float(f)); // a numpy scalar
        }
        let mut a = vec![];
        for x in list.try_iter()? {
            a.push(to_toml(&x?, at)?);
        }
        return Ok(Value::Array(a));
    }
    Err(PyTypeError::new_err(format!("{at}: expected a number, string, bool, list or dict, got {}", v.get_type().name()?)))
}

/// The raw table of a config: TOML `text` (named `source` in errors) or a dict, then each
/// `(table.key, value)` of `sets`.
fn table(py: Python<'_>, text: Option<&str>, dict: Option<&Bound<'_, PyDict>>, source: &str, sets: Vec<(String, Bound<'_, PyAny>)>) -> PyResult<Table> {
    let mut root = match (text, dict) {
        (Some(t), _) => config::parse(t, source).map_err(|e| py_err(py, e))?,
        (None, Some(d)) => match to_toml(d.as_any(), "")? {
            Value::Table(t) => t,
            _ => unreachable!("a dict converts to a table"),
        },
        (None, None) => Table::new(),
    };
    for (k, v) in sets {
        let value = to_toml(&v, &k)?;
        config::set(&mut root, &k, value).map_err(|e| py_err(py, e))?;
    }
    Ok(root)
}

/// A spatial config (papers 000/003), validated.
#[pyclass(module = "autobal._autobal", name = "SpatialConfig", frozen)]
struct PySpatial {
    source: String,
    /// The tables it was built from (the simulation reads `[drive]`, `[initial]`, ... from them).
    root: Table,
}

/// A planar problem (paper 004), validated.
#[pyclass(module = "autobal._autobal", name = "PlanarConfig", frozen)]
struct PyPlanar {
    problem: PlanarProblem,
    toml: String,
}

#[pymethods]
impl PySpatial {
    /// The config's tables as TOML text.
    #[getter]
    fn toml(&self) -> String {
        toml::to_string(&self.root).unwrap_or_default()
    }
}

#[pymethods]
impl PyPlanar {
    /// The config's tables as TOML text.
    #[getter]
    fn toml(&self) -> &str {
        &self.toml
    }
    /// The number at a parameter path (`planar.m3`, `drive.b`, `drive.psi0[1]`).
    fn get(&self, py: Python<'_>, path: &str) -> PyResult<f64> {
        self.problem.get(path).map_err(|e| py_err(py, e))
    }
    /// The problem as JSON (rotor, drive, settings).
    fn to_json(&self) -> String {
        serde_json::to_string(&self.problem).unwrap_or_default()
    }
}

#[pyfunction]
#[pyo3(signature = (text, dict, source, sets))]
fn spatial_config(
    py: Python<'_>,
    text: Option<&str>,
    dict: Option<&Bound<'_, PyDict>>,
    source: &str,
    sets: Vec<(String, Bound<'_, PyAny>)>,
) -> PyResult<PySpatial> {
    let root = table(py, text, dict, source, sets)?;
    // validated here (errors name the key); the commands read the tables again
    config::spatial(&root).map_err(|e| py_err(py, e))?;
    Ok(PySpatial { source: source.to_string(), root })
}

#[pyfunction]
#[pyo3(signature = (text, dict, source, sets))]
fn planar_config(
    py: Python<'_>,
    text: Option<&str>,
    dict: Option<&Bound<'_, PyDict>>,
    source: &str,
    sets: Vec<(String, Bound<'_, PyAny>)>,
) -> PyResult<PyPlanar> {
    let root = table(py, text, dict, source, sets)?;
    let problem = config::planar(&root).map_err(|e| py_err(py, e))?;
    Ok(PyPlanar { problem, toml: toml::to_string(&root).unwrap_or_default() })
}

fn balls(py: Python<'_>, s: &str) -> PyResult<Balls> {
    match s {
        "free" => Ok(Balls::Free),
        "locked" => Ok(Balls::Locked),
        o => Err(py_err(py, autobal::Error::invalid("balls", format!("must be \"free\" or \"locked\", got \"{o}\"")))),
    }
}

/// A speed argument: a number (the dimensionless Ω) or a speed with its unit, `"1500 rpm"`
/// ([`autobal::units`]).
#[derive(FromPyObject)]
enum SpeedArg {
    Number(f64),
    Text(String),
}

/// The options of the analytic commands, as Python's keywords (`None`: the command's default,
/// its `Args::default()`).
struct AnalyticOptions {
    omega_max: Option<SpeedArg>,
    samples: Option<usize>,
    points: Option<usize>,
    balls: String,
    route: String,
}

/// Run the analytic `command` (`inertia`, `critical`, `ranges`, `stability`, `campbell`) on
/// `config` as the CLI runs it (the same `Args`, the same `run`): its JSON text.
fn analytic_json(py: Python<'_>, command: &str, config: autobal_commands::command::ConfigSource, o: AnalyticOptions) -> PyResult<String> {
    use autobal_commands::command::{Command, Output, Route};
    use autobal_commands::{campbell, critical, inertia, ranges, stability};
    let b = self::balls(py, &o.balls)?;
    let route = match o.route.as_str() {
        "auto" => Route::Auto,
        "general" => Route::General,
        r => return Err(py_err(py, autobal::Error::invalid("route", format!("must be \"auto\" or \"general\", got \"{r}\"")))),
    };
    // a number is the dimensionless Ω (or rad/s of the planar rotor), as a bare number on the
    // CLI; Rust's shortest representation gives the same f64 back
    let omega_max = o.omega_max.map(|w| match w {
        SpeedArg::Number(w) => format!("{w}"),
        SpeedArg::Text(t) => t,
    });
    let (samples, points) = (o.samples, o.points);
    let v = match command {
        "inertia" => commands_call(py, move |c| inertia::Args { config }.run(c)?.json())?,
        "ranges" => commands_call(py, move |c| ranges::Args { config }.run(c)?.json())?,
        "critical" => commands_call(py, move |c| critical::Args { config, route, omega_max }.run(c)?.json())?,
        "stability" => commands_call(py, move |c| {
            let out = stability::Args { config, omega_max, balls: b, samples, route }.run(c)?;
            if let Some(why) = out.stopped() {
                anyhow::bail!("{why}");
            }
            out.json()
        })?,
        "campbell" => commands_call(py, move |c| {
            let out = campbell::Args { config, omega_max, balls: b, points, route, ..Default::default() }.run(c)?;
            if let Some(why) = out.stopped() {
                anyhow::bail!("{why}");
            }
            out.json()
        })?,
        o => return Err(PyValueError::new_err(format!("command: unknown analytic command \"{o}\" (inertia, critical, ranges, stability, campbell)"))),
    };
    Ok(v.to_string())
}

/// The JSON text of an analytic command (`inertia`, `critical`, `ranges`, `stability`,
/// `campbell`) on a spatial config: what `autobal COMMAND --format json` prints.
#[pyfunction]
#[pyo3(signature = (command, cfg, omega_max=None, samples=None, points=None, balls="free", route="auto"))]
#[allow(clippy::too_many_arguments)]
fn spatial_report(
    py: Python<'_>,
    command: &str,
    cfg: &PySpatial,
    omega_max: Option<SpeedArg>,
    samples: Option<usize>,
    points: Option<usize>,
    balls: &str,
    route: &str,
) -> PyResult<String> {
    let config = autobal_commands::command::ConfigSource::tables(cfg.root.clone(), &cfg.source);
    analytic_json(py, command, config, AnalyticOptions { omega_max, samples, points, balls: balls.into(), route: route.into() })
}

/// The JSON text of an analytic command on any config autobal runs (a planar config included:
/// `ranges`, `stability`, `campbell` and `critical` take the general route there, as the CLI):
/// the config as [`figures`] takes it.
#[pyfunction]
#[pyo3(signature = (command, text, dict, source, sets, omega_max=None, samples=None, points=None, balls="free", route="auto"))]
#[allow(clippy::too_many_arguments)]
fn command_json(
    py: Python<'_>,
    command: &str,
    text: Option<&str>,
    dict: Option<&Bound<'_, PyDict>>,
    source: &str,
    sets: Vec<(String, Bound<'_, PyAny>)>,
    omega_max: Option<SpeedArg>,
    samples: Option<usize>,
    points: Option<usize>,
    balls: &str,
    route: &str,
) -> PyResult<String> {
    let root = table(py, text, dict, source, sets)?;
    let config = autobal_commands::command::ConfigSource::tables(root, source);
    analytic_json(py, command, config, AnalyticOptions { omega_max, samples, points, balls: balls.into(), route: route.into() })
}

/// `autobal simulate` (the CLI's `Args` and `run`, without files) on `config`, keeping the
/// samples as columns: `(columns, summary JSON)`, the summary as `autobal simulate --format json`
/// prints it, the columns as arrays named as the CLI's CSV columns, except that a planar or
/// spatial run's ball angles `psi_1 … psi_n` are one array `psi` (samples × balls). `dt`
/// overrides the output interval; `columns = false` keeps none (the summary alone).
fn simulate_columns<'py>(
    py: Python<'py>,
    config: autobal_commands::command::ConfigSource,
    dt: Option<f64>,
    columns: bool,
) -> PyResult<(Bound<'py, PyDict>, String)> {
    use autobal_commands::command::{Command, Output};
    let args = autobal_commands::simulate::Args { config, dt, columns, ..Default::default() };
    let (cols, balls_model, summary) = commands_call(py, move |control| {
        let o = args.run(control)?;
        let (summary, balls_model) = (o.json()?.to_string(), o.is_ball_model());
        Ok((o.columns.unwrap_or_default(), balls_model, summary))
    })?;
    let out = PyDict::new(py);
    if !columns {
        return Ok((out, summary));
    }
    let (names, cols) = cols;
    let rows = cols.first().map_or(0, Vec::len);
    let mut psi: Vec<Vec<f64>> = vec![];
    for (name, c) in names.into_iter().zip(cols) {
        if balls_model && name.starts_with("psi_") {
            psi.push(c);
        } else {
            out.set_item(name, PyArray1::from_vec(py, c))?;
        }
    }
    if balls_model {
        // samples × balls, row-major
        let flat: Vec<f64> = (0..rows).flat_map(|i| psi.iter().map(move |c| c[i])).collect();
        out.set_item("psi", PyArray1::from_vec(py, flat).reshape([rows, psi.len()])?)?;
    }
    Ok((out, summary))
}

/// Run a planar problem as `autobal simulate` does ([`simulate_columns`]): columns `t, omega,
/// x, y, amplitude` and `psi` (samples × balls) as arrays, the summary JSON. `dt` overrides the
/// output interval.
#[pyfunction]
#[pyo3(signature = (cfg, dt=None))]
fn simulate<'py>(py: Python<'py>, cfg: &PyPlanar, dt: Option<f64>) -> PyResult<(Bound<'py, PyDict>, String)> {
    let root = config::parse(&cfg.toml, "PlanarProblem").map_err(|e| py_err(py, e))?;
    simulate_columns(py, autobal_commands::command::ConfigSource::tables(root, "PlanarProblem"), dt, true)
}

/// Run the spatial rotor of papers 000/003 of a spatial config with `[drive]` (and
/// `[integration]`, ...) as `autobal simulate` does ([`simulate_columns`]): columns `t, omega,
/// x, y, tilt_x, tilt_y`, `amplitude_left`, `amplitude_right` (supports), `amplitude_plane1`,
/// ... (balancer planes) and `psi` (samples × balls) as arrays, the summary JSON. `dt`
/// overrides the output interval.
#[pyfunction]
#[pyo3(signature = (cfg, dt=None))]
fn spatial_simulate<'py>(py: Python<'py>, cfg: &PySpatial, dt: Option<f64>) -> PyResult<(Bound<'py, PyDict>, String)> {
    simulate_columns(py, autobal_commands::command::ConfigSource::tables(cfg.root.clone(), &cfg.source), dt, true)
}

/// `autobal simulate` on any config it runs (planar, spatial, linear rotor), read as
/// [`command_json`] reads it: `(columns, summary JSON)` of [`simulate_columns`].
#[pyfunction]
#[pyo3(signature = (text, dict, source, sets, dt=None, columns=true))]
#[allow(clippy::too_many_arguments)]
fn simulate_command<'py>(
    py: Python<'py>,
    text: Option<&str>,
    dict: Option<&Bound<'_, PyDict>>,
    source: &str,
    sets: Vec<(String, Bound<'_, PyAny>)>,
    dt: Option<f64>,
    columns: bool,
) -> PyResult<(Bound<'py, PyDict>, String)> {
    let root = table(py, text, dict, source, sets)?;
    simulate_columns(py, autobal_commands::command::ConfigSource::tables(root, source), dt, columns)
}

/// `autobal basins` on a spatial config with `[drive]`: runs over an `n × n` grid of the first two balls'
/// initial angles, in parallel in Rust. `(arrays, summary JSON)`: `psi_1`, `psi_2` (initial
/// angles), `balanced_runs` (the CSV's `balanced` column: this run ended balanced),
/// `residual_unbalance`, `final_amplitude` per run (the CLI's CSV, row-major with `psi_2` outer;
/// not `balanced`, which the summary uses for the count of balanced runs), the summary as `autobal basins --format json` prints it (without `csv`).
#[pyfunction]
#[pyo3(signature = (cfg, n=None))]
fn spatial_basins<'py>(py: Python<'py>, cfg: &PySpatial, n: Option<usize>) -> PyResult<(Bound<'py, PyDict>, String)> {
    use autobal_commands::command::{Command, Output};
    // the CLI's `basins` (its Args and run, its default n): the JSON is the CLI's but the CSV's name
    let config = autobal_commands::command::ConfigSource::tables(cfg.root.clone(), &cfg.source);
    let args = autobal_commands::basins::Args { config, n: n.unwrap_or(autobal_commands::basins::Args::default().n) };
    let o = commands_call(py, move |control| args.run(control))?;
    if o.stopped().is_some() {
        return Err(py_err(py, autobal::Error::Interrupted { t: 0.0 }));
    }
    let ends: Vec<_> = o.ends.iter().flatten().collect();
    let out = PyDict::new(py);
    out.set_item("psi_1", PyArray1::from_vec(py, o.angles.iter().map(|a| a[0]).collect()))?;
    out.set_item("psi_2", PyArray1::from_vec(py, o.angles.iter().map(|a| a[1]).collect()))?;
    out.set_item("balanced_runs", PyArray1::from_vec(py, ends.iter().map(|s| s.balanced).collect()))?;
    out.set_item("residual_unbalance", PyArray1::from_vec(py, ends.iter().map(|s| s.residual_unbalance).collect()))?;
    out.set_item("final_amplitude", PyArray1::from_vec(py, ends.iter().map(|s| s.final_amplitude).collect()))?;
    let summary = o.json().map_err(|e| any_err(py, e))?;
    Ok((out, summary.to_string()))
}

/// The base of a batch or sweep: a planar problem or a spatial config (one per call: the
/// planar problem's size does not matter).
#[allow(clippy::large_enum_variant)]
enum Base {
    Planar(PlanarProblem),
    Spatial(autobal::sweep::SpatialSweep),
    Linear(autobal::linear_rotor::spec::LinearRotorSpec),
}

/// `cfg` (a `PlanarConfig` or a `SpatialConfig`) as the base of a batch or sweep; a spatial
/// config must convert to a simulation (`[drive]`, `[integration]`, ...).
fn base_of(py: Python<'_>, cfg: &Bound<'_, PyAny>) -> PyResult<Base> {
    if let Ok(p) = cfg.extract::<PyRef<'_, PyPlanar>>() {
        return Ok(Base::Planar(p.problem.clone()));
    }
    if let Ok(c) = cfg.extract::<PyRef<'_, PySpatial>>() {
        return autobal::sweep::SpatialSweep::new(c.root.clone()).map(Base::Spatial).map_err(|e| py_err(py, e));
    }
    if let Ok(l) = cfg.extract::<PyRef<'_, linear_rotor::PyLinearSpec>>() {
        return Ok(Base::Linear(l.spec.clone()));
    }
    Err(PyTypeError::new_err("cfg: expected a PlanarConfig, a SpatialConfig or a LinearSpec (PlanarProblem._cfg, SpatialModel._cfg)"))
}

/// Check every row of `params` (points × paths) as a batch would before running.
#[pyfunction]
fn check_batch(py: Python<'_>, cfg: &Bound<'_, PyAny>, paths: Vec<String>, params: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
    let flat: Vec<f64> = params.as_array().iter().copied().collect();
    let refs: Vec<&str> = paths.iter().map(String::as_str).collect();
    if params.shape()[1] != paths.len() {
        return Err(py_err(py, autobal::Error::invalid("params", format!("{} columns for {} paths", params.shape()[1], paths.len()))));
    }
    let r = match base_of(py, cfg)? {
        Base::Planar(p) => autobal::sweep::check_batch(&p, &refs, &flat),
        Base::Spatial(s) => autobal::sweep::check_batch(&s, &refs, &flat),
        Base::Linear(l) => autobal::sweep::check_batch(&l, &refs, &flat),
    };
    r.map_err(|e| py_err(py, e))
}

/// A batch of `base`: `rows × ncol` summaries, `ncol` the model's summary columns.
fn run_batch<M: autobal::sweep::SweepModel>(base: &M, paths: &[String], flat: &[f64], rows: usize, cancel: &Control) -> autobal::Result<Vec<f64>> {
    use autobal::sweep::SweepSummary;
    let ncol = <M::Summary as SweepSummary>::COLUMNS.len();
    let refs: Vec<&str> = paths.iter().map(String::as_str).collect();
    let mut out = vec![f64::NAN; rows * ncol];
    let o = autobal::sweep::simulate_batch(
        base,
        &refs,
        flat,
        &mut |i, _, r| {
            out[i * ncol..(i + 1) * ncol].copy_from_slice(&r.summary.values());
            true
        },
        cancel,
    )?;
    o.into_result()?;
    Ok(out)
}

/// Run `params` (points × paths) on the problem (a `PlanarConfig`, or a `SpatialConfig` with
/// `[drive]`) in parallel (`threads`, default all cores): an array points × `SUMMARY_COLUMNS`
/// (planar) or `SPATIAL_SUMMARY_COLUMNS` (spatial), the same bits whatever the threads.
#[pyfunction]
#[pyo3(signature = (cfg, paths, params, threads=None))]
fn simulate_batch<'py>(
    py: Python<'py>,
    cfg: &Bound<'py, PyAny>,
    paths: Vec<String>,
    params: PyReadonlyArray2<'py, f64>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    let shape = params.shape();
    let (rows, k) = (shape[0], shape[1]);
    if k != paths.len() {
        return Err(py_err(py, autobal::Error::invalid("params", format!("{k} columns for {} paths", paths.len()))));
    }
    let flat: Vec<f64> = params.as_array().iter().copied().collect();
    let base = base_of(py, cfg)?;
    let ncol = match base {
        Base::Planar(_) => autobal::sweep::SUMMARY_COLUMNS.len(),
        Base::Spatial(_) => autobal::sweep::SPATIAL_SUMMARY_COLUMNS.len(),
        Base::Linear(_) => autobal::sweep::LINEAR_SUMMARY_COLUMNS.len(),
    };
    let result = interruptible(py, move |cancel| {
        with_threads(threads, || match &base {
            Base::Planar(p) => run_batch(p, &paths, &flat, rows, cancel),
            Base::Spatial(s) => run_batch(s, &paths, &flat, rows, cancel),
            Base::Linear(l) => run_batch(l, &paths, &flat, rows, cancel),
        })
    })?;
    let out = result.map_err(|e| py_err(py, e))?;
    PyArray1::from_vec(py, out).reshape([rows, ncol])
}

/// `autobal sweep --format json` on the problem (a `PlanarConfig`, or a `SpatialConfig` with
/// `[drive]`): `axes` as `[(path, values), ...]` (first fastest: the CLI's `--x`, `--y`, then
/// `--axis`), `shard` as `(k, n)` 1-based. The same `sweep::Args` and `run` as the CLI: the JSON
/// text, with its `definition_checksum`.
#[pyfunction]
#[pyo3(signature = (cfg, axes, shard=None, threads=None))]
fn sweep_report(
    py: Python<'_>,
    cfg: &Bound<'_, PyAny>,
    axes: Vec<(String, Vec<f64>)>,
    shard: Option<(usize, usize)>,
    threads: Option<usize>,
) -> PyResult<String> {
    use autobal_commands::command::{Command, ConfigSource, Output};
    // the config's tables, as the CLI reads them
    let config = if let Ok(p) = cfg.extract::<PyRef<'_, PyPlanar>>() {
        ConfigSource::tables(config::parse(&p.toml, "config").map_err(|e| py_err(py, e))?, "config")
    } else if let Ok(c) = cfg.extract::<PyRef<'_, PySpatial>>() {
        ConfigSource::tables(c.root.clone(), &c.source)
    } else {
        return Err(PyTypeError::new_err("cfg: expected a PlanarConfig or a SpatialConfig (PlanarProblem._cfg, SpatialModel._cfg)"));
    };
    let mut axes = axes.into_iter().map(|(p, v)| autobal::sweep::Axis::new(p, v));
    let Some(x) = axes.next() else { return Err(py_err(py, autobal::Error::invalid("x", "required (the first axis, e.g. x='drive.b=0.5:12.5:5')"))) };
    let args = autobal_commands::sweep::Args { config, x, y: axes.next(), more: axes.collect(), shard };
    let v = commands_call(py, move |c| {
        let out = in_pool(threads, || args.run(c))?;
        if let Some(why) = out.stopped() {
            anyhow::bail!("{why}");
        }
        out.json()
    })?;
    Ok(v.to_string())
}

/// `work` (a command of the commands crate) in a pool of `threads` threads ([`with_threads`]).
fn in_pool<R: Send>(threads: Option<usize>, work: impl FnOnce() -> anyhow::Result<R> + Send) -> anyhow::Result<R> {
    with_threads(threads, || Ok(work()))?
}

/// A map's cells as arrays `len(y) × len(x)` (row `j` at `y[j]`): `margin` (max Re λ, or the
/// largest Floquet exponent on the general route; NaN with `quantity="verdict"` or where no
/// stationary state was found), `stable`; on the closed-form route `necessary` (inside 003's
/// necessary ranges) and `fixed_speed` (a speed in SI over axes that move ω0, as given, e.g.
/// `"1400 rpm"`: every cell at its own Ω; else None), on the general route `verdict` (`"stable"`, `"unstable"`, `"neutral"`,
/// `""`: no stationary state), `family_dimension` and `state` (`"balanced"`, `"semi_balanced"`,
/// `"partially_balanced"`, `"not_balanced"`, `""` without a state).
fn map_dict<'py>(py: Python<'py>, args: autobal_commands::map::Args, threads: Option<usize>) -> PyResult<Bound<'py, PyDict>> {
    use autobal_commands::command::Output;
    use autobal_commands::map::RouteOutput;
    let (xs, ys) = (args.x.values.clone(), args.y.values.clone());
    let (nx, ny) = (xs.len(), ys.len());
    let out = commands_call(py, move |c| {
        // the options checked as given (`boundary` among them: refused here, before any cell,
        // where it cannot be traced), the cells computed without the trace (the dict has no
        // place for it; `analyse`'s figure traces it)
        let out = in_pool(threads, || args.prepare()?.untraced().run(c, autobal_commands::map::Rows::Keep))?;
        if let Some(why) = out.stopped() {
            anyhow::bail!("{why}");
        }
        Ok(out)
    })?;
    let d = PyDict::new(py);
    d.set_item("x", PyArray1::from_vec(py, xs))?;
    d.set_item("y", PyArray1::from_vec(py, ys))?;
    // the margin's name in the CLI's CSV (per τ on a dimensional spatial config)
    d.set_item("margin_column", out.margin_column)?;
    // the per-τ margins' unit on a dimensional spatial config (one value, or None where the
    // axes move it: then its range), as the CLI prints it
    d.set_item("omega0_rad_s", out.omega0.filter(|[a, b]| a == b).map(|[a, _]| a))?;
    d.set_item("omega0_range_rad_s", out.omega0.map(|r| r.to_vec()))?;
    match out.route {
        RouteOutput::Closed { cells: Some(cells), at_si, .. } => {
            // a fixed speed in SI over axes that move ω0: every cell at its own Ω (the speed as
            // given, as the CLI's table and figure name it); None otherwise
            d.set_item("fixed_speed", at_si)?;
            let flat = || cells.iter().flatten();
            d.set_item("margin", PyArray1::from_vec(py, flat().map(|c| c.margin).collect()).reshape([ny, nx])?)?;
            d.set_item("stable", PyArray1::from_vec(py, flat().map(|c| c.stable).collect()).reshape([ny, nx])?)?;
            d.set_item("necessary", PyArray1::from_vec(py, flat().map(|c| c.necessary).collect()).reshape([ny, nx])?)?;
        }
        RouteOutput::General { cells: Some(cells), .. } => {
            use autobal::rotor_map::Verdict;
            let flat = || cells.iter().flatten();
            let margin = flat().map(|c| if c.verdict.is_some() { c.margin } else { f64::NAN }).collect();
            d.set_item("margin", PyArray1::from_vec(py, margin).reshape([ny, nx])?)?;
            d.set_item("stable", PyArray1::from_vec(py, flat().map(|c| c.verdict == Some(Verdict::Stable)).collect()).reshape([ny, nx])?)?;
            let name = |v: Option<Verdict>| match v {
                None => "",
                Some(Verdict::Stable) => "stable",
                Some(Verdict::Unstable) => "unstable",
                Some(Verdict::Neutral) => "neutral",
            };
            // below the periodic-orbit floor: "not_analysed", as the CLI's CSV
            let rows: Vec<Vec<&str>> =
                cells.iter().map(|r| r.iter().map(|c| if c.analysed { name(c.verdict) } else { autobal_commands::map::NOT_ANALYSED }).collect()).collect();
            d.set_item("verdict", rows)?;
            d.set_item("family_dimension", PyArray1::from_vec(py, flat().map(|c| c.family_dimension as u64).collect()).reshape([ny, nx])?)?;
            // what the state is, the CLI CSV's `state` (`""` without one)
            d.set_item("state", cells.iter().map(|r| r.iter().map(|c| c.state.map_or("", |k| k.key())).collect::<Vec<_>>()).collect::<Vec<_>>())?;
            d.set_item("route", "general")?;
        }
        _ => return Err(PyRuntimeError::new_err("autobal: the map kept no cells")),
    }
    Ok(d)
}

/// The map's `quantity` keyword.
fn quantity(py: Python<'_>, q: &str) -> PyResult<autobal_commands::map::Quantity> {
    use autobal_commands::map::Quantity;
    match q {
        "margin" => Ok(Quantity::Margin),
        "verdict" => Ok(Quantity::Verdict),
        o => Err(py_err(py, autobal::Error::invalid("quantity", format!("must be \"margin\" or \"verdict\", got \"{o}\"")))),
    }
}

/// A stability map of the spatial model (what `autobal map` writes as CSV): `x` and `y` as
/// `(path, values)` (path `omega` for the speed), `omega` the speed when neither axis is it.
/// Arrays `margin` (max Re λ; NaN for `quantity="verdict"`), `stable`, `necessary`, each
/// `len(y) × len(x)` (row `j` at `y[j]`), computed in parallel (`threads`, default all cores).
#[pyfunction]
#[pyo3(signature = (cfg, x, y, omega=None, balls="free", quantity="margin", threads=None))]
#[allow(clippy::too_many_arguments)]
fn stability_map<'py>(
    py: Python<'py>,
    cfg: &PySpatial,
    x: (String, Vec<f64>),
    y: (String, Vec<f64>),
    omega: Option<f64>,
    balls: &str,
    quantity: &str,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    // the same `map::Args` and `run` as the CLI (a bare number is Ω, as on the CLI)
    let args = autobal_commands::map::Args {
        config: autobal_commands::command::ConfigSource::tables(cfg.root.clone(), &cfg.source),
        x: autobal::paths::Axis::new(x.0, x.1),
        y: autobal::paths::Axis::new(y.0, y.1),
        omega: omega.map(|w| format!("{w}")),
        balls: self::balls(py, balls)?,
        quantity: self::quantity(py, quantity)?,
        ..Default::default()
    };
    map_dict(py, args, threads)
}

/// `autobal map` on any config (as [`figures`] takes it), by the CLI's `map::Args`: the cells
/// as arrays ([`map_dict`]); `x`, `y` as `(path, values)`; `omega` a speed with its unit or a
/// bare number (Ω); `route` `"auto"` or `"general"`; `boundary` (`analyse`'s, for its figure)
/// checked as the CLI's `--boundary` before any cell is computed, not traced.
#[pyfunction]
#[pyo3(signature = (text, dict, source, sets, x, y, omega=None, balls=None, quantity=None, route=None, threads=None, boundary=false))]
#[allow(clippy::too_many_arguments)]
fn map_cells<'py>(
    py: Python<'py>,
    text: Option<&str>,
    dict: Option<&Bound<'_, PyDict>>,
    source: &str,
    sets: Vec<(String, Bound<'_, PyAny>)>,
    x: (String, Vec<f64>),
    y: (String, Vec<f64>),
    omega: Option<SpeedArg>,
    balls: Option<&str>,
    quantity: Option<&str>,
    route: Option<&str>,
    threads: Option<usize>,
    boundary: bool,
) -> PyResult<Bound<'py, PyDict>> {
    use autobal_commands::command::Route;
    let root = table(py, text, dict, source, sets)?;
    // the options not given: the CLI's defaults (map::Args::default())
    let mut args = autobal_commands::map::Args {
        config: autobal_commands::command::ConfigSource::tables(root, source),
        x: autobal::paths::Axis::new(x.0, x.1),
        y: autobal::paths::Axis::new(y.0, y.1),
        omega: omega.map(|w| match w {
            SpeedArg::Number(w) => format!("{w}"),
            SpeedArg::Text(t) => t,
        }),
        boundary,
        ..Default::default()
    };
    if let Some(b) = balls {
        args.balls = self::balls(py, b)?;
    }
    if let Some(q) = quantity {
        args.quantity = self::quantity(py, q)?;
    }
    match route {
        None => {}
        Some("auto") => args.route = Route::Auto,
        Some("general") => args.route = Route::General,
        Some(r) => return Err(py_err(py, autobal::Error::invalid("route", format!("must be \"auto\" or \"general\", got \"{r}\"")))),
    }
    map_dict(py, args, threads)
}

/// The points of a grid (`[(path, values), ...]`, first axis fastest), rows `lo..hi`.
#[pyfunction]
#[pyo3(signature = (axes, lo=None, hi=None))]
fn grid_points<'py>(py: Python<'py>, axes: Vec<(String, Vec<f64>)>, lo: Option<usize>, hi: Option<usize>) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    let grid = autobal::sweep::Grid::new(axes.into_iter().map(|(p, v)| autobal::sweep::Axis::new(p, v)).collect()).map_err(|e| py_err(py, e))?;
    let (lo, hi) = (lo.unwrap_or(0), hi.unwrap_or(grid.len()).min(grid.len()));
    let k = grid.axes.len();
    let pts = grid.points(lo..hi.max(lo));
    PyArray1::from_vec(py, pts).reshape([hi.max(lo) - lo, k])
}

/// An axis from its text form (`drive.b=0.5:12.5:5`, `planar.m3=0.01,0.03`).
#[pyfunction]
fn parse_axis(py: Python<'_>, spec: &str) -> PyResult<(String, Vec<f64>)> {
    let a = autobal::sweep::Axis::parse(spec).map_err(|e| py_err(py, e))?;
    Ok((a.path, a.values))
}

/// Shard `k` of `n` (0-based) of `total` points: `(lo, hi)`.
#[pyfunction]
fn shard(py: Python<'_>, total: usize, k: usize, n: usize) -> PyResult<(usize, usize)> {
    let r = autobal::sweep::shard(total, k, n).map_err(|e| py_err(py, e))?;
    Ok((r.start, r.end))
}

/// Every parameter path of the planar problem with its description.
#[pyfunction]
fn planar_paths() -> Vec<(&'static str, &'static str)> {
    PlanarProblem::parameter_paths().iter().map(|p| (p.path, p.doc)).collect()
}

/// The figures of `command`'s result on a config (as [`spatial_config`] reads it), computed as
/// the CLI computes them: JSON `[{"id", "title", "figure"}, ...]`, `figure` Plotly's
/// `{data, layout}` (the description the report draws). `options`: JSON of the CLI's options
/// ([`autobal_commands::figures_api::Options`]).
#[pyfunction]
#[pyo3(signature = (command, text, dict, source, sets, options="{}"))]
fn figures(
    py: Python<'_>,
    command: &str,
    text: Option<&str>,
    dict: Option<&Bound<'_, PyDict>>,
    source: &str,
    sets: Vec<(String, Bound<'_, PyAny>)>,
    options: &str,
) -> PyResult<String> {
    let root = table(py, text, dict, source, sets)?;
    let o: autobal_commands::figures_api::Options = serde_json::from_str(options).map_err(|e| py_err(py, autobal::Error::invalid("options", e.to_string())))?;
    let (command, source) = (command.to_string(), source.to_string());
    let v = commands_call(py, move |control| autobal_commands::figures_api::figures_json(&command, &root, &source, &o, control))?;
    Ok(v.to_string())
}

/// `autobal report`: the HTML report of the config file `config` (with `sets`, the CLI's
/// `--set KEY=VALUE`) written to the folder `out` by the same code; the papers' reproductions
/// with `papers` or without a config. Returns the path of `index.html`.
#[pyfunction]
#[pyo3(signature = (config, sets, out, quick=false, papers=false))]
fn report(py: Python<'_>, config: Option<std::path::PathBuf>, sets: Vec<String>, out: std::path::PathBuf, quick: bool, papers: bool) -> PyResult<String> {
    use autobal_commands::command::{Command, ConfigSource};
    // the same `report::Args` and `run` as the CLI (the folder checked before any section runs)
    let args = autobal_commands::report::Args { config: ConfigSource::file(config.as_deref(), &sets), out, quick, papers };
    let (index, failed) = commands_call(py, move |control| {
        let out = args.run(control)?;
        // interrupted (Ctrl-C): an error; written with a run that failed (the CLI's exit 2):
        // the path, and a `UserWarning` with the CLI's line (review 23)
        if let Some(why) = &out.incomplete {
            anyhow::bail!("{why}");
        }
        Ok((out.index, out.failed))
    })?;
    if let Some(why) = failed {
        let msg = std::ffi::CString::new(why.replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyUserWarning>(), &msg, 1)?;
    }
    Ok(index.display().to_string())
}

/// `autobal merge`: the shards' CSV files (each with its `STEM.json` beside it, in any order)
/// checked and joined into the unsharded sweep's `STEM.csv` and `STEM.json` at the stem `out`
/// (and `STEM.parquet` with `parquet`, the CLI's `--parquet`), by the CLI's `merge::Args` and
/// `run`. Returns the merged JSON text (the `STEM.json` written) and the paths written.
#[pyfunction]
#[pyo3(signature = (shards, out, parquet=false))]
fn merge(py: Python<'_>, shards: Vec<std::path::PathBuf>, out: std::path::PathBuf, parquet: bool) -> PyResult<(String, Vec<String>)> {
    use autobal_commands::command::{Command, Output};
    let args = autobal_commands::merge::Args { shards, out, parquet };
    commands_call(py, move |c| {
        let o = args.run(c)?;
        let files = [Some(&o.csv), Some(&o.json_path), o.parquet.as_ref()].into_iter().flatten().map(|p| p.display().to_string()).collect();
        Ok((o.json()?.to_string(), files))
    })
}

/// `autobal export-model`: a linear rotor written as `STEM.toml` and `STEM_{M,C,G,K}.mtx` into
/// the folder `out`, by the CLI's `export_model::Args` and `run`: the rotor of the config file
/// `config` (with `sets`, the CLI's `--set`), or of the tables `dict`, or without either paper
/// 004's rotor; `out`, `stem` `None`: the CLI's defaults (`Args::default()`). Returns the
/// command's JSON text, `{"files": [...]}` (the paths written).
#[pyfunction]
#[pyo3(signature = (config, dict, sets, out=None, stem=None))]
fn export_model(
    py: Python<'_>,
    config: Option<std::path::PathBuf>,
    dict: Option<&Bound<'_, PyDict>>,
    sets: Vec<(String, Bound<'_, PyAny>)>,
    out: Option<std::path::PathBuf>,
    stem: Option<String>,
) -> PyResult<String> {
    use autobal_commands::command::{Command, ConfigSource, Output};
    let config = match dict {
        // tables: the overrides applied here, the matrices' files read from the working folder
        Some(d) => ConfigSource::tables(table(py, None, Some(d), "dict", sets)?, "dict"),
        // a file (or none): the CLI's `--config` and `--set`, read by the same code
        None => {
            let mut set = vec![];
            for (k, v) in &sets {
                set.push(format!("{k}={}", to_toml(v, k)?));
            }
            ConfigSource::file(config.as_deref(), &set)
        }
    };
    let d = autobal_commands::export_model::Args { config, ..Default::default() };
    let args = autobal_commands::export_model::Args { out: out.unwrap_or(d.out), stem: stem.unwrap_or(d.stem), config: d.config };
    let v = commands_call(py, move |c| args.run(c)?.json())?;
    Ok(v.to_string())
}

/// The `autobal` command line on `argv` (the program name first): what the binary does, with
/// the GIL released; returns the exit code. The wheel's `autobal` console script
/// (`autobal._cli:main`) calls it.
#[pyfunction]
fn cli_main(py: Python<'_>, argv: Vec<String>) -> i32 {
    py.detach(move || autobal_cli::main_with_args(argv))
}

/// How this extension was compiled (the Cargo profile of the `autobal-py` crate, which the
/// workspace's library crates share): `profile` ("release" or "debug": the base profile, so
/// `--profile dev` says "debug"), `opt_level` ("0" to "3", "s", "z"), `debug_assertions` and
/// `debug_info` (booleans). Timings are comparable with the release CLI only for an extension
/// with `opt_level` "3" and no debug assertions (bench/scaling.py checks it).
#[pyfunction]
fn build_info(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("profile", env!("AUTOBAL_BUILD_PROFILE"))?;
    d.set_item("opt_level", env!("AUTOBAL_BUILD_OPT_LEVEL"))?;
    d.set_item("debug_assertions", cfg!(debug_assertions))?;
    d.set_item("debug_info", env!("AUTOBAL_BUILD_DEBUG") == "true")?;
    Ok(d)
}

#[pymodule]
fn _autobal(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SUMMARY_COLUMNS", autobal::sweep::SUMMARY_COLUMNS.to_vec())?;
    m.add("SPATIAL_SUMMARY_COLUMNS", autobal::sweep::SPATIAL_SUMMARY_COLUMNS.to_vec())?;
    m.add("LINEAR_SUMMARY_COLUMNS", autobal::sweep::LINEAR_SUMMARY_COLUMNS.to_vec())?;
    m.add("SCHEMA", config::SCHEMA.iter().map(|(t, ks)| (*t, ks.to_vec())).collect::<Vec<_>>())?;
    m.add("DEFAULT_SPATIAL", config::DEFAULT_SPATIAL)?;
    m.add("DEFAULT_PLANAR", config::DEFAULT_PLANAR)?;
    m.add_class::<PySpatial>()?;
    m.add_class::<PyPlanar>()?;
    m.add_class::<linear_rotor::PyLinearRotor>()?;
    m.add_class::<linear_rotor::PyLinearSpec>()?;
    m.add_function(wrap_pyfunction!(linear_rotor::linear_rotor_run, m)?)?;
    m.add_function(wrap_pyfunction!(linear_rotor::linear_rotor_map_figures, m)?)?;
    m.add_function(wrap_pyfunction!(spatial_config, m)?)?;
    m.add_function(wrap_pyfunction!(planar_config, m)?)?;
    m.add_function(wrap_pyfunction!(spatial_report, m)?)?;
    m.add_function(wrap_pyfunction!(command_json, m)?)?;
    m.add_function(wrap_pyfunction!(stability_map, m)?)?;
    m.add_function(wrap_pyfunction!(map_cells, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_batch, m)?)?;
    m.add_function(wrap_pyfunction!(spatial_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_command, m)?)?;
    m.add_function(wrap_pyfunction!(spatial_basins, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_report, m)?)?;
    m.add_function(wrap_pyfunction!(check_batch, m)?)?;
    m.add_function(wrap_pyfunction!(grid_points, m)?)?;
    m.add_function(wrap_pyfunction!(parse_axis, m)?)?;
    m.add_function(wrap_pyfunction!(shard, m)?)?;
    m.add_function(wrap_pyfunction!(planar_paths, m)?)?;
    m.add_function(wrap_pyfunction!(cli_main, m)?)?;
    m.add_function(wrap_pyfunction!(figures, m)?)?;
    m.add_function(wrap_pyfunction!(report, m)?)?;
    m.add_function(wrap_pyfunction!(merge, m)?)?;
    m.add_function(wrap_pyfunction!(export_model, m)?)?;
    m.add_function(wrap_pyfunction!(build_info, m)?)?;
    m.add("COMMANDS_WITH_FIGURES", autobal_commands::figures_api::COMMANDS_WITH_FIGURES.to_vec())?;
    m.add("COMMANDS", autobal_cli::command_names())?;
    Ok(())
}
