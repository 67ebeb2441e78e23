//! Speeds as a user writes them: `"1500 rpm"`, `"157 rad/s"`, `"25 Hz"`, or a bare number, the
//! papers' dimensionless speed `Ω = ω/ω0`.
//!
//! One parser ([`parse_speed`], [`speed_of_value`]) serves every speed input: the command-line
//! options (`--omega-max`, `map --omega`), the config keys (`analysis.omega_max`,
//! `analysis.operating_speed`) and the speed axes of maps (parameter paths [`SPEED_PATHS`]).
//! The analyses work in `Ω`; [`Speed::to_omega`] converts with the rotor's `ω0 = sqrt(c_x/M_s)`
//! ([`crate::spatial::params::Scale`]):
//!
//! - `ω [rad/s] = Ω ω0`, `n [rpm] = 30 ω/π`, `f [Hz] = ω/(2π)`.
//!
//! **A bare number is `Ω`**, for a dimensionless and a dimensional config alike: every config and
//! script written before units existed keeps its meaning (`analysis.omega_max = 5.2` in
//! `examples/washing_machine.toml` was, and is, `Ω = 5.2`, 1505 rpm). The command line notes on
//! standard error when a dimensional config gets a bare number. A speed with a unit on a
//! dimensionless config is refused (it has no `ω0`): the error says to give `Ω`.
//!
//! ```
//! use autobal::units::{parse_speed, SpeedUnit};
//! let s = parse_speed("--omega-max", "1500rpm").unwrap();
//! assert_eq!((s.value, s.unit), (1500.0, SpeedUnit::Rpm));
//! // with ω0 = 100 rad/s: 1500 rpm = 157.08 rad/s = Ω 1.5708
//! assert!((s.to_omega("--omega-max", Some(100.0)).unwrap() - 0.5 * std::f64::consts::PI).abs() < 1e-15);
//! assert_eq!(parse_speed("x", "2.5").unwrap().unit, SpeedUnit::Omega);
//! let e = parse_speed("analysis.omega_max", "1500 rmp").unwrap_err().to_string();
//! assert!(e.starts_with("analysis.omega_max: unknown unit \"rmp\""), "{e}");
//! ```

use crate::error::{fmt_num, Error, Result};
use std::f64::consts::PI;

/// The unit a speed was given in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SpeedUnit {
    /// The papers' dimensionless `Ω = ω/ω0` (a bare number).
    Omega,
    /// Radians per second.
    RadPerS,
    /// Revolutions per minute (`ω = n π/30`).
    Rpm,
    /// Revolutions per second, hertz (`ω = 2π f`).
    Hz,
}

impl SpeedUnit {
    /// rad/s per unit (`π/30` for rpm, `2π` for Hz, 1 for rad/s); `None` for `Ω`, whose
    /// factor is the rotor's `ω0`.
    pub fn rad_s(self) -> Option<f64> {
        match self {
            SpeedUnit::Omega => None,
            SpeedUnit::RadPerS => Some(1.0),
            SpeedUnit::Rpm => Some(PI / 30.0),
            SpeedUnit::Hz => Some(2.0 * PI),
        }
    }

    /// The unit as written after a number (`rpm`, `rad/s`, `Hz`, `Ω`).
    pub fn symbol(self) -> &'static str {
        match self {
            SpeedUnit::Omega => "Ω",
            SpeedUnit::RadPerS => "rad/s",
            SpeedUnit::Rpm => "rpm",
            SpeedUnit::Hz => "Hz",
        }
    }

    fn from_text(u: &str) -> Option<Self> {
        match u.trim().to_ascii_lowercase().as_str() {
            "" | "ω" | "omega" => Some(SpeedUnit::Omega),
            "rpm" | "r/min" | "rev/min" | "1/min" => Some(SpeedUnit::Rpm),
            "rad/s" | "rad/sec" | "rad s^-1" | "1/s" => Some(SpeedUnit::RadPerS),
            "hz" | "rev/s" | "rps" => Some(SpeedUnit::Hz),
            _ if u.trim() == "Ω" => Some(SpeedUnit::Omega),
            _ => None,
        }
    }
}

/// A speed as given: a number and its unit.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Speed {
    /// The number as written.
    pub value: f64,
    /// Its unit.
    pub unit: SpeedUnit,
}

impl Speed {
    /// A dimensionless speed `Ω`.
    pub fn omega(value: f64) -> Self {
        Speed { value, unit: SpeedUnit::Omega }
    }

    /// The speed as `Ω = ω/ω0`: `value` for `Ω`, `value · (rad/s per unit) / ω0` otherwise.
    /// `omega0` is `None` for a dimensionless config, which then refuses a unit (`field` names
    /// the input in the error).
    pub fn to_omega(&self, field: &str, omega0: Option<f64>) -> Result<f64> {
        match (self.unit.rad_s(), omega0) {
            (None, _) => Ok(self.value),
            (Some(k), Some(w0)) => Ok(self.value * k / w0),
            (Some(_), None) => Err(Error::invalid(
                field,
                format!(
                    "{} {} needs a dimensional config (the rotor's ω0); this config is dimensionless: give the speed as a bare number Ω",
                    fmt_num(self.value),
                    self.unit.symbol()
                ),
            )),
        }
    }

    /// Whether it has a unit (is not a bare `Ω`).
    pub fn is_si(&self) -> bool {
        self.unit != SpeedUnit::Omega
    }
}

impl std::fmt::Display for Speed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.unit {
            SpeedUnit::Omega => write!(f, "Ω = {}", fmt_num(self.value)),
            u => write!(f, "{} {}", fmt_num(self.value), u.symbol()),
        }
    }
}

const UNITS_HELP: &str = "rpm, rad/s or Hz, or a bare number for the dimensionless Ω";

/// Split `text` into a number and the rest: the longest prefix that parses as a float.
fn split_number(text: &str) -> Option<(f64, &str)> {
    let t = text.trim();
    let end = t.char_indices().map(|(i, c)| i + c.len_utf8()).rfind(|&i| t[..i].trim().parse::<f64>().is_ok())?;
    // "1e" or "inf" prefixes of a unit are not numbers a user meant: keep digits, dot, sign, exponent
    let num = &t[..end];
    if !num.trim().chars().all(|c| c.is_ascii_digit() || matches!(c, '.' | '+' | '-' | 'e' | 'E')) {
        return None;
    }
    Some((num.trim().parse().ok()?, &t[end..]))
}

/// Parse one speed, `"1500rpm"`, `"1500 rpm"`, `"157 rad/s"`, `"25Hz"` or a bare number (`Ω`).
/// The number must be finite and `≥ 0`; errors name `field` and say why, on one line.
pub fn parse_speed(field: &str, text: &str) -> Result<Speed> {
    let shown: String = text.chars().take(40).collect();
    if text.len() > 100 {
        return Err(Error::invalid(field, format!("\"{shown}…\" is not a speed: give a number and a unit ({UNITS_HELP})")));
    }
    let (value, rest) =
        split_number(text).ok_or_else(|| Error::invalid(field, format!("\"{shown}\" is not a speed: give a number and a unit ({UNITS_HELP})")))?;
    let unit = SpeedUnit::from_text(rest).ok_or_else(|| {
        Error::invalid(field, format!("unknown unit \"{}\" in \"{shown}\" (units: {UNITS_HELP})", rest.trim().chars().take(20).collect::<String>()))
    })?;
    if !value.is_finite() || value < 0.0 {
        return Err(Error::invalid(field, format!("a speed must be a finite number ≥ 0, got \"{shown}\"")));
    }
    Ok(Speed { value, unit })
}

/// For a config value that should be a bare number but is a string with a unit: what that string
/// reads as in SI (a string over 100 characters: `None`), e.g. `"1400 rpm"` → `Some("1400 rpm = 146.6 rad/s")`; `None` where it is
/// no speed with a unit (a bare number in a string, a unit not a speed's, not a number).
pub fn speed_hint(text: &str) -> Option<String> {
    // (as `parse_speed`: `split_number` tries every prefix, quadratic in the length)
    if text.len() > 100 {
        return None;
    }
    let (value, rest) = split_number(text)?;
    let unit = SpeedUnit::from_text(rest)?;
    let k = unit.rad_s()?;
    (value.is_finite() && unit != SpeedUnit::RadPerS).then(|| format!("{} {} = {} rad/s", fmt_num(value), unit.symbol(), fmt_num(value * k)))
}

/// Parse a speed or a range of speeds: `"1400 rpm"`, `"1200-1400 rpm"`, `"1200 rpm - 1400 rpm"`,
/// `"1.2 to 1.6"`; the unit written once applies to both ends. Returns `(lo, hi)` (equal for one
/// speed), `lo ≤ hi`.
pub fn parse_speed_range(field: &str, text: &str) -> Result<(Speed, Speed)> {
    let t = text.trim();
    // a separator: " to ", "..", an en dash, or a '-' after a digit that is not an exponent's sign
    let sep = t.find(" to ").map(|i| (i, 4)).or_else(|| t.find("..").map(|i| (i, 2))).or_else(|| t.find('–').map(|i| (i, '–'.len_utf8()))).or_else(|| {
        let b = t.as_bytes();
        (1..b.len()).find(|&i| b[i] == b'-' && !matches!(b[i - 1], b'e' | b'E')).map(|i| (i, 1))
    });
    let Some((i, len)) = sep else {
        let s = parse_speed(field, t)?;
        return Ok((s, s));
    };
    let (a, b) = (t[..i].trim(), t[i + len..].trim());
    let hi = parse_speed(field, b)?;
    let lo = match parse_speed(field, a)? {
        // "1200-1400 rpm": the first end takes the second's unit
        s if s.unit == SpeedUnit::Omega && split_number(a).is_some_and(|(_, r)| r.trim().is_empty()) => Speed { value: s.value, unit: hi.unit },
        s => s,
    };
    if lo.unit != hi.unit {
        return Err(Error::invalid(field, format!("the two ends of \"{t}\" have different units ({} and {})", lo.unit.symbol(), hi.unit.symbol())));
    }
    if lo.value > hi.value {
        return Err(Error::invalid(field, format!("the range \"{t}\" must go from low to high")));
    }
    Ok((lo, hi))
}

/// A speed from a config value: a number is `Ω`, a string is parsed by [`parse_speed`].
pub fn speed_of_value(field: &str, v: &toml::Value) -> Result<Speed> {
    match v {
        toml::Value::Float(f) if f.is_finite() && *f >= 0.0 => Ok(Speed::omega(*f)),
        toml::Value::Float(f) => Err(Error::invalid(field, format!("a speed must be a finite number ≥ 0, got {}", fmt_num(*f)))),
        toml::Value::Integer(i) if *i >= 0 => Ok(Speed::omega(*i as f64)),
        toml::Value::Integer(i) => Err(Error::invalid(field, format!("a speed must be a finite number ≥ 0, got {i}"))),
        toml::Value::String(s) => parse_speed(field, s),
        _ => Err(Error::invalid(field, format!("expected a speed such as \"1500 rpm\" ({UNITS_HELP})"))),
    }
}

/// A speed or range of speeds from a config value ([`parse_speed_range`]; a number is one `Ω`).
pub fn speed_range_of_value(field: &str, v: &toml::Value) -> Result<(Speed, Speed)> {
    match v {
        toml::Value::String(s) => parse_speed_range(field, s),
        other => speed_of_value(field, other).map(|s| (s, s)),
    }
}

/// The map axis paths of a speed in SI, beside `omega` (`Ω`): `speed` in rad/s, `speed_rpm`,
/// `speed_hz`. A dimensional config only.
pub const SPEED_PATHS: [(&str, SpeedUnit); 3] = [("speed", SpeedUnit::RadPerS), ("speed_rpm", SpeedUnit::Rpm), ("speed_hz", SpeedUnit::Hz)];

/// The unit of a speed axis path: `omega` → `Ω`, `speed` → rad/s, `speed_rpm`, `speed_hz`; `None`
/// for a parameter path.
pub fn speed_path_unit(path: &str) -> Option<SpeedUnit> {
    if path == "omega" {
        return Some(SpeedUnit::Omega);
    }
    SPEED_PATHS.iter().find(|(p, _)| *p == path).map(|(_, u)| *u)
}

/// A dimensionless speed `Ω` in rad/s, rpm and Hz with `ω0` (rad/s): `(Ω ω0, 30 Ω ω0/π, Ω ω0/(2π))`.
pub fn omega_in_si(omega: f64, omega0: f64) -> (f64, f64, f64) {
    let w = omega * omega0;
    (w, w * 30.0 / PI, w / (2.0 * PI))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_spelling_parses_to_the_same_speed() {
        // 1500 rpm = 50π rad/s = 25 Hz: three routes to one ω (exact up to the rounding of π)
        let w0 = 100.0;
        let omegas: Vec<f64> = ["1500rpm", "1500 rpm", " 1500 RPM ", "157.07963267948966 rad/s", "25Hz", "25 hz"]
            .iter()
            .map(|t| parse_speed("f", t).unwrap().to_omega("f", Some(w0)).unwrap())
            .collect();
        for w in &omegas {
            assert!((w - 0.5 * PI).abs() < 1e-15, "{omegas:?}");
        }
        assert_eq!(parse_speed("f", "2.5").unwrap(), Speed::omega(2.5));
        assert_eq!(parse_speed("f", "1e3 rpm").unwrap().value, 1000.0);
    }

    #[test]
    fn bad_speeds_name_the_field_and_the_reason() {
        for (t, why) in [
            ("", "is not a speed"),
            ("rpm", "is not a speed"),
            ("12 furlongs", "unknown unit"),
            ("-3 rpm", "≥ 0"),
            ("inf", "is not a speed"),
            ("nan rpm", "is not a speed"),
        ] {
            let e = parse_speed("analysis.omega_max", t).unwrap_err().to_string();
            assert!(e.starts_with("analysis.omega_max: ") && e.contains(why) && !e.contains('\n'), "{t}: {e}");
        }
        let e = parse_speed("f", "3 rpm").unwrap().to_omega("--omega-max", None).unwrap_err().to_string();
        assert!(e.starts_with("--omega-max: 3 rpm needs a dimensional config"), "{e}");
    }

    #[test]
    fn ranges_take_one_unit_for_both_ends() {
        let (lo, hi) = parse_speed_range("f", "1200-1400 rpm").unwrap();
        assert_eq!((lo.value, hi.value, lo.unit, hi.unit), (1200.0, 1400.0, SpeedUnit::Rpm, SpeedUnit::Rpm));
        let (lo, hi) = parse_speed_range("f", "20 Hz - 25 Hz").unwrap();
        assert_eq!((lo.value, hi.value, lo.unit), (20.0, 25.0, SpeedUnit::Hz));
        let (lo, hi) = parse_speed_range("f", "1e-1 to 2").unwrap();
        assert_eq!((lo, hi), (Speed::omega(0.1), Speed::omega(2.0)));
        let (lo, hi) = parse_speed_range("f", "1400 rpm").unwrap();
        assert_eq!(lo, hi);
        assert!(parse_speed_range("f", "1400-1200 rpm").unwrap_err().to_string().contains("low to high"));
        assert!(parse_speed_range("f", "10 Hz-1400 rpm").unwrap_err().to_string().contains("different units"));
    }

    #[test]
    fn conversions_agree_with_their_definitions() {
        // ω = Ω ω0; one revolution per second is 60 rpm and 2π rad/s
        let (w, rpm, hz) = omega_in_si(1.0, 2.0 * PI);
        assert_eq!((w, hz), (2.0 * PI, 1.0));
        assert!((rpm - 60.0).abs() < 1e-12);
        assert_eq!(speed_path_unit("speed_rpm"), Some(SpeedUnit::Rpm));
        assert_eq!(speed_path_unit("omega"), Some(SpeedUnit::Omega));
        assert_eq!(speed_path_unit("rotor.mass"), None);
    }
}
