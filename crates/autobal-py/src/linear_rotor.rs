//! `autobal._autobal.LinearRotor`: a linear rotor–bearing model from its matrices (issue 19;
//! `autobal.from_ross` in `python/autobal/_ross.py` builds one from a `ross.Rotor`), with its
//! unbalances, balancer planes and speed-dependent bearings, or from a `[linear_rotor]` config
//! (`LinearRotor.from_config`); the structure's Campbell eigenvalues, the balanced state's
//! stability over speed, the run-up in time (`simulate`: the CLI's run, through the same
//! `autobal_commands::linear_rotor` functions), the reduction, the export.

use autobal::linear_rotor::config::LinearRotorConfig;
use autobal::linear_rotor::{BalancerPlane, Layout, LinearRotor, SpeedBearing, Unbalance};
use autobal_commands::linear_rotor as cmd;
use numpy::{PyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A linear rotor `M q'' + (C + Ω G) q' + K q = f` (DOFs per node `x, y` or `x, y, α, β`).
#[pyclass(name = "LinearRotor", module = "autobal._autobal")]
pub struct PyLinearRotor {
    rotor: LinearRotor,
    /// The rest of the config (`omega_max`, `modes`, `[drive]`, `[integration]`) when read from
    /// a file ([`PyLinearRotor::from_config`]); its `rotor` is not used (`rotor` is).
    cfg: Option<LinearRotorConfig>,
}

impl PyLinearRotor {
    /// The config the commands run: the file's settings with this rotor, or (a rotor built from
    /// matrices) a config without `[drive]` and with `[integration]`'s defaults, as
    /// `autobal export-model` writes it.
    fn config(&self) -> autobal::Result<LinearRotorConfig> {
        match &self.cfg {
            Some(c) => Ok(LinearRotorConfig { rotor: self.rotor.clone(), ..c.clone() }),
            None => {
                let empty = autobal::config::Table::new();
                let integration = autobal::config::integration(&autobal::config::Section::of(&empty, "integration"), 10.0)?;
                Ok(LinearRotorConfig {
                    rotor: self.rotor.clone(),
                    source: "matrices",
                    omega_max: None,
                    operating_speed: None,
                    modes: None,
                    drive: None,
                    integration,
                })
            }
        }
    }
}

/// An error of the library named as a `[linear_rotor]` config names the field: the model's
/// `linear_rotor.balancers[i]`, `linear_rotor.unbalances[i]` as the config's
/// `linear_rotor.balancer[i]`, `linear_rotor.unbalance[i]` (the renames of the config reader,
/// `autobal::linear_rotor::config`, so that Python's errors read as the CLI's).
fn config_names(e: autobal::Error) -> autobal::Error {
    use autobal::Error as E;
    let rename =
        |f: String| f.replacen("linear_rotor.balancers[", "linear_rotor.balancer[", 1).replacen("linear_rotor.unbalances[", "linear_rotor.unbalance[", 1);
    match e {
        E::InvalidParameter { field, reason } => E::InvalidParameter { field: rename(field), reason },
        E::TooLarge { what, size, limit, reason } => E::TooLarge { what: rename(what), size, limit, reason },
        e => e,
    }
}

/// [`crate::py_err`] of an error named as the config names its field ([`config_names`]).
fn err(py: Python<'_>, e: autobal::Error) -> PyErr {
    crate::py_err(py, config_names(e))
}

/// The library's check of every field of `rotor` ([`LinearRotor::validate`], as the CLI's
/// config reader calls it), its error named as the config names the field.
fn validated(py: Python<'_>, rotor: &LinearRotor) -> PyResult<()> {
    rotor.validate().map_err(|e| err(py, e))
}

/// A node or ball count from Python: a whole number ≥ 0, else the config reader's error on
/// `field`.
fn count(py: Python<'_>, field: String, v: i64) -> PyResult<usize> {
    usize::try_from(v).map_err(|_| err(py, autobal::Error::invalid(field, format!("expected a whole number ≥ 0, got {v}"))))
}

fn square(py: Python<'_>, name: &str, a: &PyReadonlyArray2<'_, f64>) -> PyResult<(usize, Vec<f64>)> {
    let s = a.shape();
    if s[0] != s[1] {
        return Err(err(py, autobal::Error::invalid(format!("linear_rotor.{name}"), format!("is {} × {}, must be square", s[0], s[1]))));
    }
    let v: Vec<f64> = a.as_array().iter().copied().collect();
    Ok((s[0], v))
}

impl PyLinearRotor {
    /// The `N × N` matrix `linear_rotor.NAME` as a row-major vector: square, the size of `m`.
    fn checked(&self, py: Python<'_>, name: &str, v: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<f64>> {
        let (nn, a) = square(py, name, v)?;
        let n = self.rotor.dofs();
        if nn != n {
            return Err(err(py, autobal::Error::invalid(format!("linear_rotor.{name}"), format!("is {nn} × {nn}, m is {n} × {n}"))));
        }
        Ok(a)
    }
}

#[pymethods]
impl PyLinearRotor {
    /// `LinearRotor(m, c, g, k, per_node=4)`: the matrices as 2-D float arrays (`N × N`);
    /// `per_node` the DOFs of every node (2: `x, y`; 4: `x, y, alpha, beta`) or a list of them,
    /// one per node (e.g. a shaft's nodes 4 and the support masses of its bearings 2).
    #[new]
    #[pyo3(signature = (m, c, g, k, per_node=None))]
    fn new(
        py: Python<'_>,
        m: PyReadonlyArray2<'_, f64>,
        c: PyReadonlyArray2<'_, f64>,
        g: PyReadonlyArray2<'_, f64>,
        k: PyReadonlyArray2<'_, f64>,
        per_node: Option<Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let layout = |p: usize| match p {
            2 => Ok(Layout::Translation),
            4 => Ok(Layout::TranslationTilt),
            o => Err(err(py, autobal::Error::invalid("per_node", format!("must be 2 (x, y) or 4 (x, y, alpha, beta), got {o}")))),
        };
        let (n, m) = square(py, "m", &m)?;
        let mut r = match per_node {
            Some(p) if p.extract::<usize>().is_err() => {
                let each: Vec<usize> = p.extract()?;
                let layouts = each.iter().map(|p| layout(*p)).collect::<PyResult<Vec<_>>>()?;
                let r = LinearRotor::with_layouts(&layouts);
                if r.dofs() != n || layouts.is_empty() {
                    return Err(err(py, autobal::Error::invalid("per_node", format!("gives {} DOFs, m is {n} × {n}", r.dofs()))));
                }
                r
            }
            p => {
                let per = p.map(|p| p.extract::<usize>()).transpose()?.unwrap_or(4);
                let l = layout(per)?;
                if n % per != 0 {
                    return Err(err(py, autobal::Error::invalid("linear_rotor.m", format!("{n} DOFs is no multiple of {per}"))));
                }
                LinearRotor::zeros(n / per, l)
            }
        };
        r.m = m;
        for (name, a) in [("c", &c), ("g", &g), ("k", &k)] {
            let (nn, v) = square(py, name, a)?;
            if nn != n {
                return Err(err(py, autobal::Error::invalid(format!("linear_rotor.{name}"), format!("is {nn} × {nn}, m is {n} × {n}"))));
            }
            match name {
                "c" => r.c = v,
                "g" => r.g = v,
                _ => r.k = v,
            }
        }
        // the library's check, as the CLI's config reader makes it (finite entries, M symmetric
        // positive definite, G skew): refused here, not when the rotor is first used
        validated(py, &r)?;
        Ok(PyLinearRotor { rotor: r, cfg: None })
    }

    /// `LinearRotor.from_config(path, set=None)`: the rotor of a `[linear_rotor]` config file
    /// (matrix files relative to it, or the shaft builder's tables) with its `omega_max`,
    /// `modes`, `[drive]` and `[integration]`, as `autobal simulate --config PATH` reads it;
    /// `set`: `{"table.key": value}`, the CLI's `--set` (`linear_rotor.KEY`, `drive.KEY`,
    /// `integration.KEY`).
    #[staticmethod]
    #[pyo3(signature = (path, set=None))]
    fn from_config(py: Python<'_>, path: std::path::PathBuf, set: Option<Bound<'_, PyDict>>) -> PyResult<Self> {
        let mut sets = vec![];
        for (k, v) in set.iter().flat_map(|d| d.iter()) {
            let k: String = k.extract()?;
            let v = crate::to_toml(&v, &k)?;
            sets.push(format!("{k}={v}"));
        }
        let cfg = crate::commands_call(py, move |_| {
            let (root, _) = cmd::read_set(Some(path.as_path()), &sets)?;
            if !cmd::is_linear(&root) {
                anyhow::bail!("config {}: not a linear rotor config (it has no [linear_rotor] table)", path.display());
            }
            cmd::from_table(&root, path.parent().unwrap_or(std::path::Path::new(".")))
        })?;
        Ok(PyLinearRotor { rotor: cfg.rotor.clone(), cfg: Some(cfg) })
    }

    /// Run the rotor in time as `autobal simulate` does (the same functions): the config's
    /// `[drive]`, or from rest at constant acceleration to `omega_max` (default the config's,
    /// else 1.5 × the 4th natural frequency) in 1000 revolutions; the config's reduction, or
    /// `modes` interior mode pairs (0: the full model); samples every `dt` s. Returns an
    /// `autobal.LinearSimulation`: the CSV's columns as arrays, the JSON summary, the figures.
    /// A run that stops before its end raises `SimulationError` (`.result`: the samples).
    #[pyo3(signature = (dt=None, omega_max=None, modes=None))]
    fn simulate<'py>(&self, py: Python<'py>, dt: Option<f64>, omega_max: Option<f64>, modes: Option<usize>) -> PyResult<Bound<'py, PyAny>> {
        let mut cfg = self.config().map_err(|e| err(py, e))?;
        if let Some(w) = omega_max {
            autobal::error::positive("omega_max", w).map_err(|e| err(py, e))?;
            cfg.omega_max = Some(w);
        }
        if let Some(p) = modes {
            cfg.modes = (p > 0).then_some(p);
        }
        let (cols, summary, figures) = crate::commands_call(py, move |control| {
            let w = cmd::default_omega_max(&cfg)?;
            let setup = cmd::setup(&cfg, w, dt)?;
            let mut cols: Vec<Vec<f64>> = vec![vec![]; setup.columns.len()];
            let run = cmd::run(&setup, control, |r| {
                for (c, v) in cols.iter_mut().zip(r) {
                    c.push(*v);
                }
                Ok(())
            })?;
            autobal::limits::check_finite("the summary", &run.summary)?;
            let figures: Vec<serde_json::Value> = cmd::plots(&setup, &run.kept)
                .into_iter()
                .map(|(suffix, plot)| serde_json::json!({ "id": format!("simulation_{suffix}"), "figure": plot.to_plotly() }))
                .collect();
            let summary = cmd::simulate_json(&cfg, &run.summary, &setup.reduction, run.wall);
            Ok((setup.columns.into_iter().zip(cols).collect::<Vec<_>>(), summary.to_string(), serde_json::Value::from(figures).to_string()))
        })?;
        let out = PyDict::new(py);
        for (name, c) in cols {
            out.set_item(name, PyArray1::from_vec(py, c))?;
        }
        py.import("autobal._linear_rotor")?.getattr("_simulation")?.call1((out, summary, figures))
    }

    /// Add an unbalance `m·e` (kg·m) at `node`, angle `phase` (rad), axial `offset` (m).
    /// Checked at once as the CLI checks a config's `[[linear_rotor.unbalance]]` (the node
    /// exists, the numbers are finite): refused with `InvalidParameter` naming
    /// `linear_rotor.unbalance[i].FIELD`, the rotor left as it was.
    #[pyo3(signature = (node, me, phase=0.0, offset=0.0))]
    fn add_unbalance(&mut self, py: Python<'_>, node: i64, me: f64, phase: f64, offset: f64) -> PyResult<()> {
        let i = self.rotor.unbalances.len();
        let node = count(py, format!("linear_rotor.unbalance[{i}].node"), node)?;
        let mut r = self.rotor.clone();
        r.unbalances.push(Unbalance { node, me, phase, offset });
        validated(py, &r)?;
        self.rotor = r;
        Ok(())
    }

    /// Add a balancer plane at `node`: race `radius` (m), `balls`, `ball_mass` (kg), `drag`
    /// per ball (N·m·s), axial `offset` (m); real balls by the config's keys of
    /// `[[linear_rotor.balancer]]` (`autobal::balls::BallPhysics`): `contact` (the balls touch:
    /// Hertz contact of spheres of `ball_diameter` m, default steel of `ball_mass`, with
    /// `restitution` and `contact_stiffness`), `rolling_resistance` (dimensionless, with its
    /// `slip_rate` 1/s); absent: the papers' point masses. Checked at once as the CLI checks a
    /// config's `[[linear_rotor.balancer]]` (the node exists, radius and ball mass positive, drag
    /// not negative, at least one ball, the balls fit their race): refused with
    /// `InvalidParameter` naming `linear_rotor.balancer[i].FIELD`, the rotor left as it was.
    /// Run-ups take real balls; the stationary analyses refuse them (`NoLinearisation`).
    #[pyo3(signature = (node, radius, balls, ball_mass, drag=0.0, offset=0.0, *, contact=false, ball_diameter=None, restitution=None, contact_stiffness=None, rolling_resistance=None, slip_rate=None))]
    #[allow(clippy::too_many_arguments)]
    fn add_balancer(
        &mut self,
        py: Python<'_>,
        node: i64,
        radius: f64,
        balls: i64,
        ball_mass: f64,
        drag: f64,
        offset: f64,
        contact: bool,
        ball_diameter: Option<f64>,
        restitution: Option<f64>,
        contact_stiffness: Option<f64>,
        rolling_resistance: Option<f64>,
        slip_rate: Option<f64>,
    ) -> PyResult<()> {
        let i = self.rotor.balancers.len();
        let node = count(py, format!("linear_rotor.balancer[{i}].node"), node)?;
        let balls = count(py, format!("linear_rotor.balancer[{i}].balls"), balls)?;
        let mut r = self.rotor.clone();
        r.balancers.push(BalancerPlane { node, radius, balls, ball_mass, drag, offset });
        let d = autobal::balls::BallPhysics::default();
        let physics = autobal::balls::BallPhysics {
            diameter: ball_diameter,
            contact,
            restitution: restitution.unwrap_or(d.restitution),
            contact_stiffness,
            rolling_resistance: rolling_resistance.unwrap_or(d.rolling_resistance),
            slip_rate: slip_rate.unwrap_or(d.slip_rate),
        };
        // the contact law acts only through contact, the slip rate only with rolling resistance:
        // given without them they would have no effect, so they are refused (as the config
        // reader refuses them)
        let given = |k: &str| match k {
            "ball_diameter" => ball_diameter.is_some(),
            "restitution" => restitution.is_some(),
            "contact_stiffness" => contact_stiffness.is_some(),
            "slip_rate" => slip_rate.is_some(),
            _ => false,
        };
        if let Some((k, why)) = autobal::balls::moot_key(&physics, given) {
            let lacks = match why {
                autobal::balls::Moot::Contact => "contact=True",
                autobal::balls::Moot::Rolling => "a rolling_resistance",
            };
            return Err(err(py, autobal::Error::invalid(format!("linear_rotor.balancer[{i}].{k}"), format!("has no effect without {lacks}"))));
        }
        if physics.is_active() {
            // planes before this one without real balls: point masses (the default physics)
            r.ball_physics.resize(i, d);
            r.ball_physics.push(physics);
        }
        validated(py, &r)?;
        self.rotor = r;
        Ok(())
    }

    /// Add a bearing at `node` tabulated over `speeds` (rad/s): `k` and `c` are `len(speeds) × 4`
    /// (`xx, xy, yx, yy`), added to `K`, `C` at each speed (linear interpolation); `link`: the
    /// node at its other side (ROSS's `n_link`, blocks `[[B, −B], [−B, B]]`), `None`: ground.
    /// Checked at once (the nodes exist, the speeds increase, the numbers are finite): refused
    /// with `InvalidParameter` naming `linear_rotor.bearings[i].FIELD`, the rotor left as it was.
    #[pyo3(signature = (node, speeds, k, c, link=None))]
    fn add_speed_bearing(
        &mut self,
        py: Python<'_>,
        node: i64,
        speeds: Vec<f64>,
        k: PyReadonlyArray2<'_, f64>,
        c: PyReadonlyArray2<'_, f64>,
        link: Option<i64>,
    ) -> PyResult<()> {
        let i = self.rotor.speed_bearings.len();
        let node = count(py, format!("linear_rotor.bearings[{i}].node"), node)?;
        let link = link.map(|l| count(py, format!("linear_rotor.bearings[{i}].link"), l)).transpose()?;
        let rows = |a: &PyReadonlyArray2<'_, f64>, name: &str| -> PyResult<Vec<[f64; 4]>> {
            let s = a.shape();
            if s[1] != 4 || s[0] != speeds.len() {
                return Err(err(
                    py,
                    autobal::Error::invalid(format!("bearing.{name}"), format!("must be len(speeds) × 4 = {} × 4, got {} × {}", speeds.len(), s[0], s[1])),
                ));
            }
            let a = a.as_array();
            Ok((0..s[0]).map(|i| [a[[i, 0]], a[[i, 1]], a[[i, 2]], a[[i, 3]]]).collect())
        };
        let (k, c) = (rows(&k, "k")?, rows(&c, "c")?);
        let mut r = self.rotor.clone();
        r.speed_bearings.push(SpeedBearing { node, link, speeds: speeds.clone(), k, c });
        validated(py, &r)?;
        self.rotor = r;
        Ok(())
    }

    /// The rotor's polar moment of inertia about its spin axis `I_p` (kg m², the balls
    /// excluded): the spin's inertia under a torque drive (0: not known, torque drives refused).
    #[getter]
    fn polar_inertia(&self) -> f64 {
        self.rotor.polar_inertia
    }

    #[setter]
    fn set_polar_inertia(&mut self, py: Python<'_>, v: f64) -> PyResult<()> {
        autobal::error::non_negative("linear_rotor.polar_inertia", v).map_err(|e| err(py, e))?;
        self.rotor.polar_inertia = v;
        Ok(())
    }

    /// The drag on the spin `c_θ` (N m s): the torque `−c_θ Ω` under a torque drive.
    #[getter]
    fn spin_damping(&self) -> f64 {
        self.rotor.spin_damping
    }

    #[setter]
    fn set_spin_damping(&mut self, py: Python<'_>, v: f64) -> PyResult<()> {
        autobal::error::non_negative("linear_rotor.spin_damping", v).map_err(|e| err(py, e))?;
        self.rotor.spin_damping = v;
        Ok(())
    }

    /// The angular-acceleration stiffness `K_st` of the run-ups' `Ω̇ K_st q` (ROSS's `Ksdt`;
    /// `N × N` nested lists, empty where none is set: then `G/2`).
    #[getter]
    fn spin_stiffness(&self) -> Vec<Vec<f64>> {
        let n = self.rotor.dofs();
        self.rotor.spin_stiffness.chunks(n.max(1)).map(<[f64]>::to_vec).collect()
    }

    #[setter]
    fn set_spin_stiffness(&mut self, py: Python<'_>, v: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let (nn, a) = square(py, "spin_stiffness", &v)?;
        let n = self.rotor.dofs();
        if nn != n {
            return Err(err(py, autobal::Error::invalid("linear_rotor.spin_stiffness", format!("is {nn} × {nn}, m is {n} × {n}"))));
        }
        if let Some(i) = a.iter().position(|x| !x.is_finite()) {
            return Err(err(py, autobal::Error::invalid(format!("linear_rotor.spin_stiffness[{},{}]", i / n, i % n), "must be finite")));
        }
        self.rotor.spin_stiffness = a;
        Ok(())
    }

    /// The inertia fixed to the rotor `M_rot` (kg, kg m², in axes turning with it; the Rust
    /// `LinearRotor::rotor_fixed_mass`, a config's `linear_rotor.rotor_fixed_mass`): `N × N`
    /// nested lists, empty where none is set. Set: symmetric, `M + T(φ) M_rot T(φ)ᵀ` positive
    /// definite at every angle `φ` (the library's `LinearRotor::validate`; refused, the rotor
    /// is left as it was).
    #[getter]
    fn rotor_fixed_mass(&self) -> Vec<Vec<f64>> {
        let n = self.rotor.dofs();
        self.rotor.rotor_fixed_mass.chunks(n.max(1)).map(<[f64]>::to_vec).collect()
    }

    #[setter]
    fn set_rotor_fixed_mass(&mut self, py: Python<'_>, v: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let a = self.checked(py, "rotor_fixed_mass", &v)?;
        let mut r = self.rotor.clone();
        r.rotor_fixed_mass = a;
        r.validate().map_err(|e| err(py, e))?;
        self.rotor = r;
        Ok(())
    }

    /// The tilt chart fixed to the rotor `Σ` (spin angle `s = ½ q_rᵀ Σ q_r`; the Rust
    /// `LinearRotor::spin_chart`, a config's `linear_rotor.spin_chart`): `N × N` nested lists,
    /// empty where none is set. Set: symmetric (the library's `LinearRotor::validate`; refused,
    /// the rotor is left as it was).
    #[getter]
    fn spin_chart(&self) -> Vec<Vec<f64>> {
        let n = self.rotor.dofs();
        self.rotor.spin_chart.chunks(n.max(1)).map(<[f64]>::to_vec).collect()
    }

    #[setter]
    fn set_spin_chart(&mut self, py: Python<'_>, v: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let a = self.checked(py, "spin_chart", &v)?;
        let mut r = self.rotor.clone();
        r.spin_chart = a;
        r.validate().map_err(|e| err(py, e))?;
        self.rotor = r;
        Ok(())
    }

    /// Number of DOFs.
    #[getter]
    fn dofs(&self) -> usize {
        self.rotor.dofs()
    }

    /// The DOFs' names in order, as the config's DOF table writes them (`"x0"`, `"alpha0"`, …;
    /// a node without tilts has `x`, `y` only).
    #[getter]
    fn dof_names(&self) -> Vec<String> {
        (0..self.rotor.dofs()).map(|i| autobal::linear_rotor::config::dof_key(&self.rotor, i)).collect()
    }

    /// Undamped natural frequencies at rest (rad/s), optionally with the balls as rings.
    /// Refused where the stiffness is not positive semi-definite: a mode with `ω² < 0`
    /// ([`autobal::linear_rotor::static_divergence`]) diverges at rest and has no natural
    /// frequency (it read 0 rad/s, as a rigid-body mode; the CLI says so in the same words);
    /// [`natural_frequencies_squared`](Self::natural_frequencies_squared) gives `ω²` with its sign.
    #[pyo3(signature = (with_balls=false))]
    fn natural_frequencies(&self, py: Python<'_>, with_balls: bool) -> PyResult<Vec<f64>> {
        let squared = self.rotor.at_speed(0.0).natural_frequencies_squared(&[], with_balls).map_err(|e| err(py, e))?;
        let divergent = autobal::linear_rotor::static_divergence(&squared);
        if !divergent.is_empty() {
            let why = autobal_commands::linear_rotor::divergence_text(&divergent);
            return Err(err(py, autobal::Error::invalid("k", format!("{}; natural_frequencies_squared() gives every ω² with its sign", why.trim_end()))));
        }
        // LinearRotor::natural_frequencies's map of the same eigenvalues (one eigenproblem)
        Ok(squared.into_iter().map(|l| l.max(0.0).sqrt()).collect())
    }

    /// The squares `ω²` of the undamped natural frequencies at rest ((rad/s)², ascending),
    /// with their sign: negative for a mode that diverges at rest (a stiffness that is not
    /// positive semi-definite), 0 to round-off for a rigid-body mode
    /// ([`autobal::linear_rotor::LinearRotor::natural_frequencies_squared`]).
    #[pyo3(signature = (with_balls=false))]
    fn natural_frequencies_squared(&self, py: Python<'_>, with_balls: bool) -> PyResult<Vec<f64>> {
        self.rotor.at_speed(0.0).natural_frequencies_squared(&[], with_balls).map_err(|e| err(py, e))
    }

    /// The structure's eigenvalues (no balls) at each speed (rad/s): `(real, imag)` lists,
    /// `len(speeds) × 2N`, sorted by imaginary part (ROSS's `run_campbell` without balls).
    fn campbell(&self, py: Python<'_>, speeds: Vec<f64>) -> PyResult<(Vec<Vec<f64>>, Vec<Vec<f64>>)> {
        let r = self.rotor.clone();
        let out = crate::interruptible(py, move |_| speeds.iter().map(|w| r.structure_eigenvalues(*w)).collect::<autobal::Result<Vec<_>>>())?
            .map_err(|e| err(py, e))?;
        Ok((out.iter().map(|v| v.iter().map(|z| z.re).collect()).collect(), out.iter().map(|v| v.iter().map(|z| z.im).collect()).collect()))
    }

    /// The balanced state's stability over `(0, omega_max]` at `samples` speeds, on the model
    /// reduced to `modes` mode pairs (`None`: the full model): the JSON of `autobal stability`'s
    /// general route (`model`, `stationary_state`, `stable_ranges`, `points`, …) plus `reduction`
    /// and `operating`: the verdict at `operating_speed` (a speed or range with its unit, or a
    /// number in rad/s, read as a config's `linear_rotor.operating_speed`), computed by the
    /// CLI's code (`autobal_commands::general::operating_at`, `operating_json`); `null` without
    /// one, as the CLI's. Ctrl-C stops it and raises `KeyboardInterrupt` whose `result` is the
    /// JSON of what was analysed until then, marked as the CLI's (`complete: false`,
    /// `stopped`: the speeds analysed, or the complete scan and the operating speeds solved).
    #[pyo3(signature = (omega_max, samples=200, modes=None, operating_speed=None))]
    fn stability(&self, py: Python<'_>, omega_max: f64, samples: usize, modes: Option<usize>, operating_speed: Option<Bound<'_, PyAny>>) -> PyResult<String> {
        // read as the config reader reads the key: the same forms, the same refusals
        let operating = match &operating_speed {
            Some(v) if !v.is_none() => Some(autobal::linear_rotor::config::operating_speed(&crate::to_toml(v, "operating_speed")?).map_err(|e| err(py, e))?),
            _ => None,
        };
        let r = self.rotor.clone();
        let (res, signal) = crate::interruptible_kept(py, move |control| -> anyhow::Result<serde_json::Value> {
            let speeds = autobal::rotor_stability::speed_grid(omega_max, samples)?;
            let (rotor, red) = match modes.filter(|m| *m > 0) {
                Some(p) => {
                    let red = autobal::linear_rotor::reduce::reduce(&r, p, &[])?;
                    (red.rotor.clone(), Some(red))
                }
                None => (r, None),
            };
            // as `autobal stability` on a linear rotor config (`stability::Args::linear_rotor`):
            // the scan under the control, then the verdict at the operating speed; stopped
            // (Ctrl-C), what was analysed is kept and marked (`complete: false`, `stopped`), as
            // the CLI's JSON (it was dropped: review 24)
            let g = autobal_commands::general::GeneralRotor::linear(rotor);
            let out = autobal::rotor_stability::stability_over_speed_with(&g.rotor, &speeds, control)?;
            let (st, op, stopped) = autobal_commands::stability::kept_scan(out, speeds.len(), control, |st, control| {
                operating.map(|w| autobal_commands::general::operating_at(&g, w, "linear_rotor.operating_speed", st, control)).transpose()
            })?;
            let mut v = serde_json::to_value(&st).map_err(|e| autobal::Error::invalid("stability", e.to_string()))?;
            v["omega_max"] = serde_json::json!(omega_max);
            v["reduction"] = serde_json::to_value(&red).map_err(|e| autobal::Error::invalid("reduction", e.to_string()))?;
            v["operating"] = op.as_ref().map_or(serde_json::Value::Null, autobal_commands::general::operating_json);
            Ok(autobal_commands::stability::mark_json(v, &stopped))
        })?;
        let res = match (res, signal) {
            // Ctrl-C: `KeyboardInterrupt`, its `result` the JSON kept
            (Ok(v), Some(e)) => return Err(crate::with_result(py, e, v.to_string())),
            (Err(_), Some(e)) => return Err(e),
            (r, None) => r.map_err(|e| match e.downcast::<autobal::Error>() {
                Ok(e) => err(py, e),
                Err(e) => crate::any_err(py, e),
            })?,
        };
        Ok(res.to_string())
    }

    /// The config text and Matrix Market files (`[(name, text)]`) of the rotor, as
    /// `autobal export-model` writes them (read by `autobal stability --config STEM.toml`).
    /// The rotor is checked first as the CLI's config reader checks what it reads
    /// ([`LinearRotor::validate`]): a rotor that config could not hold (a non-finite number, a
    /// node that does not exist) is refused with `InvalidParameter`, nothing written.
    fn export(&self, py: Python<'_>, stem: &str) -> PyResult<(String, Vec<(String, String)>)> {
        validated(py, &self.rotor)?;
        Ok(autobal::linear_rotor::config::export(&self.rotor, stem))
    }
}

/// Options of [`linear_rotor_run`] as JSON (`{"x": "path=lo:hi:n", "n": 8, ...}`), taken one by
/// one; what is left is an error naming the first unknown option.
struct Options {
    command: String,
    map: serde_json::Map<String, serde_json::Value>,
}

impl Options {
    fn take(&mut self, key: &str) -> Option<serde_json::Value> {
        self.map.remove(key).filter(|v| !v.is_null())
    }
    fn text(&mut self, key: &str) -> anyhow::Result<Option<String>> {
        Ok(match self.take(key) {
            None => None,
            Some(serde_json::Value::String(s)) => Some(s),
            Some(serde_json::Value::Number(n)) => Some(n.to_string()),
            Some(v) => return Err(autobal::Error::invalid(key, format!("expected a string or a number, got {v}")).into()),
        })
    }
    fn count(&mut self, key: &str) -> anyhow::Result<Option<usize>> {
        Ok(match self.take(key) {
            None => None,
            Some(v) => Some(v.as_u64().ok_or_else(|| autobal::Error::invalid(key, format!("expected a whole number ≥ 0, got {v}")))? as usize),
        })
    }
    fn texts(&mut self, key: &str) -> anyhow::Result<Vec<String>> {
        match self.take(key) {
            None => Ok(vec![]),
            Some(serde_json::Value::Array(a)) => {
                a.into_iter().map(|v| v.as_str().map(String::from).ok_or_else(|| autobal::Error::invalid(key, "expected a list of strings").into())).collect()
            }
            Some(v) => Err(autobal::Error::invalid(key, format!("expected a list of strings, got {v}")).into()),
        }
    }
    fn done(self) -> anyhow::Result<()> {
        match self.map.keys().next() {
            Some(k) => {
                Err(autobal::Error::invalid(k.as_str(), format!("not an option of {} on a linear rotor config (see help(autobal.run))", self.command)).into())
            }
            None => Ok(()),
        }
    }
}

/// A `[linear_rotor]` config's command for `autobal.run(COMMAND, config=PATH)` (issue 19): the
/// JSON text of `stability` (`omega_max`, `samples`), `simulate` (`dt`: the summary),
/// `basins` (`n`), `sweep` (`x`, `y`, `axis`, `shard` "K/N", `threads`: the sweep's JSON) and
/// `map` (`x`, `y`, `omega`, `boundary`, `threads`: the axes, `margin` and `verdict` per cell as
/// `len(y) × len(x)` lists, the bisected boundary points with the axis bisected, `along`), as the CLI computes them; `sets`: the
/// CLI's `--set` (`linear_rotor.KEY`, `drive.KEY`, `integration.KEY`); `options`: the keyword
/// options as JSON.
#[pyfunction]
#[pyo3(signature = (command, path, sets, options, dict=None))]
pub fn linear_rotor_run(
    py: Python<'_>,
    command: &str,
    path: Option<std::path::PathBuf>,
    sets: Vec<(String, Bound<'_, PyAny>)>,
    options: &str,
    dict: Option<Bound<'_, PyDict>>,
) -> PyResult<(String, String)> {
    let mut set = vec![];
    for (k, v) in &sets {
        set.push(format!("{k}={}", crate::to_toml(v, k)?));
    }
    let dict = dict_table(dict)?;
    let map = match serde_json::from_str::<serde_json::Value>(options) {
        Ok(serde_json::Value::Object(m)) => m,
        _ => return Err(err(py, autobal::Error::invalid("options", "expected keyword options"))),
    };
    let mut o = Options { command: command.to_string(), map };
    let command = command.to_string();
    // what the result object draws and tabulates beside the JSON: `figures` ([{id, figure}]),
    // `csv` (basins: the CLI's CSV)
    let mut extra = serde_json::json!({});
    let extra_out = &mut extra;
    let v = crate::commands_call(py, move |control| -> anyhow::Result<serde_json::Value> {
        use autobal_commands::command::{Command as _, Output as _};
        let config = LinearSource::read(path, dict, &set)?;
        let threads = o.count("threads")?;
        let pool = match threads {
            Some(0) => anyhow::bail!("threads: must be at least 1"),
            Some(t) => Some(rayon::ThreadPoolBuilder::new().num_threads(t).build()?),
            None => None,
        };
        let within = |f: &mut (dyn FnMut() -> anyhow::Result<serde_json::Value> + Send)| match &pool {
            Some(p) => p.install(&mut *f),
            None => f(),
        };
        match command.as_str() {
            "stability" => {
                let args = autobal_commands::stability::Args {
                    config: config.source(),
                    omega_max: o.text("omega_max")?,
                    samples: o.count("samples")?,
                    ..Default::default()
                };
                o.done()?;
                let out = args.run(control)?;
                if let Some(why) = out.stopped() {
                    anyhow::bail!("{why}");
                }
                let figures: Vec<serde_json::Value> = out.figures()?.iter().map(|f| f.to_json()).collect();
                *extra_out = serde_json::json!({ "figures": figures });
                out.json()
            }
            "simulate" => {
                let dt = o.take("dt").map(|v| v.as_f64().ok_or_else(|| autobal::Error::invalid("dt", "expected a number"))).transpose()?;
                o.done()?;
                let cfg = cmd::from_table(&config.root, &config.dir)?;
                let w = cmd::default_omega_max(&cfg)?;
                let setup = cmd::setup(&cfg, w, dt)?;
                let run = cmd::run(&setup, control, |_| Ok(()))?;
                let mut v = cmd::simulate_json(&cfg, &run.summary, &setup.reduction, run.wall);
                if let Some(s) = &run.summary.stopped {
                    v["stopped"] = serde_json::json!(s);
                }
                Ok(v)
            }
            "basins" => {
                let n = o.count("n")?.unwrap_or(16);
                o.done()?;
                let args = autobal_commands::basins::Args { config: config.source(), n };
                within(&mut || {
                    let out = args.run(control)?;
                    if let Some(ends) = &out.linear {
                        let plot = cmd::basins_plot(&out.angles, ends);
                        *extra_out = serde_json::json!({"figures": [{"id": "basins", "figure": plot.to_plotly()}], "csv": out.csv()});
                    }
                    out.json()
                })
            }
            "sweep" => {
                let mut specs: Vec<String> = o.text("x")?.into_iter().collect();
                if specs.is_empty() {
                    return Err(autobal::Error::invalid("x", "required (the first axis, e.g. x='linear_rotor.drag=0.01:0.1:4')").into());
                }
                specs.extend(o.text("y")?);
                specs.extend(o.texts("axis")?);
                let shard = o.text("shard")?;
                o.done()?;
                let axes = specs.iter().map(|s| autobal::paths::Axis::parse(s)).collect::<autobal::Result<Vec<_>>>()?;
                let grid = autobal::sweep::Grid::new(axes)?;
                let range = match &shard {
                    None => 0..grid.len(),
                    Some(s) => {
                        let bad = || autobal::Error::invalid("shard", format!("{s}: expected K/N with 1 ≤ K ≤ N, e.g. shard='3/8'"));
                        let (k, n) = s.split_once('/').ok_or_else(bad)?;
                        let (k, n): (usize, usize) = (k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
                        if k == 0 {
                            return Err(bad().into());
                        }
                        autobal::sweep::shard(grid.len(), k - 1, n)?
                    }
                };
                let (root, base, problem) = cmd::sweep_base_of(config.root.clone(), &config.dir)?;
                let kn = shard.as_deref().and_then(|s| s.split_once('/')).and_then(|(k, n)| Some((k.trim().parse().ok()?, n.trim().parse().ok()?)));
                within(&mut || {
                    let (mut runs, mut kept) = (vec![], vec![]);
                    let out = autobal::sweep::simulate_grid(
                        &base,
                        &grid,
                        range.clone(),
                        &mut |i, v, r| {
                            runs.push(autobal::sweep::run_json(i, v, r));
                            kept.push((v.to_vec(), r.summary.clone()));
                            true
                        },
                        control,
                    )?;
                    let figures: Vec<serde_json::Value> = cmd::sweep_plots(&grid.paths().iter().map(|p| p.to_string()).collect::<Vec<_>>(), &kept)
                        .into_iter()
                        .map(|(id, plot)| serde_json::json!({"id": id, "figure": plot.to_plotly()}))
                        .collect();
                    *extra_out = serde_json::json!({ "figures": figures });
                    let mut json = autobal::sweep::report(&grid, kn, &range, out.complete(), problem.clone(), std::mem::take(&mut runs));
                    json["definition_checksum"] = serde_json::json!(autobal::sweep::definition_checksum(&root, &grid));
                    json["columns"] = serde_json::json!(autobal::sweep::LINEAR_SUMMARY_COLUMNS);
                    json["values"] = serde_json::json!(json["runs"].as_array().map(|r| r.iter().map(|r| r["values"].clone()).collect::<Vec<_>>()));
                    out.into_result()?;
                    Ok(json)
                })
            }
            "map" => {
                let (Some(x), Some(y)) = (o.text("x")?, o.text("y")?) else {
                    return Err(autobal::Error::invalid("x", "required, with y (e.g. x='omega=100:2000:40', y='linear_rotor.ball_mass=0.01:0.05:5')").into());
                };
                let speed = o.text("omega")?.map(|t| autobal::units::parse_speed("omega", &t)).transpose()?;
                let boundary = match o.take("boundary") {
                    None => false,
                    Some(v) => v.as_bool().ok_or_else(|| autobal::Error::invalid("boundary", "expected True or False"))?,
                };
                o.done()?;
                let (xa, ya) = (autobal::paths::Axis::parse(&x)?, autobal::paths::Axis::parse(&y)?);
                let root = config.root.clone();
                let (mut margin, mut verdict, mut family, mut state, mut points) = (vec![], vec![], vec![], vec![], vec![]);
                within(&mut || {
                    let out = cmd::map_traced(&root, &config.dir, &xa, &ya, speed, boundary, control, &mut |_, cells, pts| {
                        margin.push(cells.iter().map(|c| c.margin).collect::<Vec<_>>());
                        verdict.push(cells.iter().map(|c| c.verdict).collect::<Vec<_>>());
                        family.push(cells.iter().map(|c| c.family_dimension).collect::<Vec<_>>());
                        state.push(cells.iter().map(|c| c.state).collect::<Vec<_>>());
                        points.extend_from_slice(pts);
                        true
                    })?;
                    if !out.complete {
                        return Err(autobal::Error::Interrupted { t: out.rows as f64 / ya.values.len().max(1) as f64 }.into());
                    }
                    // NaN (no stationary state) as null in the JSON; Python turns it back
                    Ok(serde_json::json!({
                        "model": "linear",
                        "x_path": &xa.path, "y_path": &ya.path, "x": &xa.values, "y": &ya.values,
                        "margin": margin.iter().map(|r| r.iter().map(|m| m.is_finite().then_some(*m)).collect::<Vec<_>>()).collect::<Vec<_>>(),
                        "verdict": &verdict, "family_dimension": &family, "state": &state, "boundary": &points,
                    }))
                })
            }
            o => Err(autobal::Error::invalid(
                "command",
                format!("\"{o}\" on a linear rotor config: autobal.run takes stability, simulate, map, sweep, basins (campbell, export-model: LinearRotor's methods and the CLI)"),
            )
            .into()),
        }
    })?;
    Ok((v.to_string(), extra.to_string()))
}

/// A `[linear_rotor]` config with the bytes of its matrix files, read once
/// ([`autobal::linear_rotor::spec::LinearRotorSpec`]): the base of `autobal.sweep` and
/// `autobal.simulate_batch` on a linear rotor config. What a Dask worker needs to rebuild it
/// is its TOML text (`toml`) and the files' bytes by the names the config gives them (`files()`):
/// `LinearSpec.from_parts(toml, files)` reads the same config again, without the file system.
#[pyclass(name = "LinearSpec", module = "autobal._autobal", frozen)]
pub struct PyLinearSpec {
    /// The config and its files.
    pub spec: autobal::linear_rotor::spec::LinearRotorSpec,
}

#[pymethods]
impl PyLinearSpec {
    /// `LinearSpec(path, sets)`: the config file `path` with `sets` (`[(key, value)]`, the
    /// CLI's `--set`), its matrix files read relative to its folder.
    #[new]
    fn new(py: Python<'_>, path: std::path::PathBuf, sets: Vec<(String, Bound<'_, PyAny>)>) -> PyResult<Self> {
        let mut set = vec![];
        for (k, v) in &sets {
            set.push(format!("{k}={}", crate::to_toml(v, k)?));
        }
        let spec = crate::commands_call(py, move |_| {
            let (root, _) = cmd::read_set(Some(path.as_path()), &set)?;
            if !cmd::is_linear(&root) {
                anyhow::bail!("config {}: not a linear rotor config (it has no [linear_rotor] table)", path.display());
            }
            Ok(cmd::spec(&root, path.parent().unwrap_or(std::path::Path::new(".")))?)
        })?;
        Ok(PyLinearSpec { spec })
    }

    /// `LinearSpec.from_dict(tables, sets)`: a dict of a `[linear_rotor]` config's tables with
    /// `sets` (the CLI's `--set`), its matrix files read relative to the working folder (as
    /// `autobal.run` reads a dict's).
    #[staticmethod]
    fn from_dict(py: Python<'_>, tables: Bound<'_, PyDict>, sets: Vec<(String, Bound<'_, PyAny>)>) -> PyResult<Self> {
        let mut set = vec![];
        for (k, v) in &sets {
            set.push(format!("{k}={}", crate::to_toml(v, k)?));
        }
        let root = dict_table(Some(tables))?;
        let spec = crate::commands_call(py, move |_| {
            let src = LinearSource::read(None, root, &set)?;
            Ok(cmd::spec(&src.root, &src.dir)?)
        })?;
        Ok(PyLinearSpec { spec })
    }

    /// The config from its TOML text and its files' bytes (`{name: bytes}`), as
    /// [`PyLinearSpec::toml`] and [`PyLinearSpec::files`] give them.
    #[staticmethod]
    fn from_parts(py: Python<'_>, toml: &str, files: std::collections::HashMap<String, Bound<'_, pyo3::types::PyBytes>>) -> PyResult<Self> {
        let root = autobal::config::parse(toml, "linear rotor config").map_err(|e| err(py, e))?;
        let bytes: std::collections::HashMap<String, Vec<u8>> = files.iter().map(|(k, v)| (k.clone(), v.as_bytes().to_vec())).collect();
        let spec =
            autobal::linear_rotor::spec::LinearRotorSpec::new(root, &mut |p| bytes.get(p).cloned().ok_or_else(|| format!("{p}: not among the files given")))
                .map_err(|e| err(py, e))?;
        Ok(PyLinearSpec { spec })
    }

    /// The config's tables as TOML text.
    #[getter]
    fn toml(&self) -> String {
        toml::to_string(self.spec.root()).unwrap_or_default()
    }

    /// The matrix files' bytes by the names the config gives them.
    fn files<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, v) in self.spec.files() {
            d.set_item(k, pyo3::types::PyBytes::new(py, v))?;
        }
        Ok(d)
    }
}

/// The map's figure of a `[linear_rotor]` config file or dict (`stability_map`, what `autobal
/// map --config PATH --out STEM` draws): JSON `[{"id", "title", "figure"}]`, computed by the
/// CLI's `map::Args` on the config's tables (a file's matrix files relative to it, a dict's to
/// the working folder; `sets` its `--set`); `options` the
/// JSON of [`autobal_commands::figures_api::Options`] (`x`, `y` as `KEY=LO:HI:N`, `omega`,
/// `boundary`).
#[pyfunction]
#[pyo3(signature = (path, sets, options, dict=None))]
pub fn linear_rotor_map_figures(
    py: Python<'_>,
    path: Option<std::path::PathBuf>,
    sets: Vec<(String, Bound<'_, PyAny>)>,
    options: &str,
    dict: Option<Bound<'_, PyDict>>,
) -> PyResult<String> {
    use autobal_commands::command::Output as _;
    let mut set = vec![];
    for (k, v) in &sets {
        set.push(format!("{k}={}", crate::to_toml(v, k)?));
    }
    let dict = dict_table(dict)?;
    let o: autobal_commands::figures_api::Options = serde_json::from_str(options).map_err(|e| err(py, autobal::Error::invalid("options", e.to_string())))?;
    let v = crate::commands_call(py, move |control| {
        let (Some(x), Some(y)) = (&o.x, &o.y) else { anyhow::bail!("x: required, with y (KEY=LO:HI:N, e.g. x='speed=100:2000:40')") };
        let config = LinearSource::read(path, dict, &set)?;
        let args = autobal_commands::map::Args {
            // the tables read once, the matrix files relative to the file's folder (a dict's: the
            // working folder)
            config: config.source(),
            x: autobal_commands::map::parse_axis("--x", x)?,
            y: autobal_commands::map::parse_axis("--y", y)?,
            omega: o.omega.clone(),
            boundary: o.boundary.unwrap_or(false),
            ..Default::default()
        };
        let out = args.prepare()?.run(control, autobal_commands::map::Rows::Figure)?;
        if let Some(why) = out.stopped() {
            anyhow::bail!("{why}");
        }
        Ok(serde_json::Value::Array(out.figures()?.iter().map(|f| f.to_json()).collect()))
    })?;
    Ok(v.to_string())
}

/// A dict of tables (a `[linear_rotor]` config from Python) as a TOML table.
fn dict_table(dict: Option<Bound<'_, PyDict>>) -> PyResult<Option<autobal::config::Table>> {
    match dict {
        None => Ok(None),
        Some(d) => match crate::to_toml(d.as_any(), "")? {
            toml::Value::Table(t) => Ok(Some(t)),
            _ => unreachable!("a dict converts to a table"),
        },
    }
}

/// A `[linear_rotor]` config as the Python functions take it: a file (its matrix files relative
/// to its folder) or a dict of tables (its matrix files relative to the working folder), with
/// the overrides applied as the CLI's `--set` applies them ([`cmd::apply_set`]).
struct LinearSource {
    root: autobal::config::Table,
    /// The folder the matrix files are read relative to.
    dir: std::path::PathBuf,
    /// The config file, if the config is one.
    file: Option<std::path::PathBuf>,
}

impl LinearSource {
    fn read(path: Option<std::path::PathBuf>, dict: Option<autobal::config::Table>, set: &[String]) -> anyhow::Result<Self> {
        let (root, dir, file) = match (path, dict) {
            (Some(p), _) => {
                let (root, _) = cmd::read_set(Some(p.as_path()), set)?;
                let dir = p.parent().unwrap_or(std::path::Path::new(".")).to_path_buf();
                (root, dir, Some(p))
            }
            (None, Some(mut root)) => {
                for s in set {
                    cmd::apply_set(&mut root, s)?;
                }
                (root, std::path::PathBuf::from("."), None)
            }
            (None, None) => anyhow::bail!("config: give a [linear_rotor] config file or a dict of its tables"),
        };
        if !cmd::is_linear(&root) {
            anyhow::bail!(
                "config {}: not a linear rotor config (it has no [linear_rotor] table)",
                file.as_ref().map_or("dict".to_string(), |p| p.display().to_string())
            );
        }
        Ok(LinearSource { root, dir, file })
    }

    /// The config as the commands' `Args` take it (the tables read once, the folder of its files).
    fn source(&self) -> autobal_commands::command::ConfigSource {
        let name = self.file.as_ref().map_or("dict".to_string(), |p| p.display().to_string());
        autobal_commands::command::ConfigSource::Tables { root: self.root.clone(), source: name, dir: self.dir.clone() }
    }
}
