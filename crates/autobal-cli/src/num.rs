//! Number formatting for people: the report, the figures' ticks and captions. One helper, so a
//! value prints the same everywhere and never with more digits than mean something
//! (`0.01449`, not `0.014492753623188406`).

/// `v` rounded to `digits` significant digits, trailing zeros dropped; scientific notation
/// below 1e-3 and from 1e6 in magnitude; "—" for NaN, "∞" for infinities.
///
/// ```text
/// fmt(0.014492753623188406, 4) = "0.01449"    fmt(3.8007, 3) = "3.8"    fmt(2.5e-7, 3) = "2.5e-7"
/// ```
pub fn fmt(v: f64, digits: usize) -> String {
    if v.is_nan() {
        return "—".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "∞".into() } else { "−∞".into() };
    }
    if v == 0.0 {
        return "0".into();
    }
    let digits = digits.clamp(1, 17);
    let a = v.abs();
    if !(1e-3..1e6).contains(&a) {
        let s = format!("{:.*e}", digits - 1, v);
        let (mant, exp) = s.split_once('e').unwrap_or((&s, "0"));
        return format!("{}e{exp}", trim(mant));
    }
    // decimals so that `digits` significant digits remain (after rounding, which can carry)
    let mag = a.log10().floor() as i32;
    let decimals = (digits as i32 - 1 - mag).max(0) as usize;
    let s = format!("{v:.decimals$}");
    let rounded: f64 = s.parse().unwrap_or(v);
    let mag2 = rounded.abs().log10().floor() as i32;
    let s = if mag2 > mag && decimals > 0 { format!("{v:.*}", decimals - 1) } else { s };
    trim(&s).to_string()
}

fn trim(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// `v` with `decimals` decimals and thin spaces between thousands: `11 786` rpm.
pub fn grouped(v: f64, decimals: usize) -> String {
    if !v.is_finite() {
        return fmt(v, 3);
    }
    let s = format!("{:.*}", decimals, v.abs());
    let (int, frac) = s.split_once('.').map_or((s.as_str(), None), |(i, f)| (i, Some(f)));
    let mut out = String::new();
    for (i, c) in int.chars().enumerate() {
        if i > 0 && (int.len() - i) % 3 == 0 {
            out.push('\u{202F}');
        }
        out.push(c);
    }
    if let Some(f) = frac {
        out.push('.');
        out.push_str(f);
    }
    if v < 0.0 && out.chars().any(|c| c.is_ascii_digit() && c != '0') {
        out.insert(0, '-');
    }
    out
}

/// rad/s → rpm.
pub const RPM_PER_RAD_S: f64 = 30.0 / std::f64::consts::PI;

/// A dimensionless speed Ω, with rad/s and rpm when the rotor is dimensional (`omega0` the
/// unit of speed in rad/s): `2.524 (1 234 rad/s, 11 786 rpm)`.
pub fn speed(omega: f64, omega0: Option<f64>) -> String {
    match omega0 {
        Some(w0) if omega.is_finite() => {
            format!("{} ({} rad/s, {} rpm)", fmt(omega, 4), grouped(omega * w0, 1), grouped(omega * w0 * RPM_PER_RAD_S, 0))
        }
        _ => fmt(omega, 4),
    }
}

/// Round to `digits` significant digits as a number (for JSON embedded in the report: six
/// digits are far below what a figure can show and keep the page small). Non-finite → None.
pub fn round_sig(v: f64, digits: usize) -> Option<f64> {
    if !v.is_finite() {
        return None;
    }
    if v == 0.0 {
        return Some(0.0);
    }
    format!("{:.*e}", digits.clamp(1, 17) - 1, v).parse().ok()
}

/// A float as the CSVs write it: the shortest text that reads back to the same `f64`, positional
/// or with an exponent, whichever is shorter (`0.25`, `1.6092556977295832e-7`, `1e16`; positional
/// on a tie: `100`, `0.01`). Both of Rust's forms (`{}` and `{:e}`) print the fewest digits
/// that round-trip, so either is exact; this only picks the shorter.
pub struct Csv(pub f64);

impl std::fmt::Display for Csv {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.0;
        if !v.is_finite() || v == 0.0 {
            return write!(f, "{v}");
        }
        let mut exp = Short::default();
        let _ = std::fmt::Write::write_fmt(&mut exp, format_args!("{v:e}"));
        let s = exp.as_str();
        let (mantissa, e) = s.split_once('e').unwrap_or((s, "0"));
        let e: i32 = e.parse().unwrap_or(0);
        let digits = mantissa.bytes().filter(u8::is_ascii_digit).count() as i32;
        // length of `{v}`: d digits with the point after digit e + 1, or `0.` and -e - 1 zeros
        let positional = i32::from(v < 0.0)
            + match e {
                e if e < 0 => digits + 1 - e,
                e if digits > e + 1 => digits + 1,
                e => e + 1,
            };
        if positional <= s.len() as i32 {
            write!(f, "{v}")
        } else {
            f.write_str(s)
        }
    }
}

/// A stack buffer for one `{:e}` float (at most 24 bytes: sign, 17 digits, point, `e-324`).
#[derive(Default)]
struct Short {
    buf: [u8; 32],
    len: usize,
}

impl Short {
    fn as_str(&self) -> &str {
        std::str::from_utf8(&self.buf[..self.len]).unwrap_or("")
    }
}

impl std::fmt::Write for Short {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        let end = self.len + s.len();
        self.buf.get_mut(self.len..end).ok_or(std::fmt::Error)?.copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_digits_without_float_noise() {
        assert_eq!(fmt(0.014492753623188406, 4), "0.01449");
        assert_eq!(fmt(3.8007, 3), "3.8");
        assert_eq!(fmt(3.8007, 4), "3.801");
        assert_eq!(fmt(0.39999999999999997, 6), "0.4");
        assert_eq!(fmt(-2.5e-7, 3), "-2.5e-7");
        assert_eq!(fmt(1.2345e7, 3), "1.23e7");
        assert_eq!(fmt(9.9996, 4), "10");
        assert_eq!(fmt(99.96, 3), "100");
        assert_eq!(fmt(288.0, 4), "288");
        assert_eq!(fmt(123456.0, 3), "123456");
        assert_eq!(fmt(0.0, 3), "0");
        assert_eq!(fmt(f64::NAN, 3), "—");
    }

    #[test]
    fn thousands_are_grouped() {
        assert_eq!(grouped(11786.4, 0), "11\u{202F}786");
        assert_eq!(grouped(1234.56, 1), "1\u{202F}234.6");
        assert_eq!(grouped(-999.0, 0), "-999");
        assert_eq!(grouped(-0.04, 0), "0");
        assert_eq!(grouped(1000000.0, 0), "1\u{202F}000\u{202F}000");
    }

    #[test]
    fn speeds_in_si_when_dimensional() {
        assert_eq!(speed(2.0, None), "2");
        assert_eq!(speed(2.0, Some(100.0)), "2 (200.0 rad/s, 1\u{202F}910 rpm)");
    }

    #[test]
    fn rounding_for_json_keeps_six_digits() {
        assert_eq!(round_sig(0.014492753623188406, 6), Some(0.0144928));
        assert_eq!(round_sig(f64::NAN, 6), None);
    }

    #[test]
    fn csv_numbers_are_the_shorter_exact_form() {
        use super::Csv;
        for (v, want) in [
            (1.6092556977295832e-7, "1.6092556977295832e-7"),
            (0.25, "0.25"),
            (100.0, "100"),
            (1e16, "1e16"),
            (0.01, "0.01"),
            (0.001, "1e-3"),
            (0.0001, "1e-4"),
            (-0.00012, "-1.2e-4"),
            (123456.5, "123456.5"),
            (0.0, "0"),
            (-2.5, "-2.5"),
        ] {
            assert_eq!(Csv(v).to_string(), want, "{v:e}");
        }
        // every value reads back bit for bit, in no more characters than either of Rust's forms
        let mut x = 0x2545_F491_4F6C_DD1Du64;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = f64::from_bits(x);
            if !v.is_finite() {
                continue;
            }
            let s = Csv(v).to_string();
            assert_eq!(s.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{s}");
            assert_eq!(s.len(), format!("{v}").len().min(format!("{v:e}").len()), "{v:e}: {s}");
        }
    }
}
