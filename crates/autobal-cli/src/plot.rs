//! A small SVG line-plot writer: axes with round ticks, polylines (NaN breaks a line), shaded
//! intervals, vertical markers and a legend. No fonts are embedded; the browser renders text.

use std::fmt::Write;

/// Colours of successive series (colour-blind-safe palette of Okabe and Ito).
pub const PALETTE: [&str; 8] = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#999999"];

/// One curve.
#[derive(Debug, Clone)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub color: String,
    pub dashed: bool,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, color: &str) -> Self {
        Series { label: label.into(), points, color: color.to_string(), dashed: false }
    }
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
}

/// A shaded rectangle in data coordinates (`None` ends extend to the axes).
#[derive(Debug, Clone)]
pub struct Shade {
    pub x: (f64, f64),
    pub y: (Option<f64>, Option<f64>),
    pub color: String,
}

/// A raster image (PNG bytes) filling the whole plot area, drawn under everything else: the
/// heatmap of a map, whose cells then line up with the axis ranges.
#[derive(Debug, Clone)]
pub struct Raster {
    pub png: Vec<u8>,
}

/// Standard base64 (RFC 4648, with padding), for embedding the raster in the SVG.
pub fn base64(data: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(data.len().div_ceil(3) * 4);
    for ch in data.chunks(3) {
        let b = [ch[0], *ch.get(1).unwrap_or(&0), *ch.get(2).unwrap_or(&0)];
        let v = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= ch.len() {
                s.push(T[(v >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// A figure.
#[derive(Debug, Clone, Default)]
pub struct Plot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub shades: Vec<Shade>,
    /// Vertical markers with a label.
    pub vlines: Vec<(f64, String)>,
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    /// Label of the shaded areas in the legend.
    pub shade_label: Option<String>,
    /// Heatmap under the plot area.
    pub raster: Option<Raster>,
}

const W: f64 = 720.0;
const H: f64 = 440.0;
const ML: f64 = 70.0;
const MR: f64 = 190.0;
const MT: f64 = 40.0;
const MB: f64 = 55.0;

/// Round tick positions covering `[lo, hi]`, about `target` of them.
pub fn ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    if !(hi > lo) {
        return vec![lo];
    }
    let raw = (hi - lo) / target as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0].iter().map(|m| m * mag).find(|s| *s >= raw).unwrap_or(10.0 * mag);
    let start = (lo / step).ceil() as i64;
    let end = (hi / step).floor() as i64;
    (start..=end).map(|i| i as f64 * step).collect()
}

fn fmt_tick(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        format!("{v:.1e}")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

impl Plot {
    fn data_range(&self) -> ((f64, f64), (f64, f64)) {
        let pts = self.series.iter().flat_map(|s| s.points.iter()).filter(|p| p.0.is_finite() && p.1.is_finite());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for &(x, y) in pts {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        if !x0.is_finite() {
            (x0, x1) = (0.0, 1.0);
        }
        if !y0.is_finite() {
            (y0, y1) = (0.0, 1.0);
        }
        if y1 - y0 < 1e-12 {
            y0 -= 0.5;
            y1 += 0.5;
        }
        let xr = self.x_range.unwrap_or((x0, x1));
        let yr = self.y_range.unwrap_or((y0, y1 + 0.05 * (y1 - y0)));
        (xr, yr)
    }

    /// Render to an SVG document.
    pub fn to_svg(&self) -> String {
        let ((x0, x1), (y0, y1)) = self.data_range();
        let pw = W - ML - MR;
        let ph = H - MT - MB;
        let sx = |x: f64| ML + (x - x0) / (x1 - x0) * pw;
        let sy = |y: f64| MT + (1.0 - (y - y0) / (y1 - y0)) * ph;
        let mut s = String::new();
        let _ = write!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" font-family="DejaVu Sans, Arial, sans-serif" font-size="12">
<rect width="100%" height="100%" fill="white"/>
<defs><clipPath id="plotarea"><rect x="{ML}" y="{MT}" width="{pw}" height="{ph}"/></clipPath></defs>
<text x="{}" y="22" text-anchor="middle" font-size="{}" font-weight="bold">{}</text>
"#,
            ML + pw / 2.0,
            if self.title.chars().count() > 60 { 11 } else { 14 },
            esc(&self.title)
        );
        if let Some(r) = &self.raster {
            let _ = writeln!(
                s,
                r#"<image x="{ML}" y="{MT}" width="{pw}" height="{ph}" preserveAspectRatio="none" style="image-rendering:pixelated" href="data:image/png;base64,{}"/>"#,
                base64(&r.png)
            );
        }
        s.push_str("<g clip-path=\"url(#plotarea)\">\n");
        for sh in &self.shades {
            let (ya, yb) = (sh.y.0.unwrap_or(y0).max(y0), sh.y.1.unwrap_or(y1).min(y1));
            if yb <= ya {
                continue;
            }
            let (xa, xb) = (sx(sh.x.0.max(x0)), sx(sh.x.1.min(x1)));
            let _ = writeln!(
                s,
                r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{}" fill-opacity="0.35"/>"#,
                xa,
                sy(yb),
                (xb - xa).max(0.0),
                sy(ya) - sy(yb),
                sh.color
            );
        }
        s.push_str("</g>\n");
        // grid and ticks
        for t in ticks(x0, x1, 8) {
            let _ = writeln!(
                s,
                r##"<line x1="{0:.2}" y1="{1}" x2="{0:.2}" y2="{2}" stroke="#e0e0e0"/><text x="{0:.2}" y="{3}" text-anchor="middle">{4}</text>"##,
                sx(t),
                MT,
                MT + ph,
                MT + ph + 16.0,
                fmt_tick(t)
            );
        }
        for t in ticks(y0, y1, 7) {
            let _ = writeln!(
                s,
                r##"<line x1="{1}" y1="{0:.2}" x2="{2}" y2="{0:.2}" stroke="#e0e0e0"/><text x="{3}" y="{4:.2}" text-anchor="end">{5}</text>"##,
                sy(t),
                ML,
                ML + pw,
                ML - 6.0,
                sy(t) + 4.0,
                fmt_tick(t)
            );
        }
        if y0 < 0.0 && y1 > 0.0 {
            let _ = writeln!(s, r##"<line x1="{ML}" y1="{0:.2}" x2="{1}" y2="{0:.2}" stroke="#555"/>"##, sy(0.0), ML + pw);
        }
        let _ = writeln!(s, r##"<rect x="{ML}" y="{MT}" width="{pw}" height="{ph}" fill="none" stroke="#333"/>"##);
        let _ = writeln!(s, r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#, ML + pw / 2.0, H - 12.0, esc(&self.x_label));
        let _ = writeln!(
            s,
            r#"<text x="16" y="{0}" text-anchor="middle" transform="rotate(-90 16 {0})">{1}</text>"#,
            MT + ph / 2.0,
            esc(&self.y_label)
        );
        s.push_str("<g clip-path=\"url(#plotarea)\" fill=\"none\" stroke-width=\"1.8\">\n");
        for (x, label) in &self.vlines {
            if *x >= x0 && *x <= x1 {
                let _ = writeln!(
                    s,
                    r##"<line x1="{0:.2}" y1="{1}" x2="{0:.2}" y2="{2}" stroke="#777" stroke-dasharray="2 3" stroke-width="1"/><text x="{3:.2}" y="{4}" fill="#555" stroke="none" font-size="10">{5}</text>"##,
                    sx(*x),
                    MT,
                    MT + ph,
                    sx(*x) + 3.0,
                    MT + 12.0,
                    esc(label)
                );
            }
        }
        for se in &self.series {
            let dash = if se.dashed { r#" stroke-dasharray="6 4""# } else { "" };
            let mut seg: Vec<String> = vec![];
            let flush = |seg: &mut Vec<String>, s: &mut String| {
                if seg.len() >= 2 {
                    let _ = writeln!(s, r#"<polyline points="{}" stroke="{}"{dash}/>"#, seg.join(" "), se.color);
                } else if seg.len() == 1 {
                    let xy: Vec<&str> = seg[0].split(',').collect();
                    let _ = writeln!(s, r#"<circle cx="{}" cy="{}" r="2" fill="{}" stroke="none"/>"#, xy[0], xy[1], se.color);
                }
                seg.clear();
            };
            for &(x, y) in &se.points {
                if x.is_finite() && y.is_finite() {
                    // keep far-off points finite in SVG while the clip path hides them
                    let py = sy(y).clamp(-1e4, 1e4);
                    seg.push(format!("{:.2},{:.2}", sx(x), py));
                } else {
                    flush(&mut seg, &mut s);
                }
            }
            flush(&mut seg, &mut s);
        }
        s.push_str("</g>\n");
        // legend
        let lx = ML + pw + 12.0;
        let mut ly = MT + 8.0;
        for se in &self.series {
            if se.label.is_empty() {
                continue;
            }
            let dash = if se.dashed { r#" stroke-dasharray="6 4""# } else { "" };
            let _ = writeln!(
                s,
                r#"<line x1="{lx}" y1="{ly}" x2="{}" y2="{ly}" stroke="{}" stroke-width="2"{dash}/><text x="{}" y="{}">{}</text>"#,
                lx + 24.0,
                se.color,
                lx + 30.0,
                ly + 4.0,
                esc(&se.label)
            );
            ly += 18.0;
        }
        if let (Some(label), Some(sh)) = (&self.shade_label, self.shades.first()) {
            let _ = writeln!(
                s,
                r#"<rect x="{lx}" y="{}" width="24" height="10" fill="{}" fill-opacity="0.35"/><text x="{}" y="{}">{}</text>"#,
                ly - 5.0,
                sh.color,
                lx + 30.0,
                ly + 4.0,
                esc(label)
            );
        }
        s.push_str("</svg>\n");
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        for (i, o) in [("", ""), ("f", "Zg=="), ("fo", "Zm8="), ("foo", "Zm9v"), ("foob", "Zm9vYg=="), ("fooba", "Zm9vYmE="), ("foobar", "Zm9vYmFy")] {
            assert_eq!(base64(i.as_bytes()), o);
        }
    }

    #[test]
    fn ticks_are_round_and_cover_the_range() {
        let t = ticks(0.0, 3.7, 8);
        assert_eq!(t.first(), Some(&0.0));
        assert!(t.windows(2).all(|w| ((w[1] - w[0]) - 0.5).abs() < 1e-12));
        assert!(*t.last().unwrap() <= 3.7);
    }

    #[test]
    fn nan_breaks_a_line_and_svg_is_well_formed() {
        let p = Plot {
            title: "t <&>".into(),
            series: vec![Series::new("a", vec![(0.0, 1.0), (1.0, 2.0), (2.0, f64::NAN), (3.0, 1.0), (4.0, 0.5)], "#000")],
            ..Default::default()
        };
        let svg = p.to_svg();
        assert_eq!(svg.matches("<polyline").count(), 2);
        assert!(svg.contains("t &lt;&amp;&gt;"));
        assert!(!svg.contains("NaN") && !svg.contains("inf"));
    }
}
