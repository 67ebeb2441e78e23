//! Real balls, shared by the dynamic models: finite size and ball–ball contact, rolling
//! resistance between ball and race, and the closed forms that follow from them (how far apart
//! touching balls sit, the largest unbalance `n` touching balls can cancel, where friction lets a
//! ball rest). The models' balls are otherwise point masses with viscous drag; every force here is
//! a *generalised force on a ball's angle* `ψ_j` relative to the housing (a torque about the race
//! centre E, N·m), so a model adds it to its ball equations and nothing else: forces between two
//! balls, or between a ball and its race, do no work on the rotor's own coordinates when the
//! balls' angles are measured relative to the housing.
//!
//! ## Finite size and contact
//! A ball of mass `m` is a steel sphere of diameter `d = (6 m/(π ρ_steel))^{1/3}`,
//! `ρ_steel = 7850 kg/m³` ([`STEEL_DENSITY`]), unless a diameter is given. On a race of (centre)
//! radius `r`, the centres of two balls `Δ = ψ_b − ψ_a` apart are a chord `c = 2 r |sin(Δ/2)|`
//! apart; they overlap by `δ = d − c` when `δ > 0`, so touching balls sit `Δ_c = 2 asin(d/(2r))`
//! apart ([`min_separation`]). The contact is a linear spring–damper along the line of centres
//! (Kelvin–Voigt), `F = k_c δ + c_c δ̇` while `δ > 0`, with `c_c = 2 ζ sqrt(k_c m_e)`,
//! `m_e = m/(2 cos²(Δ_c/2))` (the pair's reduced mass along the chord) and
//! `ζ = −ln e / sqrt(π² + ln² e)`: a free impact then ends with the relative speed reversed and
//! multiplied by exactly `e`, the restitution coefficient, whatever the impact speed (a
//! Hunt–Crossley law `k δ^{3/2}(1 + α δ̇)` has no closed form for its restitution). The
//! generalised forces are `Q_b = −Q_a = F ∂c/∂ψ_b = F r cos(Δ/2) sgn Δ`.
//!
//! `k_c` is a penalty: the end states converge to the rigid-ball ones as `1/k_c` (tested). Its
//! default puts the contact's frequency `sqrt(k_c/m_e)` at 20 times the model's reference
//! frequency (the shaft's `sqrt(k/m0)` in the planar model; 5760 rad/s for paper 004's rotor):
//! the overlap under the tangential loads of a balancer (a few N; tens at the highest speeds) is
//! then below 0.2 % of the diameter, an error of the positions below 1e-3 rad. The cost grows
//! as `sqrt(k_c)` while balls touch (the explicit method's step is bounded by the contact's
//! period; measured in docs/notes/balls.md): 25 times the default moves paper 004's forward peak by
//! 2.4e-5 of its value.

//! Why compliant and not event-driven impacts: the state that matters is balls *resting* against
//! each other for hundreds of seconds (an impact law with `e < 1` reaches it only through an
//! infinite sequence of ever smaller impacts, which needs a separate sticking mode, its own
//! release condition, and an impulse through the rotor's mass matrix at every impact); a
//! compliant contact gives resting contact, impacts and release from one smooth law, and its
//! cost is that of resolving the contact's period while balls touch (measured in docs/notes/balls.md;
//! event-driven impacts were not built, so not measured).

//! ## Rolling resistance
//! A ball rolling on its race feels a rolling-resistance moment `M = μ_r (d/2) N`, `N` the
//! race's normal force on the ball: at the ball's centre a tangential force `μ_r N` against the
//! relative motion, i.e. `Q_j = −μ_r r N_j sgn ψ̇_j` (`μ_r`, dimensionless, is the config's
//! `rolling_resistance`; steel on hardened steel 1e-4 to 1e-3). While `|ψ̇_j|` is zero the moment
//! is whatever holds the ball, up to `μ_r r N_j`. The sign function is regularised,
//! `sgn v ≈ v/sqrt(v² + v_ε²)` (`slip_rate` `v_ε`, rad/s): a held ball creeps at a speed below
//! `v_ε` instead of resting, so its position drifts at most `v_ε t`; the error vanishes with
//! `v_ε` (tested against the exact resting set).
//!
//! A ball at rest relative to the rotor at constant speed `ω` whose race centre E whirls with
//! `P` (E's position relative to the axis, in rotor axes) feels the torque
//! `m r ω² P·(i e^{iψ})` pulling it towards `−P` against `μ_r r N`, `N = m ω² (r + P·e^{iψ})`:
//! it can rest where `|P| |sin(ψ − arg P)| ≤ μ_r (r + |P| cos(ψ − arg P))` ([`can_rest`]). Near
//! the balanced state `|P| ≪ r`, so the balls stop as soon as `|P| ≲ μ_r r`: the residual
//! eccentricity of E is about `μ_r r`, to first order independent of speed and ball mass (both
//! sides scale with `m ω²`).

use crate::error::{finite, non_negative, positive, Error, Result};
use serde::Serialize;
use std::f64::consts::PI;

/// Density of bearing steel (kg/m³), for the default ball diameter.
pub const STEEL_DENSITY: f64 = 7850.0;

/// A ball counts as sticking while `|ψ̇| ≤ STICK_FACTOR v_ε` ([`EventCounter`]).
pub const STICK_FACTOR: f64 = 10.0;

/// Contact frequency over the model's reference frequency for the default contact stiffness.
pub const DEFAULT_CONTACT_FREQUENCY_RATIO: f64 = 20.0;

/// Diameter (m) of a steel ball of `mass` (kg): `(6 m/(π ρ_steel))^{1/3}`.
pub fn steel_diameter(mass: f64) -> f64 {
    (6.0 * mass / (PI * STEEL_DENSITY)).cbrt()
}

/// Angle between the centres of two touching balls of diameter `d` on a race of radius `r`:
/// `Δ_c = 2 asin(d/(2r))` (needs `d ≤ 2r`).
pub fn min_separation(d: f64, r: f64) -> f64 {
    2.0 * (d / (2.0 * r)).min(1.0).asin()
}

/// Largest resultant `|Σ_j e^{iψ_j}|` of `n` balls whose centres are at least `Δ_c` apart on the
/// circle: the packed arc, `sin(nΔ_c/2)/sin(Δ_c/2)` (point masses: `n`). The largest unbalance
/// `n` balls of mass `m` on radius `r` can cancel is `m r` times this ([`capacity`]).
pub fn packed_resultant(n: usize, sep: f64) -> f64 {
    if n == 0 {
        return 0.0;
    }
    if sep <= 0.0 {
        return n as f64;
    }
    ((n as f64 * sep / 2.0).sin() / (sep / 2.0).sin()).max(0.0)
}

/// The largest unbalance (kg·m) `n` balls of mass `m` and diameter `d` on a race of radius `r`
/// can cancel: `m r sin(nΔ_c/2)/sin(Δ_c/2)`, the touching balls packed in one arc.
pub fn capacity(n: usize, m: f64, d: f64, r: f64) -> f64 {
    m * r * packed_resultant(n, min_separation(d, r))
}

/// Whether a ball at angle `psi` can rest on its race under friction `mu_r` when the race centre
/// is at `p = (p_x, p_y)` from the axis (rotor axes, constant speed): the pull towards `−P`,
/// `|P| |sin(ψ − arg P)|`, is at most `μ_r (r + P·e^{iψ})`. Returns the margin
/// `μ_r (r + P·e^{iψ}) − |P·(i e^{iψ})|` (non-negative where the ball can rest).
pub fn can_rest(mu_r: f64, r: f64, p: (f64, f64), psi: f64) -> f64 {
    let (s, c) = psi.sin_cos();
    let along = p.0 * c + p.1 * s;
    let across = -p.0 * s + p.1 * c;
    mu_r * (r + along) - across.abs()
}

/// The ball physics of one set of balls, as the config gives it (`planar.*`, or a spatial
/// balancer plane's keys). The default is the papers' point masses: no contact, no rolling
/// resistance, and then none of it costs anything.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BallPhysics {
    /// Ball diameter (m); `None`: a steel ball of the set's mass ([`steel_diameter`]).
    pub diameter: Option<f64>,
    /// Whether balls collide and cannot overlap (finite size).
    pub contact: bool,
    /// Restitution coefficient `e` of a ball–ball impact, in `[0, 1]` (default 0.5).
    pub restitution: f64,
    /// Contact stiffness `k_c` (N/m); `None`: contact frequency 20 times the model's reference.
    pub contact_stiffness: Option<f64>,
    /// Rolling-resistance coefficient `μ_r` (dimensionless; moment `μ_r (d/2) N`); 0: none.
    pub rolling_resistance: f64,
    /// Regularisation `v_ε` of the rolling resistance's sign (rad/s).
    pub slip_rate: f64,
}

/// The papers' point masses: steel-ball diameter if contact is switched on, no contact, `e = 0.5`,
/// the default contact stiffness, no rolling resistance, `v_ε = 1e-4 rad/s`.
impl Default for BallPhysics {
    fn default() -> Self {
        BallPhysics { diameter: None, contact: false, restitution: 0.5, contact_stiffness: None, rolling_resistance: 0.0, slip_rate: 1e-4 }
    }
}

crate::builder::builder!(
    /// Builder of [`BallPhysics`], starting from the point masses ([`BallPhysics::default`]).
    /// `build()` checks the fields alone, named as the planar section spells them
    /// (`planar.restitution`, `planar.ball_diameter`, ...); [`BallPhysicsBuilder::build_for`]
    /// also checks them against a set of balls (do they fit on the race?) under another
    /// section's name (`balancer`, `balancer2`).
    ///
    /// ```
    /// use autobal::balls::BallPhysics;
    /// let b = BallPhysics::builder().contact(true).restitution(0.8).rolling_resistance(1e-3).build().unwrap();
    /// assert!(b.is_active() && b.diameter.is_none());
    /// let e = BallPhysics::builder().restitution(1.5).build().unwrap_err();
    /// assert!(e.to_string().starts_with("planar.restitution"), "{e}");
    /// // 40 mm balls do not fit twice on a 15 mm race
    /// let e = BallPhysics::builder().contact(true).diameter(Some(0.04)).build_for("balancer", 0.02, 0.015, 2).unwrap_err();
    /// assert!(e.to_string().starts_with("balancer.ball_diameter"), "{e}");
    /// let e = BallPhysics::builder().slip_rate(0.0).build_for("balancer2", 0.02, 0.1, 2).unwrap_err();
    /// assert!(e.to_string().starts_with("balancer2.slip_rate"), "{e}");
    /// ```
    BallPhysicsBuilder for BallPhysics, |b| b.validate("planar", 0.0, 0.0, 0);
    diameter: Option<f64>, contact: bool, restitution: f64, contact_stiffness: Option<f64>, rolling_resistance: f64, slip_rate: f64,
);

impl BallPhysicsBuilder {
    /// Validate for `n` balls of `mass` (kg) on a race of radius `r` (m), errors naming
    /// `PREFIX.field` ([`BallPhysics::validate`]), and return the physics.
    pub fn build_for(self, prefix: &str, mass: f64, r: f64, n: usize) -> Result<BallPhysics> {
        self.inner.validate(prefix, mass, r, n)?;
        Ok(self.inner)
    }
}

/// The keys of a ball set that act only through contact (the contact law).
pub const CONTACT_KEYS: [&str; 3] = ["ball_diameter", "restitution", "contact_stiffness"];

/// Why a key of a ball set given with these balls has no effect, if one does: the first of
/// [`CONTACT_KEYS`] given without contact (`Moot::Contact`), else `slip_rate` given without a
/// rolling resistance (`Moot::Rolling`); `given` says which keys were given. One rule for every
/// front end: the planar and spatial configs warn ([`crate::config::ball_physics_of`]), the
/// linear rotor's config and Python's `add_balancer` refuse.
pub fn moot_key(b: &BallPhysics, given: impl Fn(&str) -> bool) -> Option<(&'static str, Moot)> {
    if !b.contact {
        if let Some(k) = CONTACT_KEYS.into_iter().find(|k| given(k)) {
            return Some((k, Moot::Contact));
        }
    }
    (b.rolling_resistance == 0.0 && given("slip_rate")).then_some(("slip_rate", Moot::Rolling))
}

/// What a moot key of [`moot_key`] lacks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Moot {
    /// A contact-law key without contact.
    Contact,
    /// `slip_rate` without a rolling resistance.
    Rolling,
}

impl BallPhysics {
    /// A builder starting from [`BallPhysics::default`].
    pub fn builder() -> BallPhysicsBuilder {
        BallPhysicsBuilder::default()
    }

    /// Whether any of it is switched on.
    pub fn is_active(&self) -> bool {
        self.contact || self.rolling_resistance > 0.0
    }

    /// The balls' diameter (m) for ball mass `mass`.
    pub fn diameter(&self, mass: f64) -> f64 {
        self.diameter.unwrap_or_else(|| steel_diameter(mass))
    }

    /// Check the fields for `n` balls of `mass` on a race of radius `r`; errors name
    /// `PREFIX.ball_diameter`, `PREFIX.restitution`, ... (`prefix` as the config spells the set,
    /// e.g. `planar`).
    pub fn validate(&self, prefix: &str, mass: f64, r: f64, n: usize) -> Result<()> {
        let f = |k: &str| format!("{prefix}.{k}");
        if let Some(d) = self.diameter {
            positive(&f("ball_diameter"), d)?;
        }
        let rr = finite(&f("restitution"), self.restitution)?;
        if !(0.0..=1.0).contains(&rr) {
            return Err(Error::invalid(f("restitution"), format!("must lie in [0, 1], got {}", crate::error::fmt_num(rr))));
        }
        if let Some(k) = self.contact_stiffness {
            positive(&f("contact_stiffness"), k)?;
        }
        non_negative(&f("rolling_resistance"), self.rolling_resistance)?;
        if self.rolling_resistance > 1.0 {
            return Err(Error::invalid(
                f("rolling_resistance"),
                format!("{} is not a rolling resistance (at most 1; steel on steel is ~1e-3)", crate::error::fmt_num(self.rolling_resistance)),
            ));
        }
        positive(&f("slip_rate"), self.slip_rate)?;
        if self.contact && n > 0 && mass > 0.0 && r > 0.0 {
            let d = self.diameter(mass);
            if d >= 2.0 * r {
                return Err(Error::invalid(
                    f("ball_diameter"),
                    format!("{} m does not fit a race of radius {} m", crate::error::fmt_num(d), crate::error::fmt_num(r)),
                ));
            }
            let sep = min_separation(d, r);
            if n as f64 * sep > 2.0 * PI * (1.0 + 1e-12) {
                return Err(Error::invalid(
                    f("ball_diameter"),
                    format!(
                        "{n} balls of diameter {} m do not fit on a race of radius {} m (at most {})",
                        crate::error::fmt_num(d),
                        crate::error::fmt_num(r),
                        (2.0 * PI / sep).floor()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Absolute tolerance (rad/s) for a ball's rate given the model's own `atol`: with rolling
    /// resistance at most `0.1 v_ε`, so the integrator resolves the regularised sign (a held
    /// ball creeps below `v_ε`); unchanged otherwise.
    pub fn rate_tolerance(&self, atol: f64) -> f64 {
        if self.rolling_resistance > 0.0 {
            atol.min(0.1 * self.slip_rate)
        } else {
            atol
        }
    }

    /// Check that no two balls overlap at the start (`psi`: the initial angles); the error names
    /// `field` (e.g. `drive.psi0`).
    pub fn check_initial(&self, field: &str, mass: f64, r: f64, psi: &[f64]) -> Result<()> {
        if !self.contact {
            return Ok(());
        }
        let d = self.diameter(mass);
        // the pairs that can touch (neighbours on the race above ALL_PAIRS_UP_TO balls: if two
        // balls overlap, so do two neighbours), O(n log n) instead of O(n²)
        let mut first = None;
        for_each_contact_pair(psi.len(), psi, |a, b| {
            let (a, b) = (a.min(b), a.max(b));
            if first.is_none_or(|f| (a, b) < f) && chord(r, psi[b] - psi[a]) < d * (1.0 - 1e-9) {
                first = Some((a, b));
            }
        });
        match first {
            Some((a, b)) => Err(Error::invalid(
                field,
                format!(
                    "balls {} and {} overlap at the start ({} m apart, diameter {} m)",
                    a + 1,
                    b + 1,
                    crate::error::fmt_num(chord(r, psi[b] - psi[a])),
                    crate::error::fmt_num(d)
                ),
            )),
            None => Ok(()),
        }
    }
}

/// Chord between two points `dpsi` apart on a circle of radius `r`.
fn chord(r: f64, dpsi: f64) -> f64 {
    2.0 * r * (0.5 * dpsi).sin().abs()
}

/// `x` wrapped into `(−π, π]`.
fn wrap(x: f64) -> f64 {
    let y = x.rem_euclid(2.0 * PI);
    if y > PI {
        y - 2.0 * PI
    } else {
        y
    }
}

/// The linear spring–damper contact between two balls (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLaw {
    /// Ball diameter `d` (m).
    pub diameter: f64,
    /// Race radius `r` (m).
    pub r: f64,
    /// Stiffness `k_c` (N/m).
    pub stiffness: f64,
    /// Damping `c_c = 2ζ sqrt(k_c m_e)` (N·s/m).
    pub damping: f64,
}

impl ContactLaw {
    /// The law for balls of `mass` and `diameter` on radius `r` with restitution `e` and
    /// stiffness `k_c`.
    pub fn new(mass: f64, diameter: f64, r: f64, restitution: f64, stiffness: f64) -> Self {
        let m_e = reduced_mass(mass, diameter, r);
        ContactLaw { diameter, r, stiffness, damping: 2.0 * damping_ratio(restitution) * (stiffness * m_e).sqrt() }
    }

    /// The generalised force on ball `b` (ball `a` gets its negative) when `b` is `dpsi` ahead
    /// of `a` and their angles separate at `drate` (rad/s); 0 when they do not overlap.
    #[inline]
    pub fn pair(&self, dpsi: f64, drate: f64) -> f64 {
        let h = 0.5 * wrap(dpsi);
        let (s, c) = h.sin_cos();
        let overlap = self.diameter - 2.0 * self.r * s.abs();
        if overlap <= 0.0 {
            return 0.0;
        }
        let arm = self.r * c * s.signum(); // ∂chord/∂ψ_b
        let force = self.stiffness * overlap - self.damping * arm * drate;
        force * arm
    }

    /// Elastic energy `½ k_c δ²` stored in the pair (J).
    pub fn energy(&self, dpsi: f64) -> f64 {
        let overlap = self.diameter - chord(self.r, dpsi);
        if overlap > 0.0 {
            0.5 * self.stiffness * overlap * overlap
        } else {
            0.0
        }
    }

    /// Overlap `δ = d − c` of a pair `dpsi` apart (m; negative: a gap).
    pub fn overlap(&self, dpsi: f64) -> f64 {
        self.diameter - chord(self.r, dpsi)
    }
}

/// Reduced mass of a ball pair along their line of centres when touching:
/// `m/(2 cos²(Δ_c/2)) = m/(2(1 − d²/(4r²)))`.
pub fn reduced_mass(mass: f64, diameter: f64, r: f64) -> f64 {
    mass / (2.0 * (1.0 - diameter * diameter / (4.0 * r * r)))
}

/// Damping ratio `ζ = −ln e/sqrt(π² + ln² e)` of a linear contact with restitution `e`
/// (`e = 0`: critical damping, `ζ = 1`).
pub fn damping_ratio(restitution: f64) -> f64 {
    if restitution <= 0.0 {
        return 1.0;
    }
    let l = restitution.ln();
    -l / (PI * PI + l * l).sqrt()
}

/// Rolling resistance on a ball: `−μ_r r N v/sqrt(v² + v_ε²)` (N·m) at relative rate `v`.
#[inline]
pub fn rolling_torque(mu_r: f64, r: f64, normal: f64, rate: f64, slip_rate: f64) -> f64 {
    -mu_r * r * normal * rate / (rate * rate + slip_rate * slip_rate).sqrt()
}

/// Everything a right-hand side needs for one set of `n` balls, resolved once per run.
#[derive(Debug, Clone)]
pub struct BallForces {
    /// Number of balls.
    pub n: usize,
    /// Race radius (m).
    pub r: f64,
    /// The contact law, when balls collide.
    pub contact: Option<ContactLaw>,
    /// `μ_r`.
    pub rolling_resistance: f64,
    /// `v_ε` (rad/s).
    pub slip_rate: f64,
}

impl BallForces {
    /// The forces of `physics` on `n` balls of `mass` on radius `r`; `reference_frequency`
    /// (rad/s) sets the default contact stiffness. `None` when nothing is switched on (then the
    /// model's equations are the point-mass ones, at no cost).
    pub fn new(physics: &BallPhysics, mass: f64, r: f64, n: usize, reference_frequency: f64) -> Option<Self> {
        if !physics.is_active() || n == 0 {
            return None;
        }
        let contact = if physics.contact && n > 1 {
            let d = physics.diameter(mass);
            let m_e = reduced_mass(mass, d, r);
            let w = DEFAULT_CONTACT_FREQUENCY_RATIO * reference_frequency;
            let k = physics.contact_stiffness.unwrap_or(m_e * w * w);
            Some(ContactLaw::new(mass, d, r, physics.restitution, k))
        } else {
            None
        };
        Some(BallForces { n, r, contact, rolling_resistance: physics.rolling_resistance, slip_rate: physics.slip_rate })
    }

    /// Write the generalised forces `Q_j` (N·m) on the balls' angles into `q`: contact between
    /// every pair (the balls cannot pass each other, so every overlap is a real contact) and
    /// rolling resistance with the race's normal force `normal(j)` (N).
    #[inline]
    pub fn torques(&self, psi: &[f64], rate: &[f64], normal: impl Fn(usize) -> f64, q: &mut [f64]) {
        for j in 0..self.n {
            q[j] =
                if self.rolling_resistance > 0.0 { rolling_torque(self.rolling_resistance, self.r, normal(j).max(0.0), rate[j], self.slip_rate) } else { 0.0 };
        }
        if let Some(c) = &self.contact {
            for_each_contact_pair(self.n, psi, |a, b| {
                let f = c.pair(psi[b] - psi[a], rate[b] - rate[a]);
                q[b] += f;
                q[a] -= f;
            });
        }
    }

    /// Elastic energy stored in the contacts (J).
    pub fn contact_energy(&self, psi: &[f64]) -> f64 {
        let Some(c) = &self.contact else { return 0.0 };
        let mut e = 0.0;
        for_each_contact_pair(self.n, psi, |a, b| e += c.energy(psi[b] - psi[a]));
        e
    }
}

/// Up to this many balls every pair is visited (`n(n−1)/2` pairs, no sorting); above it only the
/// `n` pairs of neighbours on the race.
pub const ALL_PAIRS_UP_TO: usize = 16;

/// The pairs `(a, b)` of balls that can touch: every pair for `n ≤` [`ALL_PAIRS_UP_TO`]; above
/// it the `n` pairs of neighbours in the order of the balls' angles on the race (sorted modulo
/// 2π, the last with the first), so the cost is `O(n log n)` instead of `O(n²)`. The two agree
/// whenever only neighbours overlap: a ball overlapping a ball two places away would have to
/// pass through the one between (an overlap of a whole diameter against a contact stiffness
/// chosen so that overlaps stay a small fraction of it, docs/notes/balls.md).
fn for_each_contact_pair(n: usize, psi: &[f64], mut f: impl FnMut(usize, usize)) {
    if n <= ALL_PAIRS_UP_TO {
        for a in 0..n {
            for b in a + 1..n {
                f(a, b);
            }
        }
        return;
    }
    let mut order: Vec<(f64, usize)> = psi.iter().enumerate().map(|(j, p)| (p.rem_euclid(2.0 * PI), j)).collect();
    order.sort_by(|x, y| x.0.total_cmp(&y.0));
    for k in 0..n {
        f(order[k].1, order[(k + 1) % n].1);
    }
}

/// Counts, over a run, the contacts that began and the balls' transitions between sticking
/// (`|ψ̇| ≤ 10 v_ε`: a held ball creeps at `v_ε Q/sqrt(Q_max² − Q²)`, below `10 v_ε` unless its
/// load `Q` is within 0.5 % of the limit `Q_max`) and slipping, from the states at the ends of
/// accepted steps.
#[derive(Debug, Clone, Default)]
pub struct EventCounter {
    /// The pairs `(a, b)`, `a < b`, that overlapped at the last step, sorted: at most `n`
    /// neighbour pairs above [`ALL_PAIRS_UP_TO`] balls, so memory and time are `O(n)` and
    /// `O(n log n)` per step (an `n²` table of pairs was 5 GB for 100 000 balls).
    touching: Vec<(usize, usize)>,
    sticking: Vec<bool>,
    started: bool,
    /// Contacts that began (a pair went from a gap to an overlap).
    pub contacts: u64,
    /// Transitions between sticking and slipping, all balls together.
    pub stick_slip: u64,
}

impl EventCounter {
    /// Observe the balls' angles and rates at the end of a step.
    pub fn observe(&mut self, forces: &BallForces, psi: &[f64], rate: &[f64]) {
        let n = forces.n;
        if !self.started {
            self.started = true;
            self.touching = vec![];
            self.sticking = vec![false; n];
            self.record(forces, psi, rate, false);
        } else {
            self.record(forces, psi, rate, true);
        }
    }

    fn record(&mut self, forces: &BallForces, psi: &[f64], rate: &[f64], count: bool) {
        if let Some(c) = &forces.contact {
            // the pairs that can touch, as the contact forces visit them
            let mut now = vec![];
            for_each_contact_pair(forces.n, psi, |a, b| {
                if c.overlap(psi[b] - psi[a]) > 0.0 {
                    now.push((a.min(b), a.max(b)));
                }
            });
            now.sort_unstable();
            now.dedup();
            if count {
                self.contacts += now.iter().filter(|p| self.touching.binary_search(p).is_err()).count() as u64;
            }
            self.touching = now;
        }
        if forces.rolling_resistance > 0.0 {
            for (j, v) in rate.iter().enumerate().take(forces.n) {
                let now = v.abs() <= STICK_FACTOR * forces.slip_rate;
                if count && now != self.sticking[j] {
                    self.stick_slip += 1;
                }
                self.sticking[j] = now;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steel_ball_of_ten_grams_is_13_mm() {
        // 0.01 kg of steel: V = 1.274e-6 m³, d = 13.45 mm
        let d = steel_diameter(0.01);
        assert!((d - 0.013_45).abs() < 1e-5, "{d}");
        assert!((PI / 6.0 * d.powi(3) * STEEL_DENSITY - 0.01).abs() < 1e-15);
    }

    #[test]
    fn packed_resultant_is_the_best_of_any_arrangement() {
        // brute force over arrangements of 3 balls with separations ≥ Δ_c: none beats the packed arc
        let sep = 0.4;
        let best = packed_resultant(3, sep);
        assert!((best - (1.0 + 2.0 * sep.cos())).abs() < 1e-14);
        let mut found: f64 = 0.0;
        for i in 0..400 {
            for k in 0..400 {
                let a = sep + (2.0 * PI - 3.0 * sep) * i as f64 / 399.0;
                let b = sep + (2.0 * PI - 3.0 * sep) * k as f64 / 399.0;
                if a + b > 2.0 * PI - sep {
                    continue;
                }
                let (x, y) = (1.0 + a.cos() + (a + b).cos(), a.sin() + (a + b).sin());
                found = found.max(x.hypot(y));
            }
        }
        assert!(found <= best + 1e-12 && found > best - 1e-9, "{found} vs {best}");
        assert_eq!(packed_resultant(4, 0.0), 4.0);
    }

    #[test]
    fn contact_force_is_the_gradient_of_its_energy() {
        let law = ContactLaw::new(0.01, 0.0134, 0.06, 1.0, 1e6); // e = 1: no damping
        assert_eq!(law.damping, 0.0);
        let sep = min_separation(0.0134, 0.06);
        for dpsi in [sep * 0.999, -sep * 0.995, sep * 0.9] {
            let h = 1e-7;
            let numeric = -(law.energy(dpsi + h) - law.energy(dpsi - h)) / (2.0 * h);
            let q = law.pair(dpsi, 0.0);
            assert!((q - numeric).abs() < 1e-6 * q.abs(), "{q} {numeric}");
        }
        assert_eq!(law.pair(sep * 1.01, 0.0), 0.0);
    }

    #[test]
    fn the_event_counter_counts_as_every_pair_with_neighbours_only() {
        // 40 balls (above ALL_PAIRS_UP_TO) on a packed race, shuffled, some with whole turns
        // added; over 200 random steps the pairs that begin to overlap, counted from the
        // neighbour pairs in O(n) memory, equal those of all n(n−1)/2 pairs
        let (d, r, n) = (0.006, 0.06, 40);
        let law = ContactLaw::new(0.001, d, r, 0.5, 1e6);
        let forces = BallForces { n, r, contact: Some(law), rolling_resistance: 0.0, slip_rate: 1e-3 };
        let sep = min_separation(d, r);
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let slots: Vec<f64> = (0..n).map(|k| k as f64 * sep * 1.005).collect();
        let mut counter = EventCounter::default();
        let (mut brute, mut before) = (0u64, vec![false; n * n]);
        let rate = vec![0.0; n];
        for step in 0..200 {
            let psi: Vec<f64> = (0..n).map(|j| slots[(j * 17) % n] + (next() - 0.5) * 0.03 * sep + if j % 5 == 0 { 2.0 * PI } else { 0.0 }).collect();
            counter.observe(&forces, &psi, &rate);
            for a in 0..n {
                for b in a + 1..n {
                    let now = law.overlap(psi[b] - psi[a]) > 0.0;
                    if step > 0 && now && !before[a * n + b] {
                        brute += 1;
                    }
                    before[a * n + b] = now;
                }
            }
        }
        assert!(brute > 100, "{brute}: the balls must touch and part for the test to mean anything");
        assert_eq!(counter.contacts, brute);
    }

    #[test]
    fn neighbour_pairs_give_the_all_pairs_contact_forces_and_energy() {
        // 60 balls packed round the race with small random overlaps and gaps, in a shuffled
        // order and with whole turns added to some angles: the neighbour pairs (O(n log n))
        // must give the all-pairs sums (O(n²)) to round-off, since only neighbours touch
        let (d, r, n) = (0.006, 0.06, 60);
        let law = ContactLaw::new(0.001, d, r, 0.5, 1e6);
        let forces = BallForces { n, r, contact: Some(law), rolling_resistance: 0.0, slip_rate: 1e-3 };
        let sep = min_separation(d, r);
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut psi = vec![0.0; n];
        let mut at = 0.0;
        let step = (2.0 * PI).min(n as f64 * sep * 1.02) / n as f64;
        for k in 0..n {
            // place ball k at the k-th slot, under a permutation, some with extra turns
            let j = (k * 37) % n;
            psi[j] = at + (next() - 0.5) * 0.04 * sep + if k % 7 == 0 { 2.0 * PI * (k % 3) as f64 } else { 0.0 };
            at += step;
        }
        let rate: Vec<f64> = (0..n).map(|_| next() - 0.5).collect();
        let mut q = vec![0.0; n];
        forces.torques(&psi, &rate, |_| 0.0, &mut q);
        let mut all = vec![0.0; n];
        let mut e_all = 0.0;
        for a in 0..n {
            for b in a + 1..n {
                let f = law.pair(psi[b] - psi[a], rate[b] - rate[a]);
                all[b] += f;
                all[a] -= f;
                e_all += law.energy(psi[b] - psi[a]);
            }
        }
        let scale = all.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(scale > 0.0 && e_all > 0.0, "the balls must touch for the test to mean anything");
        for j in 0..n {
            assert!((q[j] - all[j]).abs() <= 1e-12 * scale, "ball {j}: {} vs {}", q[j], all[j]);
        }
        let e = forces.contact_energy(&psi);
        assert!((e - e_all).abs() <= 1e-12 * e_all, "{e} vs {e_all}");
        assert!(n > ALL_PAIRS_UP_TO);
    }

    #[test]
    fn damping_ratio_gives_the_restitution_of_a_linear_oscillator() {
        for e in [0.1, 0.5, 0.9, 1.0] {
            let z = damping_ratio(e);
            let back = (-PI * z / (1.0 - z * z).sqrt()).exp();
            assert!((back - e).abs() < 1e-12, "{e} {back}");
        }
    }

    #[test]
    fn validation_names_the_field() {
        let p = BallPhysics { contact: true, ..Default::default() };
        let e = p.validate("planar", 0.03, 0.06, 20).unwrap_err();
        assert_eq!(e.field(), Some("planar.ball_diameter"));
        assert!(p.validate("planar", 0.03, 0.06, 19).is_ok()); // 2π/0.324 = 19.4
        let e = BallPhysics { restitution: 1.5, ..Default::default() }.validate("planar", 0.03, 0.06, 2).unwrap_err();
        assert_eq!(e.field(), Some("planar.restitution"));
        let e = BallPhysics { rolling_resistance: -1.0, ..Default::default() }.validate("planar", 0.03, 0.06, 2).unwrap_err();
        assert_eq!(e.field(), Some("planar.rolling_resistance"));
        let e = p.check_initial("drive.psi0", 0.03, 0.06, &[0.0, 0.2]).unwrap_err();
        assert_eq!(e.field(), Some("drive.psi0"));
    }
}
