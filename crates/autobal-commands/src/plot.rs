//! Figures: one description ([`Plot`]) drawn three ways.
//!
//! - [`Plot::to_svg`]: a static SVG of our own (axes with round ticks, a legend sized to its
//!   labels so it never clips, a colour bar beside a heatmap, vertical markers whose labels
//!   step down when they would overlap, an optional second speed axis on top, e.g. rpm);
//! - [`Plot::to_png`]: that SVG rasterised by `resvg` with the DejaVu fonts compiled in (no
//!   system fonts), so the PNG is as complete as the SVG;
//! - [`Plot::to_plotly`]: the figure as Plotly JSON (data and layout), which the HTML report
//!   embeds and draws interactively (zoom, hover values, curves toggled in the legend).

use serde_json::{json, Value};
use std::fmt::Write;

/// Colours of successive series (colour-blind-safe palette of Okabe and Ito).
pub const PALETTE: [&str; 8] = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#999999"];

/// One curve.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text; empty: not in the legend (a further branch of the group above it).
    pub label: String,
    /// Points; a NaN coordinate breaks the line.
    pub points: Vec<(f64, f64)>,
    pub color: String,
    pub dashed: bool,
    /// Curves of one group share one legend entry and are toggled together.
    pub group: Option<String>,
    /// Draw markers instead of a line.
    pub markers: bool,
    /// Line width in px (default 2).
    pub width: Option<f64>,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, color: &str) -> Self {
        Series { label: label.into(), points, color: color.to_string(), dashed: false, group: None, markers: false, width: None }
    }
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
    /// Put the curve in a legend group (one entry, toggled together).
    pub fn group(mut self, g: impl Into<String>) -> Self {
        self.group = Some(g.into());
        self
    }
    pub fn markers(mut self) -> Self {
        self.markers = true;
        self
    }
    pub fn width(mut self, w: f64) -> Self {
        self.width = Some(w);
        self
    }

    /// A line (not markers) of a colour [`hex_color`] reads, whose consecutive finite points
    /// share `x` or `y` to `tol` (a map's cell-edge boundary, its points computed from
    /// neighbouring cells: equal to rounding): the PNG may paint it itself.
    fn straight_polyline(&self, tol: (f64, f64)) -> bool {
        let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        !self.markers
            && hex_color(&self.color).is_some()
            && self.points.windows(2).all(|w| !(finite(&w[0]) && finite(&w[1])) || (w[0].0 - w[1].0).abs() <= tol.0 || (w[0].1 - w[1].1).abs() <= tol.1)
    }
}

/// `#rgb` or `#rrggbb` as bytes.
fn hex_color(c: &str) -> Option<[u8; 3]> {
    let h = c.strip_prefix('#')?;
    // hex digits only (`from_str_radix` would take a leading `+`, which SVG renderers refuse)
    let v = u32::from_str_radix(h, 16).ok().filter(|_| h.bytes().all(|b| b.is_ascii_hexdigit()))?;
    match h.len() {
        6 => Some([(v >> 16) as u8, (v >> 8) as u8, v as u8]),
        3 => Some([(v >> 8 & 15) as u8 * 17, (v >> 4 & 15) as u8 * 17, (v & 15) as u8 * 17]),
        _ => None,
    }
}

/// A shaded rectangle in data coordinates (`None` ends extend to the axes).
#[derive(Debug, Clone)]
pub struct Shade {
    pub x: (f64, f64),
    pub y: (Option<f64>, Option<f64>),
    pub color: String,
}

/// How heatmap values map to colours.
#[derive(Debug, Clone, Copy)]
pub enum ColorScale {
    /// Diverging about zero: blue for negative values down to `-neg`, red for positive up to
    /// `pos`, each side with square-root contrast (small margins near the boundary stay
    /// visible), white at zero.
    Diverging { neg: f64, pos: f64 },
    /// Two classes: negative values "stable" (green), positive "unstable" (red).
    Verdict,
}

/// A heatmap filling the plot area: `z[j][i]` at `(x[i], y[j])` on an even grid; NaN cells
/// (not computed) are grey.
#[derive(Debug, Clone)]
pub struct Heatmap {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub z: Vec<Vec<f64>>,
    pub scale: ColorScale,
    /// Title of the colour bar, e.g. "max Re λ".
    pub label: String,
}

impl Heatmap {
    /// Whether the figure draws it: a grid of at least one point each way, its `x` and `y`
    /// finite, each rising from its first value to its last (the raster's cells run left to right
    /// and bottom to top; every command's grid ascends, a `--x`/`--y` range with `HI ≤ LO` is
    /// refused), and `z` of `y.len()` rows of `x.len()` values. A non-finite `z` value is a
    /// cell not computed, drawn grey. Anything else (an empty or descending axis, a non-finite
    /// axis value, a ragged or missing row) is left out of the SVG, the PNG and the axis
    /// ranges, and the rest of the figure drawn: never a panic.
    pub fn drawable(&self) -> bool {
        let (nx, ny) = (self.x.len(), self.y.len());
        nx > 0
            && ny > 0
            && self.z.len() == ny
            && self.z.iter().all(|r| r.len() == nx)
            && self.x.iter().chain(&self.y).all(|v| v.is_finite())
            && self.cells_span().is_some()
    }

    /// The raster's extent `((x_lo, x_hi), (y_lo, y_hi))`: cells centred on the grid values, a
    /// half step beyond the first and last (half a unit for one value); `None` where it is not
    /// finite and of positive width.
    fn cells_span(&self) -> Option<((f64, f64), (f64, f64))> {
        let half = |v: &[f64]| if v.len() > 1 { (v[1] - v[0]).abs() / 2.0 } else { 0.5 };
        let span = |v: &[f64]| {
            let (a, b) = (v.first()? - half(v), v.last()? + half(v));
            (a.is_finite() && b.is_finite() && b > a).then_some((a, b))
        };
        Some((span(&self.x)?, span(&self.y)?))
    }
}

/// A second horizontal axis along the top: the bottom axis times `factor` (e.g. rpm over rad/s).
#[derive(Debug, Clone)]
pub struct SecondAxis {
    pub factor: f64,
    pub label: String,
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
    /// Legend entries of shaded areas by colour `(colour, label)`, when they are of several kinds.
    pub shade_legend: Vec<(String, String)>,
    /// Heatmap under the plot area.
    pub heatmap: Option<Heatmap>,
    /// Second speed axis on top.
    pub x2: Option<SecondAxis>,
    /// Named ticks of the vertical axis (rows of a diagram) instead of numbers.
    pub y_ticks: Option<Vec<(f64, String)>>,
}

const PW: f64 = 540.0;
const PH: f64 = 340.0;
const ML: f64 = 74.0;
const MB: f64 = 58.0;
const FONT: f64 = 13.0;
/// Average advance of DejaVu Sans at 13 px, generous, for sizing the legend.
const CHAR_W: f64 = 7.9;
const COLORBAR_W: f64 = 96.0;

/// Round tick positions covering `[lo, hi]`, about `target` of them.
pub fn ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    if !matches!(hi.partial_cmp(&lo), Some(std::cmp::Ordering::Greater)) {
        return vec![lo];
    }
    let raw = (hi - lo) / target.max(1) as f64;
    // a span past the largest float (±1e308) or below the smallest step: one tick
    if !raw.is_finite() || raw <= 0.0 {
        return vec![lo];
    }
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0].iter().map(|m| m * mag).find(|s| *s >= raw).unwrap_or(10.0 * mag);
    let start = (lo / step).ceil() as i64;
    let end = (hi / step).floor() as i64;
    (start..=end).map(|i| i as f64 * step).collect()
}

fn fmt_tick(v: f64) -> String {
    crate::num::fmt(v, 6)
}

fn esc(s: &str) -> String {
    pesc(s).replace('"', "&quot;")
}

/// Escape for Plotly's text, which reads a little HTML (`<br>`, entities).
fn pesc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

fn text_width(s: &str) -> f64 {
    // combining marks (the papers' bars: Ā) take no room
    s.chars().filter(|c| !('\u{0300}'..='\u{036F}').contains(c)).count() as f64 * CHAR_W
}

/// Colour of a heatmap value.
pub fn heat_color(v: f64, scale: ColorScale) -> [u8; 3] {
    if !v.is_finite() {
        return [200, 200, 200];
    }
    match scale {
        ColorScale::Verdict => {
            if v <= 0.0 {
                [168, 221, 181]
            } else {
                [244, 165, 130]
            }
        }
        ColorScale::Diverging { neg, pos } => diverging_colour(diverging_t(v, neg, pos).abs(), v < 0.0),
    }
}

/// The diverging scale's colour at `|t|` (0 … 1) on the negative (blue) or positive (red) side.
fn diverging_colour(t: f64, negative: bool) -> [u8; 3] {
    // `round_i64`: `round()` without the C library's call (a map's PNG and SVG colour
    // every cell: 960 000 calls for 400 x 400), the same value in [0, 255]
    let lerp = |a: f64, b: f64| round_i64(a + (b - a) * t) as u8;
    if negative {
        [lerp(247.0, 33.0), lerp(247.0, 102.0), lerp(247.0, 172.0)]
    } else {
        [lerp(247.0, 178.0), lerp(247.0, 24.0), lerp(247.0, 43.0)]
    }
}

/// [`heat_color`] on a diverging scale by table, the same colours: a value's colour is a
/// function of `q = |v|/side` alone (`diverging_t`: `|t| = sqrt(min(q, 1))`), and each channel
/// is monotone in `q` (every step, division, `min`, `sqrt`, the lerp's multiply and add, the
/// rounding, is a monotone function of its rounded input). `q < 1` falls in the bin
/// `⌊q·BINS⌋` exactly (`BINS` a power of 2: the product is exact) between the endpoints
/// `k/BINS` and `(k+1)/BINS`; where the two endpoints have the same colour every `q` between
/// them has it too, and only the values in bins where a channel steps are computed one by one.
/// For a 400 x 400 margin map: 2 x 4 097 endpoints computed, one bin in ten steps, and a
/// quarter of the cells (the small margins, where the square root is steep) fall in one.
struct DivergingTable {
    /// The sides' extents, as the scale's.
    neg: f64,
    pos: f64,
    /// `[negative side, positive side]`: each bin's colour where it does not step.
    bins: [Vec<Option<[u8; 3]>>; 2],
    /// The colours at `q ≥ 1` (`|t| = 1`).
    ends: [[u8; 3]; 2],
}

impl DivergingTable {
    const BINS: usize = 4096;

    fn new(neg: f64, pos: f64) -> Self {
        let side = |negative: bool| {
            let colour = |k: usize| diverging_colour((k as f64 / Self::BINS as f64).min(1.0).sqrt(), negative);
            let mut prev = colour(0);
            let bins = (1..=Self::BINS)
                .map(|k| {
                    let next = colour(k);
                    let same = (prev == next).then_some(prev);
                    prev = next;
                    same
                })
                .collect();
            (bins, colour(Self::BINS))
        };
        let ((bn, en), (bp, ep)) = (side(true), side(false));
        DivergingTable { neg, pos, bins: [bn, bp], ends: [en, ep] }
    }

    /// `heat_color(v, Diverging { neg, pos })`.
    #[inline]
    fn of(&self, v: f64) -> [u8; 3] {
        if !v.is_finite() {
            return [200, 200, 200];
        }
        // as `diverging_t`: the side of `v < 0`, its extent at least 1e-300
        let negative = v < 0.0;
        let q = v.abs() / if negative { self.neg } else { self.pos }.max(1e-300);
        let s = usize::from(!negative);
        if q >= 1.0 {
            return self.ends[s];
        }
        match self.bins[s][(q * Self::BINS as f64) as usize] {
            Some(c) => c,
            None => diverging_colour(q.sqrt(), negative),
        }
    }
}

/// [`heat_color`] with the last value's colour kept on the verdict's scale, whose cells take
/// two values (its SVG's 160 000 cells for 400 x 400); a margin map's neighbours rarely
/// repeat, so its colours are computed each.
struct ColourCache {
    scale: ColorScale,
    last: Option<(u64, [u8; 3])>,
}

impl ColourCache {
    fn new(scale: ColorScale) -> Self {
        ColourCache { scale, last: None }
    }

    #[inline]
    fn of(&mut self, v: f64) -> [u8; 3] {
        if matches!(self.scale, ColorScale::Diverging { .. }) {
            return heat_color(v, self.scale);
        }
        match self.last {
            Some((bits, c)) if bits == v.to_bits() => c,
            _ => {
                let c = heat_color(v, self.scale);
                self.last = Some((v.to_bits(), c));
                c
            }
        }
    }
}

/// A heatmap's cell colours ([`heat_color`]) in the raster's order, its top row the last `y`:
/// `z[j][i]` at `(ny - 1 - j) * nx + i`; `None` for an empty or ragged grid (which the SVG
/// leaves out). What the SVG's raster and the PNG's painted cells
/// are both made of when a figure is written both ways ([`Plot::to_svg_and_png`]).
fn heat_colours(h: &Heatmap) -> Option<Vec<[u8; 3]>> {
    let (nx, ny) = (h.x.len(), h.y.len());
    if !h.drawable() {
        return None;
    }
    // sized once (a `flat_map`'s collect cannot know its length: it grew and copied)
    let mut out = Vec::with_capacity(nx * ny);
    match h.scale {
        // a table pays where the cells outnumber its 8 194 endpoints several times
        ColorScale::Diverging { neg, pos } if nx * ny >= 8 * DivergingTable::BINS => {
            let table = DivergingTable::new(neg, pos);
            for r in h.z.iter().rev() {
                out.extend(r.iter().map(|&v| table.of(v)));
            }
        }
        _ => {
            let mut colour = ColourCache::new(h.scale);
            for r in h.z.iter().rev() {
                out.extend(r.iter().map(|&v| colour.of(v)));
            }
        }
    }
    Some(out)
}

/// Position on the diverging colour scale, −1 (most negative) … 1: signed square root of the
/// value over its side's extent.
fn diverging_t(v: f64, neg: f64, pos: f64) -> f64 {
    let side = if v < 0.0 { neg } else { pos }.max(1e-300);
    v.signum() * (v.abs() / side).min(1.0).sqrt()
}

/// The value at position `t` (−1 … 1, bottom to top) of a colour bar: the inverse of
/// [`diverging_t`] (`t·|t|` times the side's extent), or `t` itself for the verdict.
fn bar_value(t: f64, scale: ColorScale) -> f64 {
    match scale {
        ColorScale::Verdict => t,
        ColorScale::Diverging { neg, pos } => t.signum() * t * t * if t < 0.0 { neg } else { pos },
    }
}

/// Ticks of a colour bar: (position −1…1, value).
fn colorbar_ticks(scale: ColorScale) -> Vec<(f64, String)> {
    match scale {
        ColorScale::Verdict => vec![(-0.5, "stable".into()), (0.5, "unstable".into())],
        ColorScale::Diverging { neg, pos } => [-1.0, -0.5, 0.0, 0.5, 1.0]
            .iter()
            .map(|&t: &f64| {
                let side = if t < 0.0 { neg } else { pos };
                (t, if t == 0.0 { "0".to_string() } else { crate::num::fmt(t.signum() * t * t * side, 2) })
            })
            .collect(),
    }
}

fn png_bytes(w: usize, h: usize, rgb: &[u8]) -> Result<Vec<u8>, png::EncodingError> {
    // sized as `rasterise` sizes its PNG (an eighth of the pixels' bytes): one allocation, no
    // copies as the file grows
    let mut out = Vec::with_capacity(rgb.len() / 8 + 4096);
    {
        let mut enc = png::Encoder::new(&mut out, w as u32, h as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut wr = enc.write_header()?;
        wr.write_image_data(rgb)?;
    }
    Ok(out)
}

/// Standard base64 (RFC 4648, with padding), for embedding rasters in the SVG. Each whole
/// group of three bytes is four characters written at once into a byte buffer (one capacity
/// check a group, not one a character: a map's SVG embeds ~170 kB of PNG); the last, partial
/// group is padded with `=`.
pub fn base64(data: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s: Vec<u8> = Vec::with_capacity(data.len().div_ceil(3) * 4);
    let groups = data.chunks_exact(3);
    let rest = groups.remainder();
    for g in groups {
        let v = u32::from(g[0]) << 16 | u32::from(g[1]) << 8 | u32::from(g[2]);
        s.extend_from_slice(&[T[(v >> 18) as usize], T[(v >> 12 & 63) as usize], T[(v >> 6 & 63) as usize], T[(v & 63) as usize]]);
    }
    if !rest.is_empty() {
        let v = u32::from(rest[0]) << 16 | u32::from(*rest.get(1).unwrap_or(&0)) << 8;
        let third = if rest.len() == 2 { T[(v >> 6 & 63) as usize] } else { b'=' };
        s.extend_from_slice(&[T[(v >> 18) as usize], T[(v >> 12 & 63) as usize], third, b'=']);
    }
    // every byte is from `T` or `=`: ASCII
    String::from_utf8(s).unwrap_or_default()
}

/// Rows of staggered labels: a label moves down a row while it would overlap the previous
/// one in the same row (`min_gap` in the same units as `xs`).
fn stagger(xs: &[f64], min_gap: f64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..xs.len()).collect();
    order.sort_by(|&a, &b| xs[a].total_cmp(&xs[b]));
    let mut last: Vec<f64> = vec![];
    let mut rows = vec![0; xs.len()];
    for i in order {
        let row = last.iter().position(|&l| xs[i] - l >= min_gap).unwrap_or(last.len());
        if row == last.len() {
            last.push(xs[i]);
        } else {
            last[row] = xs[i];
        }
        rows[i] = row;
    }
    rows
}

/// Legend entries: (label, colour, dashed, markers, is a shade).
fn legend_entries(p: &Plot) -> Vec<(String, String, bool, bool, bool)> {
    let mut out: Vec<(String, String, bool, bool, bool)> =
        p.series.iter().filter(|s| !s.label.is_empty()).map(|s| (s.label.clone(), s.color.clone(), s.dashed, s.markers, false)).collect();
    if let (Some(label), Some(sh)) = (&p.shade_label, p.shades.first()) {
        out.push((label.clone(), sh.color.clone(), false, false, true));
    }
    for (color, label) in &p.shade_legend {
        if p.shades.iter().any(|s| &s.color == color) {
            out.push((label.clone(), color.clone(), false, false, true));
        }
    }
    out
}

impl Plot {
    /// The axis ranges: the configured ones, else the data's (y with 5 % headroom).
    pub fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let pts = self.series.iter().flat_map(|s| s.points.iter()).filter(|p| p.0.is_finite() && p.1.is_finite());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for &(x, y) in pts {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        if let Some(((ha, hb), (va, vb))) = self.heatmap.as_ref().filter(|h| h.drawable()).and_then(Heatmap::cells_span) {
            x0 = x0.min(ha);
            x1 = x1.max(hb);
            y0 = y0.min(va);
            y1 = y1.max(vb);
        }
        // no finite data, or a span past the largest float (points at ±1e308)
        if !(x1 - x0).is_finite() {
            (x0, x1) = (0.0, 1.0);
        }
        if !(y1 - y0).is_finite() {
            (y0, y1) = (0.0, 1.0);
        }
        if x1 - x0 < 1e-12 {
            x0 -= 0.5;
            x1 += 0.5;
        }
        if y1 - y0 < 1e-12 {
            y0 -= 0.5;
            y1 += 0.5;
        }
        let head = if self.heatmap.is_some() { 0.0 } else { 0.05 * (y1 - y0) };
        // a configured range is taken where it is finite and increasing (else the data's)
        let given = |r: Option<(f64, f64)>| r.filter(|&(a, b)| a.is_finite() && b.is_finite() && (b - a).is_finite() && b > a);
        (given(self.x_range).unwrap_or((x0, x1)), given(self.y_range).unwrap_or((y0, y1 + head)))
    }

    /// The raster of the SVG's heatmap (its top row the last `y`), from the cells' colours
    /// ([`heat_colours`]) where given, else computed.
    fn heat_png(h: &Heatmap, colours: Option<&[[u8; 3]]>) -> Option<Vec<u8>> {
        let (nx, ny) = (h.x.len(), h.y.len());
        let own;
        let colours = match colours {
            Some(c) => c,
            None => {
                own = heat_colours(h)?;
                &own[..]
            }
        };
        if nx == 0 || ny == 0 || colours.len() != nx * ny {
            return None;
        }
        // the colours are in the raster's order: no copy
        png_bytes(nx, ny, colours.as_flattened()).ok()
    }

    /// Render to an SVG document.
    pub fn to_svg(&self) -> String {
        self.svg_with(true, true, None).0
    }

    /// The SVG document and the PNG at `scale` of one figure, [`Plot::to_svg`] and
    /// [`Plot::to_png`] byte for byte, with a heatmap's cell colours computed once for both
    /// (each computed all of them: 160 000 colours, ~13 M instructions, for a 400 x 400 map).
    pub fn to_svg_and_png(&self, scale: f32) -> (String, anyhow::Result<Vec<u8>>) {
        let colours = self.heatmap.as_ref().and_then(heat_colours);
        let svg = self.svg_doc(true, true, None, colours.as_deref()).0;
        let png = self.png_with(scale, colours.as_deref());
        (svg, png)
    }

    /// The SVG document of the PNG at `scale`: neither the white background nor the heatmap's
    /// raster are in it, and the heatmap's placement is returned instead: its rectangle
    /// `[x, y, w, h]` and the clip rectangle (the plot area) in the document's units, with
    /// what else the PNG paints itself ([`Plot::svg_with`]).
    fn svg_png(&self, scale: f32) -> (String, Option<HeatPlacement>) {
        self.svg_with(false, true, Some(scale))
    }

    /// The SVG document, its dense curves thinned by [`chord_thin`] where `thin` (the tests
    /// draw them whole to compare); without `embed`, see [`Plot::svg_png`]. With `lean` (the
    /// PNG's scale, with a heatmap left out) the colour bar's raster and the axis-aligned strokes
    /// the PNG paints as tiny-skia would ([`paint_bar`], [`paint_lines`]: wider than a pixel
    /// at that scale, where tiny-skia draws no hairline) are left out too and returned in the
    /// placement; without it (the tests' reference) they are in the document as before.
    fn svg_with(&self, embed: bool, thin: bool, lean: Option<f32>) -> (String, Option<HeatPlacement>) {
        self.svg_doc(embed, thin, lean, None)
    }

    /// [`Plot::svg_with`], the heatmap's raster from `colours` ([`heat_colours`]) where given.
    fn svg_doc(&self, embed: bool, thin: bool, lean: Option<f32>, colours: Option<&[[u8; 3]]>) -> (String, Option<HeatPlacement>) {
        let mut placement: Option<HeatPlacement> = None;
        let ((x0, x1), (y0, y1)) = self.ranges();
        // left margin: room for named row ticks
        let ml = self.y_ticks.as_ref().map_or(ML, |v| ML.max(v.iter().map(|t| text_width(&t.1)).fold(0.0, f64::max) + 40.0));
        let legend = legend_entries(self);
        let legend_w = legend.iter().map(|e| text_width(&e.0)).fold(0.0, f64::max);
        let legend_w = if legend.is_empty() { 0.0 } else { legend_w + 48.0 };
        let cb_w = if self.heatmap.is_some() { COLORBAR_W } else { 0.0 };
        let mt = if self.x2.is_some() { 78.0 } else { 44.0 };
        let w = (ml + PW + 16.0 + cb_w + legend_w).ceil();
        // title: wrapped to the width
        let max_chars = ((w - 20.0) / 8.6).max(20.0) as usize;
        let title_lines = wrap(&self.title, max_chars);
        let mt = mt + 18.0 * (title_lines.len().saturating_sub(1)) as f64;
        let legend_h = 24.0 * legend.len() as f64 + 8.0;
        let h = (mt + PH.max(legend_h) + MB).ceil();
        let sx = |x: f64| ml + (x - x0) / (x1 - x0) * PW;
        let sy = |y: f64| mt + (1.0 - (y - y0) / (y1 - y0)) * PH;
        // the text's size known ahead, one allocation: the frame, ~16 bytes a drawn point (at
        // most 4 a pixel column of each unbroken line, `pixel_columns`), a raster's base64
        let drawn: usize = self.series.iter().map(|se| se.points.len().min(4 * PW as usize + 64)).sum();
        let raster = self.heatmap.as_ref().map_or(0, |h| 4 * h.x.len() * h.y.len());
        let mut s = String::with_capacity(8192 + 16 * drawn + raster);
        let background = if embed { "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n" } else { "" };
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, Verdana, sans-serif" font-size="{FONT}">
{background}<defs><clipPath id="plotarea"><rect x="{ml}" y="{mt}" width="{PW}" height="{PH}"/></clipPath></defs>"#
        );
        for (k, line) in title_lines.iter().enumerate() {
            let _ = writeln!(
                s,
                r#"<text x="{}" y="{}" text-anchor="middle" font-size="15" font-weight="bold">{}</text>"#,
                w / 2.0,
                22.0 + 18.0 * k as f64,
                esc(line)
            );
        }
        if let (false, Some(((ha, hb), (va, vb)))) = (embed, self.heatmap.as_ref().filter(|h| h.drawable()).and_then(Heatmap::cells_span)) {
            placement = Some(HeatPlacement { rect: [sx(ha), sy(vb), sx(hb) - sx(ha), sy(va) - sy(vb)], clip: [ml, mt, PW, PH], bar: None, lines: vec![] });
        }
        // with a heatmap left out, the PNG also paints the figure's axis-aligned strokes itself
        // (ticks, frames, a map's boundaries, legend lines), in the document's order, after its
        // render ([`paint_lines`]); they are written here only where it does not
        let lean = lean.filter(|_| placement.is_some());
        let direct = lean.is_some();
        // a stroke the PNG paints: wider than a pixel (tiny-skia draws a hairline otherwise)
        let thick = |width: f64| lean.is_some_and(|k| width * f64::from(k) > 1.0);
        let mut lines: Vec<StraightLine> = vec![];
        let gray = [0x33, 0x33, 0x33];
        // the last series that are all axis-aligned polylines of a known colour are painted by
        // the PNG itself (after the render: nothing drawn later reaches into the plot area), in
        // their order; any other curve after them would have been drawn over them, so only a
        // run of them at the end; the ticks and the plot area's frame, drawn before them and
        // under them, only when all are and nothing else is drawn over the frame
        let direct_from = match direct {
            // (a millionth of a pixel: the points as written, to two decimals, share it exactly)
            true => {
                let tol = (1e-6 * (x1 - x0) / PW, 1e-6 * (y1 - y0) / PH);
                self.series.len() - self.series.iter().rev().take_while(|se| thick(se.width.unwrap_or(2.0)) && se.straight_polyline(tol)).count()
            }
            false => self.series.len(),
        };
        // (nothing else drawn over the frame: no vertical markers, no top axis's ticks)
        let frames = direct_from == 0 && thick(1.0) && self.vlines.is_empty() && self.x2.is_none();
        // the raster's cells centred on the grid values (`heat_png` is `None` unless the heatmap
        // is drawable)
        let embedded = self.heatmap.as_ref().filter(|_| embed).and_then(|h| Some((Self::heat_png(h, colours)?, h.cells_span()?)));
        if let Some((png, ((ha, hb), (va, vb)))) = embedded {
            // clipped to the plot area only where it reaches outside it (a map's raster fills
            // it exactly, and a clip costs the PNG rasteriser a mask over the whole figure)
            let inside = sx(ha) >= ml - 0.01 && sx(hb) <= ml + PW + 0.01 && sy(vb) >= mt - 0.01 && sy(va) <= mt + PH + 0.01;
            let (open, close) = if inside { ("<g>", "</g>") } else { (r#"<g clip-path="url(#plotarea)">"#, "</g>") };
            let _ = writeln!(
                s,
                r#"{open}<image x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" preserveAspectRatio="none" image-rendering="optimizeSpeed" style="image-rendering:pixelated" href="data:image/png;base64,{}"/>{close}"#,
                sx(ha),
                sy(vb),
                sx(hb) - sx(ha),
                sy(va) - sy(vb),
                base64(&png)
            );
        }
        // the shades, clipped to the plot area (no group when none is drawn: an empty clipped
        // group still costs the PNG rasteriser a layer and a mask over the whole figure)
        let shades_at = s.len();
        s.push_str("<g clip-path=\"url(#plotarea)\">\n");
        let mut shaded = false;
        for sh in &self.shades {
            let (ya, yb) = (sh.y.0.unwrap_or(y0).max(y0), sh.y.1.unwrap_or(y1).min(y1));
            if yb <= ya {
                continue;
            }
            let (xa, xb) = (sx(sh.x.0.max(x0)), sx(sh.x.1.min(x1)));
            let _ = writeln!(
                s,
                r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{}" fill-opacity="0.3"/>"#,
                xa,
                sy(yb),
                (xb - xa).max(0.0),
                sy(ya) - sy(yb),
                sh.color
            );
            shaded = true;
        }
        if shaded {
            s.push_str("</g>\n");
        } else {
            s.truncate(shades_at);
        }
        // grid and ticks
        let grid = if self.heatmap.is_some() { "none" } else { "#e3e3e3" };
        for t in ticks(x0, x1, 7) {
            if frames {
                // (a heatmap's grid lines are `stroke="none"`: nothing drawn)
                let x = two_decimals(sx(t));
                lines.push(StraightLine::new(vec![(x, mt + PH), (x, mt + PH + 5.0)], 1.0, gray));
                let _ = writeln!(s, r#"<text x="{:.2}" y="{}" text-anchor="middle">{}</text>"#, sx(t), mt + PH + 19.0, fmt_tick(t));
                continue;
            }
            let _ = writeln!(
                s,
                r##"<line x1="{0:.2}" y1="{1}" x2="{0:.2}" y2="{2}" stroke="{grid}"/><line x1="{0:.2}" y1="{2}" x2="{0:.2}" y2="{3}" stroke="#333"/><text x="{0:.2}" y="{4}" text-anchor="middle">{5}</text>"##,
                sx(t),
                mt,
                mt + PH,
                mt + PH + 5.0,
                mt + PH + 19.0,
                fmt_tick(t)
            );
        }
        let yt: Vec<(f64, String)> = match &self.y_ticks {
            Some(v) => v.iter().filter(|t| t.0 >= y0 && t.0 <= y1).cloned().collect(),
            None => ticks(y0, y1, 6).into_iter().map(|t| (t, fmt_tick(t))).collect(),
        };
        for (t, label) in yt {
            if frames {
                let y = two_decimals(sy(t));
                lines.push(StraightLine::new(vec![(ml - 5.0, y), (ml, y)], 1.0, gray));
                let _ = writeln!(s, r#"<text x="{}" y="{:.2}" text-anchor="end">{}</text>"#, ml - 8.0, sy(t) + 4.5, esc(&label));
                continue;
            }
            let _ = writeln!(
                s,
                r##"<line x1="{1}" y1="{0:.2}" x2="{2}" y2="{0:.2}" stroke="{grid}"/><line x1="{3}" y1="{0:.2}" x2="{1}" y2="{0:.2}" stroke="#333"/><text x="{4}" y="{5:.2}" text-anchor="end">{6}</text>"##,
                sy(t),
                ml,
                ml + PW,
                ml - 5.0,
                ml - 8.0,
                sy(t) + 4.5,
                esc(&label)
            );
        }
        if let Some(a) = &self.x2 {
            for t in ticks(x0 * a.factor, x1 * a.factor, 7) {
                let x = sx(t / a.factor);
                let _ = writeln!(
                    s,
                    r##"<line x1="{x:.2}" y1="{mt}" x2="{x:.2}" y2="{}" stroke="#333"/><text x="{x:.2}" y="{}" text-anchor="middle">{}</text>"##,
                    mt - 5.0,
                    mt - 9.0,
                    fmt_tick(t)
                );
            }
            let _ = writeln!(s, r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#, ml + PW / 2.0, mt - 28.0, esc(&a.label));
        }
        if y0 < 0.0 && y1 > 0.0 && self.heatmap.is_none() {
            let _ = writeln!(s, r##"<line x1="{ml}" y1="{0:.2}" x2="{1}" y2="{0:.2}" stroke="#666"/>"##, sy(0.0), ml + PW);
        }
        if frames {
            lines.push(StraightLine::frame([ml, mt, PW, PH], gray));
        } else {
            let _ = writeln!(s, r##"<rect x="{ml}" y="{mt}" width="{PW}" height="{PH}" fill="none" stroke="#333"/>"##);
        }
        let _ = writeln!(s, r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#, ml + PW / 2.0, mt + PH + 42.0, esc(&self.x_label));
        let _ = writeln!(s, r#"<text x="18" y="{0}" text-anchor="middle" transform="rotate(-90 18 {0})">{1}</text>"#, mt + PH / 2.0, esc(&self.y_label));
        // the curves and vertical markers, written apart first: their group is clipped to the
        // plot area only where something drawn reaches outside it (`drawn_inside`; a clip costs
        // the PNG rasteriser a layer and a mask over the whole figure, a third of a map's PNG)
        let doc = std::mem::replace(&mut s, String::with_capacity(1024 + 16 * drawn));
        let area = [ml, ml + PW, mt, mt + PH];
        let vis: Vec<&(f64, String)> = self.vlines.iter().filter(|(x, _)| *x >= x0 && *x <= x1).collect();
        // a marker's label may run past the plot area's right edge
        let mut clip = !vis.is_empty();
        let rows = stagger(&vis.iter().map(|v| sx(v.0)).collect::<Vec<_>>(), 30.0);
        for ((x, label), row) in vis.iter().zip(rows) {
            let _ = writeln!(
                s,
                r##"<line x1="{0:.2}" y1="{1}" x2="{0:.2}" y2="{2}" stroke="#666" stroke-dasharray="2 3" stroke-width="1"/><text x="{3:.2}" y="{4}" fill="#444" stroke="none" font-size="11">{5}</text>"##,
                sx(*x),
                mt,
                mt + PH,
                sx(*x) + 3.0,
                mt + 13.0 + 13.0 * row as f64,
                esc(label)
            );
        }
        let curves_from = lines.len();
        for (n, se) in self.series.iter().enumerate() {
            let direct = n >= direct_from;
            let dash = if se.dashed { r#" stroke-dasharray="7 4""# } else { "" };
            // pixel coordinates of one unbroken piece of the curve (NaN breaks it), reduced to
            // what a pixel column shows (`pixel_columns`), written with two decimals
            let mut seg: Vec<(f64, f64)> = Vec::with_capacity(se.points.len());
            let mut flush = |seg: &mut Vec<(f64, f64)>, s: &mut String, clip: &mut bool| {
                if se.markers {
                    *clip |= !seg.iter().all(|&p| disk_inside(p, 3.5, area));
                    for &(x, y) in seg.iter() {
                        s.push_str(r#"<circle cx=""#);
                        push_px(s, x);
                        s.push_str(r#"" cy=""#);
                        push_px(s, y);
                        let _ = writeln!(s, r#"" r="3.5" fill="{}" stroke="none"/>"#, se.color);
                    }
                } else if seg.len() >= 2 {
                    let mut kept = pixel_columns(seg);
                    // (decided on the column points: the same for a line built from its columns,
                    // `line_columns`)
                    let dense = kept.len() > THIN_ABOVE;
                    if thin && dense {
                        kept = chord_thin(&kept, THIN_PX);
                    }
                    *clip |= !drawn_inside(&kept, se.width.unwrap_or(2.0) / 2.0, area);
                    // the points as the document writes them (two decimals)
                    let written = || kept.iter().map(|&(x, y)| (round_i64(x * 100.0) as f64 / 100.0, round_i64(y * 100.0) as f64 / 100.0)).collect::<Vec<_>>();
                    let axis_aligned = |p: &[(f64, f64)]| p.windows(2).all(|w| w[0].0 == w[1].0 || w[0].1 == w[1].1);
                    if direct {
                        let pts = written();
                        if let (true, Some(color)) = (axis_aligned(&pts), hex_color(&se.color)) {
                            lines.push(StraightLine { pts, half: se.width.unwrap_or(2.0) / 2.0, color, dashed: se.dashed, clipped: false });
                            seg.clear();
                            return;
                        }
                    }
                    s.push_str(r#"<polyline points=""#);
                    let mut text: Vec<u8> = Vec::with_capacity(16 * kept.len());
                    for (k, &(x, y)) in kept.iter().enumerate() {
                        if k > 0 {
                            text.push(b' ');
                        }
                        push_px_bytes(&mut text, x);
                        text.push(b',');
                        push_px_bytes(&mut text, y);
                    }
                    // digits, '.', '-', ',' and ' ': ASCII
                    s.push_str(std::str::from_utf8(&text).unwrap_or(""));
                    // a dense curve's joins round: its column points turn sharply within a
                    // pixel, where a miter join would draw a spike of up to 4 px (SVG's miter
                    // limit) that the data do not have, and which thinning would move; not an
                    // axis-aligned one (a map's cell edges), whose right-angle miters are the
                    // square corners of its cells
                    // (`axis_aligned(&written())` without building the written points: the same
                    // rounding, stopped at the first turn)
                    let px = |v: f64| round_i64(v * 100.0) as f64 / 100.0;
                    let written_axis_aligned = || kept.windows(2).all(|w| px(w[0].0) == px(w[1].0) || px(w[0].1) == px(w[1].1));
                    let join = if dense && !written_axis_aligned() { r#" stroke-linejoin="round""# } else { "" };
                    let _ = writeln!(s, r#"" stroke="{}" stroke-width="{}"{join}{dash}/>"#, se.color, se.width.unwrap_or(2.0));
                } else if let Some(&(x, y)) = seg.first() {
                    *clip |= !disk_inside((x, y), 2.0, area);
                    s.push_str(r#"<circle cx=""#);
                    push_px(s, x);
                    s.push_str(r#"" cy=""#);
                    push_px(s, y);
                    let _ = writeln!(s, r#"" r="2" fill="{}" stroke="none"/>"#, se.color);
                }
                seg.clear();
            };
            for &(x, y) in &se.points {
                if x.is_finite() && y.is_finite() {
                    // keep far-off points finite in SVG while the clip path hides them
                    seg.push((sx(x).clamp(-1e4, 1e4), sy(y).clamp(-1e4, 1e4)));
                } else {
                    flush(&mut seg, &mut s, &mut clip);
                }
            }
            flush(&mut seg, &mut s, &mut clip);
        }
        for l in &mut lines[curves_from..] {
            l.clipped = clip;
        }
        // `s` holds the curves, `doc` the document before them
        let curves = std::mem::replace(&mut s, doc);
        s.push_str(if clip { "<g clip-path=\"url(#plotarea)\" fill=\"none\" stroke-width=\"2\">\n" } else { "<g fill=\"none\" stroke-width=\"2\">\n" });
        s.push_str(&curves);
        s.push_str("</g>\n");
        // colour bar
        let mut lx = ml + PW + 16.0;
        if let Some(hm) = &self.heatmap {
            let (bx, bw) = (lx + 4.0, 16.0);
            let n = 64;
            // the PNG paints the bar's colours itself, one per pixel row ([`paint_bar`])
            let painted = direct && placement.as_mut().map(|at| at.bar = Some(([bx, mt, bw, PH], hm.scale))).is_some();
            let colours = || {
                let mut px = Vec::with_capacity(n * 3);
                for k in (0..n).rev() {
                    px.extend_from_slice(&heat_color(bar_value(-1.0 + 2.0 * (k as f64 + 0.5) / n as f64, hm.scale), hm.scale));
                }
                px
            };
            if painted && thick(1.0) {
                lines.push(StraightLine::frame([bx, mt, bw, PH], gray));
            } else if painted {
                let _ = writeln!(s, r##"<rect x="{bx}" y="{mt}" width="{bw}" height="{PH}" fill="none" stroke="#333"/>"##);
            } else if let Ok(png) = png_bytes(1, n, &colours()) {
                let _ = writeln!(
                    s,
                    r##"<image x="{bx}" y="{mt}" width="{bw}" height="{PH}" preserveAspectRatio="none" href="data:image/png;base64,{}"/><rect x="{bx}" y="{mt}" width="{bw}" height="{PH}" fill="none" stroke="#333"/>"##,
                    base64(&png)
                );
            }
            for (t, label) in colorbar_ticks(hm.scale) {
                let y = mt + (1.0 - (t + 1.0) / 2.0) * PH;
                if thick(1.0) {
                    let yw = two_decimals(y);
                    lines.push(StraightLine::new(vec![(bx + bw, yw), (bx + bw + 4.0, yw)], 1.0, gray));
                    let _ = writeln!(s, r#"<text x="{}" y="{:.2}" font-size="12">{}</text>"#, bx + bw + 6.0, y + 4.0, esc(&label));
                    continue;
                }
                let _ = writeln!(
                    s,
                    r##"<line x1="{}" y1="{y:.2}" x2="{}" y2="{y:.2}" stroke="#333"/><text x="{}" y="{:.2}" font-size="12">{}</text>"##,
                    bx + bw,
                    bx + bw + 4.0,
                    bx + bw + 6.0,
                    y + 4.0,
                    esc(&label)
                );
            }
            let _ = writeln!(
                s,
                r#"<text x="{0}" y="{1}" text-anchor="middle" font-size="12" transform="rotate(-90 {0} {1})">{2}</text>"#,
                bx - 6.0,
                mt + PH / 2.0,
                esc(&hm.label)
            );
            lx += cb_w;
        }
        // legend
        let mut ly = mt + 10.0;
        for (label, color, dashed, markers, shade) in legend {
            if shade {
                let _ = writeln!(s, r#"<rect x="{lx}" y="{}" width="30" height="12" fill="{color}" fill-opacity="0.3"/>"#, ly - 6.0);
            } else if markers {
                let _ = writeln!(s, r#"<circle cx="{}" cy="{ly}" r="3.5" fill="{color}"/>"#, lx + 15.0);
            } else if let (true, Some(c)) = (thick(2.5), hex_color(&color)) {
                lines.push(StraightLine { pts: vec![(lx, ly), (lx + 30.0, ly)], half: 1.25, color: c, dashed, clipped: false });
            } else {
                let dash = if dashed { r#" stroke-dasharray="7 4""# } else { "" };
                let _ = writeln!(s, r#"<line x1="{lx}" y1="{ly}" x2="{}" y2="{ly}" stroke="{color}" stroke-width="2.5"{dash}/>"#, lx + 30.0);
            }
            let _ = writeln!(s, r#"<text x="{}" y="{}">{}</text>"#, lx + 38.0, ly + 4.5, esc(&label));
            ly += 24.0;
        }
        s.push_str("</svg>\n");
        if let Some(at) = placement.as_mut() {
            at.lines = lines;
        }
        (s, placement)
    }

    /// Rasterise [`Plot::to_svg`] at `scale` (2 gives a sharp 150 dpi-like image), with the
    /// DejaVu fonts compiled into the binary. A heatmap's cells are painted straight into the
    /// pixels (nearest cell at each pixel's centre, clipped to the plot area: what the SVG's
    /// `image-rendering="optimizeSpeed"` raster gives) on white, and the rest of the figure is
    /// rasterised over them, instead of the SVG's embedded PNG being decoded and resampled.
    pub fn to_png(&self, scale: f32) -> anyhow::Result<Vec<u8>> {
        self.png_with(scale, None)
    }

    /// [`Plot::to_png`], the heatmap's cells painted in `colours` ([`heat_colours`]) where
    /// given.
    fn png_with(&self, scale: f32, colours: Option<&[[u8; 3]]>) -> anyhow::Result<Vec<u8>> {
        let (Some(h), (svg, Some(at))) = (&self.heatmap, self.svg_png(scale)) else { return svg_to_png(&self.to_svg(), scale) };
        if !h.drawable() {
            // a heatmap the SVG leaves out (ragged rows) is left out here too
            return svg_to_png(&self.to_svg(), scale);
        }
        rasterise(&svg, scale, true, |pix| paint_under(pix, h, &at, scale, colours), |pix| paint_over(pix, &at, scale))
    }

    /// The figure as Plotly JSON `{data, layout}` for the interactive report. Values are
    /// rounded to 6 significant digits; NaN becomes null (a gap in the line).
    pub fn to_plotly(&self) -> Value {
        use crate::num::round_sig;
        let r = |v: f64| round_sig(v, 6);
        let ((x0, x1), (y0, y1)) = self.ranges();
        let mut data = vec![];
        if let Some(h) = &self.heatmap {
            let t: Vec<Vec<Option<f64>>> =
                h.z.iter()
                    .map(|row| {
                        row.iter()
                            .map(|&v| {
                                if !v.is_finite() {
                                    return None;
                                }
                                round_sig(
                                    match h.scale {
                                        ColorScale::Verdict => v.signum() * 0.5,
                                        ColorScale::Diverging { neg, pos } => diverging_t(v, neg, pos),
                                    },
                                    4,
                                )
                            })
                            .collect()
                    })
                    .collect();
            let raw: Vec<Vec<Option<f64>>> = h.z.iter().map(|row| row.iter().map(|&v| round_sig(v, 4)).collect()).collect();
            let rgb = |v: f64| {
                let c = heat_color(v, h.scale);
                format!("rgb({},{},{})", c[0], c[1], c[2])
            };
            let (colorscale, hover) = match h.scale {
                ColorScale::Verdict => {
                    (json!([[0.0, rgb(-1.0)], [0.5, rgb(-1.0)], [0.5, rgb(1.0)], [1.0, rgb(1.0)]]), format!("{}: %{{customdata:.0f}}", pesc(&h.label)))
                }
                ColorScale::Diverging { neg, pos } => {
                    let stops: Vec<Value> = (0..=20)
                        .map(|k| {
                            let t = -1.0 + k as f64 / 10.0;
                            let v = t.signum() * t * t * if t < 0.0 { neg } else { pos };
                            json!([k as f64 / 20.0, rgb(if t == 0.0 { 0.0 } else { v })])
                        })
                        .collect();
                    (Value::Array(stops), format!("{} = %{{customdata:.3e}}", pesc(&h.label)))
                }
            };
            let cb = colorbar_ticks(h.scale);
            data.push(json!({
                "type": "heatmap",
                "name": h.label,
                "x": h.x.iter().map(|&v| r(v)).collect::<Vec<_>>(),
                "y": h.y.iter().map(|&v| r(v)).collect::<Vec<_>>(),
                "z": t,
                "customdata": raw,
                "zmin": -1.0, "zmax": 1.0,
                "colorscale": colorscale,
                "showlegend": false,
                "hoverongaps": false,
                "hovertemplate": format!("{} = %{{x:.4g}}<br>{} = %{{y:.4g}}<br>{hover}<extra></extra>", pesc(&self.x_label), pesc(&self.y_label)),
                "colorbar": {
                    "title": {"text": h.label, "side": "right"},
                    "tickvals": cb.iter().map(|c| c.0).collect::<Vec<_>>(),
                    "ticktext": cb.iter().map(|c| c.1.clone()).collect::<Vec<_>>(),
                    "x": 1.02, "xanchor": "left", "len": 1.0, "thickness": 16
                }
            }));
        }
        let mut seen_groups = std::collections::HashSet::new();
        for (k, se) in self.series.iter().enumerate() {
            // a curve whose points are all gaps draws nothing: no trace (its legend entry would
            // name a curve that is not there; a simulate figure's "semi-balanced (= s2)" where
            // that state exists nowhere on the run's speeds, audit 21). A series without points
            // is a legend entry by design (the Campbell diagram's log-decrement classes): kept.
            if !se.points.is_empty() && !se.points.iter().any(|p| p.0.is_finite() && p.1.is_finite()) {
                continue;
            }
            let group = se.group.clone().unwrap_or_else(|| format!("s{k}"));
            let first = seen_groups.insert(group.clone());
            let show = !se.label.is_empty() && first;
            let name = if se.label.is_empty() {
                // hover shows the group's name
                self.series.iter().find(|o| o.group.as_deref() == Some(group.as_str()) && !o.label.is_empty()).map_or(String::new(), |o| o.label.clone())
            } else {
                se.label.clone()
            };
            data.push(json!({
                "type": "scatter",
                "mode": if se.markers { "markers" } else { "lines" },
                "name": name,
                "legendgroup": group,
                "showlegend": show,
                "x": se.points.iter().map(|p| if p.1.is_finite() { r(p.0) } else { None }).collect::<Vec<_>>(),
                "y": se.points.iter().map(|p| if p.0.is_finite() { r(p.1) } else { None }).collect::<Vec<_>>(),
                "line": {"color": se.color, "width": se.width.unwrap_or(2.0), "dash": if se.dashed { "dash" } else { "solid" }},
                "marker": {"color": se.color, "size": 7},
                "hovertemplate": format!("{}<br>{} = %{{x:.4g}}<br>{} = %{{y:.4g}}<extra></extra>", pesc(&name), pesc(&self.x_label), pesc(&self.y_label)),
            }));
        }
        let mut shapes = vec![];
        let mut annotations = vec![];
        for (k, sh) in self.shades.iter().enumerate() {
            let mut shape = json!({
                "type": "rect", "xref": "x", "yref": "y", "layer": "below",
                "x0": r(sh.x.0.max(x0)), "x1": r(sh.x.1.min(x1)),
                "y0": r(sh.y.0.unwrap_or(y0).max(y0)), "y1": r(sh.y.1.unwrap_or(y1).min(y1)),
                "fillcolor": sh.color, "opacity": 0.3, "line": {"width": 0},
                "legendgroup": "shade",
            });
            if let Some((_, l)) = self.shade_legend.iter().find(|c| c.0 == sh.color) {
                shape["legendgroup"] = json!(format!("shade {}", sh.color));
                if self.shades[..k].iter().all(|o| o.color != sh.color) {
                    shape["showlegend"] = json!(true);
                    shape["name"] = json!(pesc(l));
                }
            } else if k == 0 {
                if let Some(l) = &self.shade_label {
                    shape["showlegend"] = json!(true);
                    shape["name"] = json!(pesc(l));
                }
            }
            shapes.push(shape);
        }
        let vis: Vec<&(f64, String)> = self.vlines.iter().filter(|(x, _)| *x >= x0 && *x <= x1).collect();
        let rows = stagger(&vis.iter().map(|v| (v.0 - x0) / (x1 - x0)).collect::<Vec<_>>(), 0.05);
        for ((x, label), row) in vis.iter().zip(rows) {
            shapes.push(json!({"type": "line", "xref": "x", "yref": "paper", "x0": r(*x), "x1": r(*x), "y0": 0, "y1": 1,
                "line": {"color": "#666", "width": 1, "dash": "dot"}}));
            annotations.push(json!({"x": r(*x), "xref": "x", "yref": "paper", "y": 1, "yanchor": "top", "xanchor": "left",
                "yshift": -2.0 - 14.0 * row as f64, "text": pesc(label), "showarrow": false, "font": {"size": 11, "color": "#444"},
                "hovertext": format!("{} = {}", pesc(label), crate::num::fmt(*x, 4))}));
        }
        let mut layout = json!({
            "title": {"text": pesc(&self.title), "font": {"size": 15}},
            "xaxis": {"title": {"text": pesc(&self.x_label)}, "range": [r(x0), r(x1)], "zeroline": false, "showline": true, "mirror": true, "ticks": "outside"},
            "yaxis": {"title": {"text": pesc(&self.y_label)}, "range": [r(y0), r(y1)], "zeroline": self.heatmap.is_none(), "showline": true, "mirror": true, "ticks": "outside"},
            "hovermode": "closest",
            "legend": {"x": if self.heatmap.is_some() { 1.16 } else { 1.02 }, "xanchor": "left", "y": 1, "yanchor": "top"},
            "margin": {"l": 70, "r": 20, "t": if self.x2.is_some() { 115 } else { 60 }, "b": 60},
            "shapes": shapes,
            "annotations": annotations,
            "font": {"family": "DejaVu Sans, Verdana, sans-serif", "size": 13},
            "plot_bgcolor": "white",
            "paper_bgcolor": "white",
        });
        if let Some(t) = &self.y_ticks {
            layout["yaxis"]["tickvals"] = json!(t.iter().map(|t| t.0).collect::<Vec<_>>());
            layout["yaxis"]["ticktext"] = json!(t.iter().map(|t| pesc(&t.1)).collect::<Vec<_>>());
        }
        if let Some(a) = &self.x2 {
            layout["xaxis2"] = json!({"title": {"text": pesc(&a.label), "standoff": 4}, "overlaying": "x", "side": "top", "range": [r(x0 * a.factor), r(x1 * a.factor)],
                "showgrid": false, "ticks": "outside", "tickmode": "auto", "fixedrange": true});
            layout["title"]["y"] = json!(0.985);
            layout["title"]["yanchor"] = json!("top");
            layout["meta"] = json!({"x2factor": a.factor});
            // an axis shows only with a trace on it: an invisible one, named after the axis,
            // along the bottom of the plot from one end of the axis to the other (finite: a
            // trace of nulls read as an empty, unnamed curve, audit 21)
            data.push(json!({"type": "scatter", "name": pesc(&a.label), "x": [r(x0 * a.factor), r(x1 * a.factor)], "y": [r(y0), r(y0)], "xaxis": "x2",
                "showlegend": false, "hoverinfo": "skip", "mode": "lines", "opacity": 0}));
        }
        json!({"data": data, "layout": layout})
    }

    /// Number of finite data points of the curves and heatmap (what the report's browser test
    /// expects the page to hold).
    pub fn point_count(&self) -> usize {
        let s: usize = self.series.iter().map(|s| s.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()).count()).sum();
        s + self.heatmap.as_ref().map_or(0, |h| h.z.iter().flatten().filter(|v| v.is_finite()).count())
    }
}

/// Slack of [`drawn_inside`] and [`disk_inside`] (px): coordinates are written with two
/// decimals, so a point computed on the plot area's edge may be written up to 0.005 px past it.
const EDGE_SLACK: f64 = 0.01;

/// Whether a polyline stroked with half-width `half` (butt caps, miter joins: SVG's defaults)
/// stays inside `area = [x0, x1, y0, y1]` (to [`EDGE_SLACK`]), so that clipping it to the plot
/// area changes no pixel: every point at least `half` inside, except an end point on or
/// near an edge whose segment is perpendicular to that edge (a map's cell-edge boundary ends
/// on the plot area's edge: its butt cap lies along the edge, nothing is drawn past it).
fn drawn_inside(pts: &[(f64, f64)], half: f64, area: [f64; 4]) -> bool {
    let [x0, x1, y0, y1] = area;
    let n = pts.len();
    pts.iter().enumerate().all(|(k, &(x, y))| {
        if !(x >= x0 - EDGE_SLACK && x <= x1 + EDGE_SLACK && y >= y0 - EDGE_SLACK && y <= y1 + EDGE_SLACK) {
            return false;
        }
        let near_x = x < x0 + half || x > x1 - half;
        let near_y = y < y0 + half || y > y1 - half;
        if !near_x && !near_y {
            return true;
        }
        // an end, and its segment perpendicular to the edge it is near
        let other = match k {
            0 if n > 1 => pts[1],
            _ if k + 1 == n && n > 1 => pts[n - 2],
            _ => return false,
        };
        // perpendicular to a millionth of a pixel (a map's cell edges meet at points computed
        // from neighbouring cells, equal to rounding): the cap's corner then reaches past the
        // edge by less than that
        (!near_x || (other.1 - y).abs() <= 1e-6) && (!near_y || (other.0 - x).abs() <= 1e-6)
    })
}

/// Whether a disk of radius `r` about `p` lies inside `area = [x0, x1, y0, y1]` (to
/// [`EDGE_SLACK`]).
fn disk_inside(p: (f64, f64), r: f64, area: [f64; 4]) -> bool {
    let [x0, x1, y0, y1] = area;
    p.0 - r >= x0 - EDGE_SLACK && p.0 + r <= x1 + EDGE_SLACK && p.1 - r >= y0 - EDGE_SLACK && p.1 + r <= y1 + EDGE_SLACK
}

/// Append a pixel coordinate with two decimals (a hundredth of a pixel, below what any
/// renderer resolves): `round(100 v)` split into integer and hundredths, the same text as
/// `format!("{v:.2}")` but without its exact-decimal machinery (the figures of a 4 801-sample
/// run write tens of thousands of them). `|v| ≤ 1e4` here (the caller clamps).
fn push_px(s: &mut String, v: f64) {
    let (buf, k) = px_text(v);
    s.push_str(std::str::from_utf8(&buf[k..]).unwrap_or("0"));
}

/// [`push_px`]'s text appended to bytes: a polyline's coordinates are written into one byte
/// buffer and checked as UTF-8 once (a check per coordinate cost more than the digits).
fn push_px_bytes(out: &mut Vec<u8>, v: f64) {
    let (buf, k) = px_text(v);
    out.extend_from_slice(&buf[k..]);
}

/// [`push_px`]'s text: it is `buf[k..]`.
#[inline]
fn px_text(v: f64) -> ([u8; 24], usize) {
    let c = v * 100.0;
    let c = if c.abs() < 1e15 { round_i64(c) } else { 0 };
    let a = c.unsigned_abs();
    // written backwards: hundredths, tenths, point, integer digits, sign
    let mut buf = [b'0'; 24];
    let mut k = buf.len() - 3;
    buf[k + 2] = b'0' + (a % 10) as u8;
    buf[k + 1] = b'0' + (a / 10 % 10) as u8;
    buf[k] = b'.';
    let mut int = a / 100;
    loop {
        k -= 1;
        buf[k] = b'0' + (int % 10) as u8;
        int /= 10;
        if int == 0 {
            break;
        }
    }
    if c < 0 {
        k -= 1;
        buf[k] = b'-';
    }
    (buf, k)
}

/// `v.round()` (half away from zero) for `|v| < 2^52`, as an integer, without the C library's
/// call: `v − trunc(v)` is exact there, so the comparison with ½ is the rounding's own.
fn round_i64(v: f64) -> i64 {
    let i = v as i64;
    let f = v - i as f64;
    if f >= 0.5 {
        i + 1
    } else if f <= -0.5 {
        i - 1
    } else {
        i
    }
}

/// `⌊v⌋` for `|v| < 2^52`, as an integer, without the C library's call.
fn floor_i64(v: f64) -> i64 {
    let i = v as i64;
    if (i as f64) > v {
        i - 1
    } else {
        i
    }
}

/// A polyline in pixel coordinates reduced to what a one-pixel column shows: each run of
/// consecutive points in the same column `⌊x⌋` keeps its first, lowest, highest and last point,
/// in their order along the curve (M4 aggregation). Every vertical extent, peak and the order of
/// entry and exit of each column are kept, so the drawn line differs from the full one by less
/// than a pixel; a curve that goes back (x not increasing) only starts a new run. A 4 801-sample
/// run over the 540-pixel plot keeps at most 4 points a column.
fn pixel_columns(pts: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut keep: Vec<usize> = Vec::with_capacity(pts.len().min(4 * PW as usize + 8));
    let mut i = 0;
    while i < pts.len() {
        // the caller clamps to ±1e4: the column as an integer is `⌊x⌋` exactly
        let col = floor_i64(pts[i].0);
        let (mut lo, mut hi, mut j) = (i, i, i + 1);
        while j < pts.len() && floor_i64(pts[j].0) == col {
            if pts[j].1 < pts[lo].1 {
                lo = j;
            }
            if pts[j].1 > pts[hi].1 {
                hi = j;
            }
            j += 1;
        }
        for k in [i, lo.min(hi), lo.max(hi), j - 1] {
            // ascending indices, each once
            if keep.last().is_none_or(|&l| l < k) {
                keep.push(k);
            }
        }
        i = j;
    }
    keep.into_iter().map(|k| pts[k]).collect()
}

/// An unbroken piece of a curve of more points than this in its pixel columns
/// ([`pixel_columns`]) is drawn thinned by [`chord_thin`]: about 4 px apart or closer over the
/// 540 px plot, its vertices are not visible as such (a sweep's curve of a few dozen runs
/// keeps a vertex per run).
const THIN_ABOVE: usize = 128;

/// How far (px) a dropped vertex may lie from the line drawn instead ([`chord_thin`]): a
/// twentieth of a pixel, far under the 2 px stroke's antialiased edge (at a quarter of a pixel
/// a smooth curve's chords show as facets at twice the scale).
const THIN_PX: f64 = 0.05;

/// A polyline in pixel coordinates with the vertices dropped that lie within `tol` px of the
/// chord drawn instead, in one pass (the sleeve of Zhao and Saalfeld): from each kept vertex
/// `a`, every later vertex `p` at distance `d > tol` allows the chord's direction only within
/// `asin(tol / d)` of its own, and the chord extends to the next vertex while that vertex's
/// direction lies in all those cones (the wedge, narrowed vertex by vertex) and it is at least
/// as far from `a` as every vertex before it; otherwise the last vertex that fitted is kept and
/// becomes the anchor. Every dropped vertex then lies within `tol` of the chord's line and
/// projects inside the chord (its angle to the chord is under 90° and its distance at most the
/// end's), so within `tol` of the segment: the path between two kept vertices stays within
/// `tol` of their chord and the chord within `tol` of the path (distance to a segment is
/// convex, and the path's projection runs over the whole chord), so the drawing moves by at
/// most `tol`. After [`pixel_columns`], this drops the smooth stretches of a dense curve (most
/// of a run's speed, its stationary curves) and keeps its oscillations.
fn chord_thin(pts: &[(f64, f64)], tol: f64) -> Vec<(f64, f64)> {
    if pts.len() <= 2 {
        return pts.to_vec();
    }
    let cross = |u: (f64, f64), v: (f64, f64)| u.0 * v.1 - u.1 * v.0;
    let mut out = Vec::with_capacity(pts.len());
    out.push(pts[0]);
    let mut a = 0;
    // the wedge of allowed chord directions, from `lo` counter-clockwise to `hi` (unbounded
    // while `open`), and the farthest distance from the anchor so far
    let (mut lo, mut hi, mut open, mut far) = ((0.0, 0.0), (0.0, 0.0), true, 0.0f64);
    let mut k = 1;
    while k < pts.len() {
        let v = (pts[k].0 - pts[a].0, pts[k].1 - pts[a].1);
        // (a square root, not `hypot`'s libm call: pixel coordinates cannot overflow)
        let d = (v.0 * v.0 + v.1 * v.1).sqrt();
        if !(d >= far && (open || (cross(lo, v) >= 0.0 && cross(v, hi) >= 0.0))) {
            // the chord ends at the last vertex that fitted (k - 1 > a: the anchor's next
            // vertex always fits), which anchors the next one
            out.push(pts[k - 1]);
            (a, open, far) = (k - 1, true, 0.0);
            continue;
        }
        if d > tol {
            // narrow the wedge to this vertex's cone (its direction is inside the wedge, so the
            // cone overlaps it and each pair compared is less than 180° apart)
            let (sn, u) = (tol / d, (v.0 / d, v.1 / d));
            let cs = (1.0 - sn * sn).sqrt();
            let (l, h) = ((u.0 * cs + u.1 * sn, u.1 * cs - u.0 * sn), (u.0 * cs - u.1 * sn, u.1 * cs + u.0 * sn));
            if open {
                (lo, hi, open) = (l, h, false);
            } else {
                if cross(lo, l) > 0.0 {
                    lo = l;
                }
                if cross(h, hi) > 0.0 {
                    hi = h;
                }
            }
        }
        far = far.max(d);
        k += 1;
    }
    out.push(pts[pts.len() - 1]);
    out
}

/// The points of a line that its own figure draws (the pixel columns `Plot::svg` reduces each
/// unbroken piece to, for the points' own x-range): for building a dense series from many
/// samples (a run's 4 801) without holding every one. When the figure's x-range is the
/// points' the drawing is the same (a test compares the SVG bytes); otherwise the columns are
/// off by less than one, which moves no drawn point by more than a pixel's column. Per run of
/// points in one column: the first, the first largest and first smallest `y` and the last, in
/// their order; a non-finite point is kept as the break it is. Two passes over `points` (the
/// range, then the columns).
pub fn line_columns<I: Iterator<Item = (f64, f64)> + Clone>(points: I) -> Vec<(f64, f64)> {
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    for (x, y) in points.clone() {
        if x.is_finite() && y.is_finite() {
            x0 = x0.min(x);
            x1 = x1.max(x);
        }
    }
    if !(x1 - x0 >= 1e-12) {
        return points.collect();
    }
    // `Plot::svg`'s column of x (its `sx`, clamped, floored) with the left margin of a figure
    // without named row ticks
    let col = |x: f64| floor_i64((ML + (x - x0) / (x1 - x0) * PW).clamp(-1e4, 1e4));
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(4 * PW as usize + 64);
    // the current run: its column, and (position, point) of its first, largest, smallest, last
    type Run = (i64, [(usize, (f64, f64)); 4]);
    let flush = |run: &mut Option<Run>, out: &mut Vec<(f64, f64)>| {
        if let Some((_, [first, hi, lo, last])) = run.take() {
            // in the order of their positions, each once: the run's first is its earliest and
            // its last its latest, so only the largest and smallest are ordered
            let (a, b) = if hi.0 <= lo.0 { (hi, lo) } else { (lo, hi) };
            let mut prev = usize::MAX;
            for (k, p) in [first, a, b, last] {
                if k != prev {
                    out.push(p);
                    prev = k;
                }
            }
        }
    };
    let mut run: Option<Run> = None;
    for (k, p) in points.enumerate() {
        if !(p.0.is_finite() && p.1.is_finite()) {
            flush(&mut run, &mut out);
            out.push(p);
            continue;
        }
        let c = col(p.0);
        match &mut run {
            Some((rc, four)) if *rc == c => {
                if p.1 > four[1].1 .1 {
                    four[1] = (k, p);
                }
                if p.1 < four[2].1 .1 {
                    four[2] = (k, p);
                }
                four[3] = (k, p);
            }
            _ => {
                flush(&mut run, &mut out);
                run = Some((c, [(k, p); 4]));
            }
        }
    }
    flush(&mut run, &mut out);
    out
}

/// Split `s` into lines of at most about `max` characters at spaces.
fn wrap(s: &str, max: usize) -> Vec<String> {
    let mut lines = vec![];
    let mut cur = String::new();
    for word in s.split(' ') {
        if !cur.is_empty() && cur.chars().count() + 1 + word.chars().count() > max {
            lines.push(std::mem::take(&mut cur));
        }
        if !cur.is_empty() {
            cur.push(' ');
        }
        cur.push_str(word);
    }
    lines.push(cur);
    lines
}

fn fontdb() -> &'static std::sync::Arc<resvg::usvg::fontdb::Database> {
    static DB: std::sync::OnceLock<std::sync::Arc<resvg::usvg::fontdb::Database>> = std::sync::OnceLock::new();
    DB.get_or_init(|| {
        use resvg::usvg::fontdb::{Database, Source};
        let mut db = Database::new();
        // the fonts compiled into the binary, borrowed where they lie (no 1.4 MB copy into the
        // heap): only the pages of the tables read are touched
        db.load_font_source(Source::Binary(std::sync::Arc::new(dejavu::sans::regular())));
        db.load_font_source(Source::Binary(std::sync::Arc::new(dejavu::sans::bold())));
        db.set_sans_serif_family("DejaVu Sans");
        std::sync::Arc::new(db)
    })
}

/// Where [`Plot::svg`] places a heatmap it leaves out: the raster's rectangle and the clip
/// rectangle, each `[x, y, width, height]` in the document's units; with it, what else the
/// PNG paints itself: the colour bar (its rectangle and scale) and the axis-aligned curves
/// drawn last (clipped to the plot area where the document's curves are).
struct HeatPlacement {
    rect: [f64; 4],
    clip: [f64; 4],
    bar: Option<([f64; 4], ColorScale)>,
    lines: Vec<StraightLine>,
}

/// An axis-aligned polyline of the document left for the PNG to paint ([`paint_lines`]): its
/// points in the document's units as written (two decimals), the stroke's half-width, its
/// colour, whether it is dashed (SVG's `7 4`) and clipped to the plot area.
struct StraightLine {
    pts: Vec<(f64, f64)>,
    half: f64,
    color: [u8; 3],
    dashed: bool,
    clipped: bool,
}

impl StraightLine {
    /// A solid line of width `2 half`, not clipped.
    fn new(pts: Vec<(f64, f64)>, width: f64, color: [u8; 3]) -> Self {
        StraightLine { pts, half: width / 2.0, color, dashed: false, clipped: false }
    }

    /// The 1-unit stroke of the rectangle `[x, y, w, h]` (SVG's `<rect>`, closed: its first
    /// side drawn twice so that every corner is a join).
    fn frame([x, y, w, h]: [f64; 4], color: [u8; 3]) -> Self {
        StraightLine::new(vec![(x, y), (x + w, y), (x + w, y + h), (x, y + h), (x, y), (x + w, y)], 1.0, color)
    }
}

/// `v` as the document writes it with `{:.2}`.
fn two_decimals(v: f64) -> f64 {
    format!("{v:.2}").parse().unwrap_or(v)
}

/// Paint the colour bar into `pix` (document units times `scale`): each pixel whose centre lies
/// in the bar's rectangle takes the colour map's colour at its centre's height (−1 at the
/// bottom, 1 at the top), what the document's 64-row raster samples; resvg would resample that
/// raster bicubically over the bar's 510 × 24 pixels (a map's figure at 1.5), 7 M instructions.
#[inline(never)]
fn paint_bar(pix: &mut resvg::tiny_skia::Pixmap, bar: [f64; 4], cs: ColorScale, scale: f32) {
    let s = f64::from(scale);
    let [bx, by, bw, bh] = bar;
    let (w, h) = (pix.width() as usize, pix.height() as usize);
    // the pixels whose centres (p + 0.5) / s lie in [a, b)
    let span = |a: f64, b: f64, n: usize| {
        let lo = (a * s - 0.5).ceil().max(0.0) as usize;
        let hi = ((b * s - 0.5).ceil().max(0.0) as usize).min(n);
        lo..hi.max(lo)
    };
    let cols = span(bx, bx + bw, w);
    let px = pix.pixels_mut();
    for p in span(by, by + bh, h) {
        let t = 1.0 - 2.0 * (((p as f64 + 0.5) / s - by) / bh);
        let [r, g, b] = heat_color(bar_value(t, cs), cs);
        let c = resvg::tiny_skia::PremultipliedColorU8::from_rgba(r, g, b, 255).expect("opaque");
        px[p * w + cols.start..p * w + cols.end].fill(c);
    }
}

/// The dashes of a polyline (SVG's `stroke-dasharray="7 4"` from its start) as tiny-skia cuts
/// them (in `f32`, its arithmetic: a dash that ends a rounding error past a corner turns it
/// there too): each dash's points, the polyline's corners inside it kept.
fn dashes(pts: &[(f32, f32)]) -> Vec<Vec<(f32, f32)>> {
    // the segments of positive length: their cumulative length and first point
    let mut segs: Vec<(f32, usize)> = vec![];
    let mut length = 0f32;
    for k in 0..pts.len().saturating_sub(1) {
        let (dx, dy) = (pts[k + 1].0 - pts[k].0, pts[k + 1].1 - pts[k].1);
        let prev = length;
        length += (dx * dx + dy * dy).sqrt();
        if length > prev {
            segs.push((length, k));
        }
    }
    if segs.is_empty() {
        return vec![];
    }
    // the segment a distance lies on (the first that reaches it) and the fraction along it
    let at = |d: f32| {
        let i = segs.partition_point(|s| s.0 < d).min(segs.len() - 1);
        let start = if i > 0 { segs[i - 1].0 } else { 0.0 };
        (i, (d - start) / (segs[i].0 - start))
    };
    let point = |i: usize, t: f32| {
        let k = segs[i].1;
        match t {
            1.0 => pts[k + 1],
            _ => (pts[k].0 + (pts[k + 1].0 - pts[k].0) * t, pts[k].1 + (pts[k + 1].1 - pts[k].1) * t),
        }
    };
    let mut out = vec![];
    let (mut distance, mut on, mut len) = (0f32, true, 7f32);
    while distance < length {
        if on {
            let (start, stop) = (distance, (distance + len).min(length));
            let ((i, t0), (j, t1)) = (at(start), at(stop));
            if (0.0..=1.0).contains(&t0) && (0.0..=1.0).contains(&t1) {
                let mut piece = vec![point(i, t0)];
                if i == j {
                    piece.push(if t1 == t0 { piece[0] } else { point(i, t1) });
                } else {
                    // to the end of the first segment, through the whole ones, into the last
                    piece.extend((i..j).map(|m| pts[segs[m].1 + 1]));
                    piece.push(if t1 == 0.0 { *piece.last().expect("a point") } else { point(j, t1) });
                }
                out.push(piece);
            }
        }
        distance += len;
        on = !on;
        len = if on { 7.0 } else { 4.0 };
    }
    out
}

/// Paint axis-aligned polylines into `pix` (document units times `scale`) as tiny-skia strokes
/// them (butt caps, miter joins: at a right angle the cell's square corner), without its
/// general path machinery: a polyline's stroke is then a union of rectangles, each segment
/// widened by the half-width and lengthened by it at a right-angle join. Each polyline (all
/// its dashes) is one coverage, as tiny-skia's supersampled scan of one path: four sub-rows a
/// pixel, the rectangles' edges at quarter pixels (rounded), each sub-row's intervals merged,
/// a quarter pixel's coverage 16 of 255 (a full pixel 64, 63 on the last sub-row), then the
/// colour blended over by that coverage (`(d (255 − a) + c a + 255) >> 8`). The lines marked
/// `clipped` are clipped to `clip` (`[x, y, w, h]`).
#[inline(never)]
fn paint_lines(pix: &mut resvg::tiny_skia::Pixmap, lines: &[StraightLine], clip: [f64; 4], scale: f32) {
    let (w, h) = (pix.width() as i64, pix.height() as i64);
    // an edge at `v` (document units, f32) in quarter pixels, as tiny-skia places it: the
    // point scaled in f32, truncated to 1/256 of a pixel, rounded to a quarter
    let q = |v: f32| ((((v * scale) * 256.0) as i32 + 32) >> 6) as i64;
    // the area painted, in quarter pixels: the pixmap, and the clip for a clipped line
    let all = (0, 4 * w, 0, 4 * h);
    let [cx, cy, cw, ch] = clip;
    let within = (q(cx as f32).max(0), q((cx + cw) as f32).min(4 * w), q(cy as f32).max(0), q((cy + ch) as f32).min(4 * h));
    // the stroker leaves out a segment shorter than this (document units) with butt caps
    let teeny = 1.0 / 4096.0 / scale;
    // the pixmap's bytes: opaque (its figure is), premultiplied RGBA, so the colour is its RGB
    let px = pix.data_mut();
    let mut touched: Vec<(usize, usize)> = vec![];
    // per polyline: its rectangles [x0, x1) x [y0, y1) in quarter pixels, then (sub-row, x0, x1)
    let mut rects: Vec<[i64; 4]> = vec![];
    let mut spans: Vec<(i64, i64, i64)> = vec![];
    let mut starts: Vec<usize> = vec![];
    let mut acc: Vec<u16> = vec![0; w as usize];
    for line in lines {
        rects.clear();
        let (x0, x1, y0, y1) = if line.clipped { within } else { all };
        let pts: Vec<(f32, f32)> = line.pts.iter().map(|&(x, y)| (x as f32, y as f32)).collect();
        let half = line.half as f32;
        let pieces = if line.dashed { dashes(&pts) } else { vec![pts] };
        for piece in &pieces {
            // the piece without its teeny segments
            let mut p: Vec<(f32, f32)> = Vec::with_capacity(piece.len());
            for &v in piece {
                if p.last().is_none_or(|l: &(f32, f32)| (l.0 - v.0).abs() > teeny || (l.1 - v.1).abs() > teeny) {
                    p.push(v);
                }
            }
            let horizontal = |k: usize| p[k].1 == p[k + 1].1;
            let mut push = |r: [i64; 4]| {
                let r = [r[0].max(x0), r[1].min(x1), r[2].max(y0), r[3].min(y1)];
                if r[0] < r[1] && r[2] < r[3] {
                    rects.push(r);
                }
            };
            for k in 0..p.len().saturating_sub(1) {
                let (a, b) = (p[k], p[k + 1]);
                // the segment widened by the half-width
                push(match horizontal(k) {
                    true => [q(a.0.min(b.0)), q(a.0.max(b.0)), q(a.1 - half), q(a.1 + half)],
                    false => [q(a.0 - half), q(a.0 + half), q(a.1.min(b.1)), q(a.1.max(b.1))],
                });
                // a right-angle miter join at `b`: the outer square, from `b` on along this
                // segment and back against the next one (a turn back or a straight
                // continuation adds nothing)
                if k + 2 < p.len() && horizontal(k + 1) != horizontal(k) {
                    let c = p[k + 2];
                    let (sx, sy) = match horizontal(k) {
                        true => ((b.0 - a.0).signum(), -(c.1 - b.1).signum()),
                        false => (-(c.0 - b.0).signum(), (b.1 - a.1).signum()),
                    };
                    let (xa, xb) = (b.0, b.0 + sx * half);
                    let (ya, yb) = (b.1, b.1 + sy * half);
                    push([q(xa.min(xb)), q(xa.max(xb)), q(ya.min(yb)), q(ya.max(yb))]);
                }
            }
        }
        if rects.is_empty() {
            continue;
        }
        // the rectangles' intervals by sub-row (a counting sort), each sub-row's by their start
        let (top, bottom) = rects.iter().fold((i64::MAX, i64::MIN), |(t, b), r| (t.min(r[2]), b.max(r[3])));
        starts.clear();
        starts.resize((bottom - top + 1) as usize, 0);
        for r in &rects {
            for y in r[2]..r[3] {
                starts[(y - top + 1) as usize] += 1;
            }
        }
        for k in 1..starts.len() {
            starts[k] += starts[k - 1];
        }
        spans.clear();
        spans.resize(starts[starts.len() - 1], (0, 0, 0));
        for r in &rects {
            for y in r[2]..r[3] {
                let at = &mut starts[(y - top) as usize];
                spans[*at] = (y, r[0], r[1]);
                *at += 1;
            }
        }
        let mut k = 0;
        while k < spans.len() {
            let y = spans[k].0;
            let e = k + spans[k..].iter().take_while(|v| v.0 == y).count();
            spans[k..e].sort_unstable_by_key(|v| v.1);
            k = e;
        }
        let [c0, c1, c2] = line.color.map(u32::from);
        let mut k = 0;
        while k < spans.len() {
            // one pixel row: its four sub-rows' merged intervals accumulated into `acc`
            let row = spans[k].0 >> 2;
            touched.clear();
            while k < spans.len() && spans[k].0 >> 2 == row {
                let y = spans[k].0;
                let full = 64 - (((y & 3) + 1) >> 2) as u16;
                let (mut a, mut b) = (spans[k].1, spans[k].2);
                k += 1;
                loop {
                    // merge the intervals that overlap or touch this one
                    while k < spans.len() && spans[k].0 == y && spans[k].1 <= b {
                        b = b.max(spans[k].2);
                        k += 1;
                    }
                    let add = |acc: &mut [u16], i: i64, v: u16| {
                        let t = acc[i as usize] + v;
                        acc[i as usize] = t - (t >> 8);
                    };
                    let (fb, fe, mut n) = (a & 3, b & 3, (b >> 2) - (a >> 2) - 1);
                    let mut x = a >> 2;
                    if n < 0 {
                        add(&mut acc, x, ((fe - fb) * 16) as u16);
                    } else {
                        if fb == 0 {
                            n += 1;
                        } else {
                            add(&mut acc, x, ((4 - fb) * 16) as u16);
                            x += 1;
                        }
                        for i in x..x + n {
                            add(&mut acc, i, full);
                        }
                        if fe != 0 {
                            add(&mut acc, x + n, (fe * 16) as u16);
                        }
                    }
                    touched.push(((a >> 2) as usize, ((b + 3) >> 2) as usize));
                    if k < spans.len() && spans[k].0 == y {
                        (a, b) = (spans[k].1, spans[k].2);
                        k += 1;
                    } else {
                        break;
                    }
                }
            }
            // the pixels covered, each blended once (its coverage then cleared)
            let base = (row * w) as usize;
            for &(lo, hi) in &touched {
                let out = &mut px[4 * (base + lo)..4 * (base + hi)];
                for (o, c) in out.chunks_exact_mut(4).zip(&mut acc[lo..hi]) {
                    match u32::from(std::mem::take(c)) {
                        0 => {}
                        255 => o[..3].copy_from_slice(&line.color),
                        a => {
                            let blend = |d: u8, c: u32| ((u32::from(d) * (255 - a) + c * a + 255) >> 8) as u8;
                            (o[0], o[1], o[2]) = (blend(o[0], c0), blend(o[1], c1), blend(o[2], c2));
                        }
                    }
                }
            }
        }
    }
}

/// Paint the heatmap's cells into `pix` (document units times `scale`): each pixel whose centre
/// lies in the raster's rectangle and the clip takes the colour of the cell under its centre
/// (row 0 of the raster at the top is the last `y`). One colour per cell, computed once.
#[inline(never)]
fn paint_heatmap(pix: &mut resvg::tiny_skia::Pixmap, h: &Heatmap, at: &HeatPlacement, scale: f32, colours: Option<&[[u8; 3]]>) {
    let (nx, ny) = (h.x.len(), h.y.len());
    let s = f64::from(scale);
    let [rx, ry, rw, rh] = at.rect;
    let [cx, cy, cw, ch] = at.clip;
    let (w, hgt) = (pix.width() as usize, pix.height() as usize);
    // the pixels whose centres (p + 0.5) / s lie in [max(r0, c0), min(r1, c1))
    let span = |r0: f64, r1: f64, c0: f64, c1: f64, n: usize| {
        let (a, b) = (r0.max(c0) * s - 0.5, r1.min(c1) * s - 0.5);
        let lo = a.ceil().max(0.0) as usize;
        let hi = if b.ceil() > 0.0 { (b.ceil() as usize).min(n) } else { 0 };
        lo..hi.max(lo)
    };
    let cols = span(rx, rx + rw, cx, cx + cw, w);
    let rows = span(ry, ry + rh, cy, cy + ch, hgt);
    // the cell of each pixel column
    let cell_of = |p: usize, r0: f64, len: f64, n: usize| ((((p as f64 + 0.5) / s - r0) / len * n as f64).floor().max(0.0) as usize).min(n - 1);
    let col_cell: Vec<usize> = cols.clone().map(|p| cell_of(p, rx, rw, nx)).collect();
    // the colours of one row of cells at a time, computed when its first pixel row is painted
    // (the pixel rows go down the figure, the cell rows up: each row once, consecutively)
    let mut line = vec![resvg::tiny_skia::PremultipliedColorU8::TRANSPARENT; nx];
    let mut line_of = usize::MAX;
    // the last value's colour (a verdict map's cells take two values; a margin map's rarely
    // repeat)
    let verdict = matches!(h.scale, ColorScale::Verdict);
    let mut last: Option<(u64, resvg::tiny_skia::PremultipliedColorU8)> = None;
    let px = pix.pixels_mut();
    for p in rows {
        let j = ny - 1 - cell_of(p, ry, rh, ny);
        if j == line_of {
            // the same row of cells as the pixel row above: its pixels copied
            px.copy_within((p - 1) * w + cols.start..(p - 1) * w + cols.end, p * w + cols.start);
            continue;
        }
        if let Some(cs) = colours.filter(|cs| cs.len() == nx * ny) {
            // the raster's order: `z[j]` is row `ny - 1 - j`
            let row = ny - 1 - j;
            for (c, &[r, g, b]) in line.iter_mut().zip(&cs[row * nx..(row + 1) * nx]) {
                *c = resvg::tiny_skia::PremultipliedColorU8::from_rgba(r, g, b, 255).expect("opaque");
            }
        } else {
            for (c, &v) in line.iter_mut().zip(&h.z[j]) {
                *c = match last {
                    Some((bits, c)) if verdict && bits == v.to_bits() => c,
                    _ => {
                        let [r, g, b] = heat_color(v, h.scale);
                        let c = resvg::tiny_skia::PremultipliedColorU8::from_rgba(r, g, b, 255).expect("opaque");
                        last = Some((v.to_bits(), c));
                        c
                    }
                };
            }
        }
        line_of = j;
        let out = &mut px[p * w + cols.start..p * w + cols.end];
        for (o, &i) in out.iter_mut().zip(&col_cell) {
            *o = line[i];
        }
    }
}

/// What the PNG paints before the document's render: the heatmap, the colour bar.
fn paint_under(pix: &mut resvg::tiny_skia::Pixmap, h: &Heatmap, at: &HeatPlacement, scale: f32, colours: Option<&[[u8; 3]]>) {
    paint_heatmap(pix, h, at, scale, colours);
    if let Some((bar, cs)) = at.bar {
        paint_bar(pix, bar, cs, scale);
    }
}

/// What the PNG paints after the document's render: the axis-aligned curves left out of it.
fn paint_over(pix: &mut resvg::tiny_skia::Pixmap, at: &HeatPlacement, scale: f32) {
    paint_lines(pix, &at.lines, at.clip, scale);
}

/// Rasterise an SVG document to PNG bytes at `scale`.
pub fn svg_to_png(svg: &str, scale: f32) -> anyhow::Result<Vec<u8>> {
    rasterise(svg, scale, false, |_| {}, |_| {})
}

/// Rasterise `svg` at `scale` over what `under` paints first into the pixels (white where
/// `white`, else transparent), then let `over` paint over the result. The pixels are touched
/// once before the render: a white pixmap is allocated as white bytes (premultiplied opaque
/// white is all 255), not zeroed and then filled.
fn rasterise(
    svg: &str,
    scale: f32,
    white: bool,
    under: impl FnOnce(&mut resvg::tiny_skia::Pixmap),
    over: impl FnOnce(&mut resvg::tiny_skia::Pixmap),
) -> anyhow::Result<Vec<u8>> {
    use resvg::{tiny_skia, usvg};
    let opt = usvg::Options { fontdb: fontdb().clone(), font_family: "DejaVu Sans".into(), ..Default::default() };
    let tree = usvg::Tree::from_str(svg, &opt).map_err(|e| anyhow::anyhow!("SVG not readable: {e}"))?;
    let size = tree.size().to_int_size().scale_by(scale).ok_or_else(|| anyhow::anyhow!("empty figure"))?;
    let too_large = || anyhow::anyhow!("figure too large");
    let mut pix = match white {
        true => {
            let bytes = (size.width() as usize).checked_mul(size.height() as usize).and_then(|n| n.checked_mul(4)).ok_or_else(too_large)?;
            tiny_skia::Pixmap::from_vec(vec![255u8; bytes], size).ok_or_else(too_large)?
        }
        false => tiny_skia::Pixmap::new(size.width(), size.height()).ok_or_else(too_large)?,
    };
    under(&mut pix);
    resvg::render(&tree, tiny_skia::Transform::from_scale(scale, scale), &mut pix.as_mut());
    over(&mut pix);
    // the figures are opaque (white background): RGB, with the png crate's fast deflate, a
    // third of the instructions of tiny-skia's RGBA `encode_png` at its default level
    if !opaque(pix.data()) {
        return pix.encode_png().map_err(|e| anyhow::anyhow!("PNG encoding: {e}"));
    }
    let (w, h) = (pix.width(), pix.height());
    // opaque: premultiplied is straight; the RGB bytes are packed into the pixmap's own front
    // (no 2.9 MB copy for a map's figure)
    let mut data = pix.take();
    let n = rgba_to_rgb_in_place(&mut data);
    // the PNG is written into the quarter the RGB bytes freed (pages the pixmap touched; a
    // map's PNG is 4-11 % of its RGB bytes, 118-315 kB of 2.9 MB), then moved to the front and
    // the pixmap's buffer returned as the file: no fresh pages for it. A PNG that does not fit
    // (an image deflate hardly shrinks) is encoded again into a buffer of its own.
    let (rgb, tail) = data.split_at_mut(n);
    let room = tail.len();
    let mut free: &mut [u8] = tail;
    if encode_rgb(&mut free, w, h, rgb).is_ok() {
        let written = room - free.len();
        data.copy_within(n..n + written, 0);
        data.truncate(written);
        return Ok(data);
    }
    let mut out = Vec::with_capacity(n / 8 + 4096);
    encode_rgb(&mut out, w, h, &data[..n]).map_err(|e| anyhow::anyhow!("PNG encoding: {e}"))?;
    Ok(out)
}

/// RGB bytes (`w` x `h`) as a PNG written to `out`: the png crate's fast deflate, filter Sub.
fn encode_rgb(out: &mut impl std::io::Write, w: u32, h: u32, rgb: &[u8]) -> Result<(), png::EncodingError> {
    let mut enc = png::Encoder::new(out, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Fast);
    let mut wr = enc.write_header()?;
    wr.write_image_data(rgb)?;
    wr.finish()
}

/// Whether every pixel of RGBA bytes is opaque: the AND of all alphas is 255 only if each is
/// (the AND taken over 8-byte words, two pixels each, then their alpha bytes checked).
#[inline(never)]
fn opaque(rgba: &[u8]) -> bool {
    let words = rgba.chunks_exact(8);
    let tail = words.remainder().chunks_exact(4).fold(255u8, |a, p| a & p[3]);
    let all = words.fold(u64::MAX, |a, w| a & u64::from_le_bytes(w.try_into().expect("8 bytes")));
    const ALPHAS: u64 = 0xFF00_0000_FF00_0000;
    all & ALPHAS == ALPHAS && tail == 255
}

/// RGBA bytes to RGB in place: pixel `i`'s first three bytes move from `4i` to `3i`; returns
/// the RGB length (`3/4` of the bytes). Eight pixels at a time through a local copy: block `k`
/// reads bytes `32k..32k+32` before it writes `24k..24k+24`, which end before block `k + 1`'s
/// reads begin, so no byte is overwritten before it is read.
fn rgba_to_rgb_in_place(d: &mut [u8]) -> usize {
    let n = d.len() / 4;
    let mut i = 0;
    while i + 8 <= n {
        let mut b = [0u8; 32];
        b.copy_from_slice(&d[4 * i..4 * i + 32]);
        let o = &mut d[3 * i..3 * i + 24];
        for k in 0..8 {
            o[3 * k..3 * k + 3].copy_from_slice(&b[4 * k..4 * k + 3]);
        }
        i += 8;
    }
    while i < n {
        d.copy_within(4 * i..4 * i + 3, 3 * i);
        i += 1;
    }
    3 * n
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::SQRT_2;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        for (i, o) in [("", ""), ("f", "Zg=="), ("fo", "Zm8="), ("foo", "Zm9v"), ("foob", "Zm9vYg=="), ("fooba", "Zm9vYmE="), ("foobar", "Zm9vYmFy")] {
            assert_eq!(base64(i.as_bytes()), o);
        }
        // many whole groups and every byte value, against Python's `base64.b64encode(bytes(range(256)) * 2)`
        // (its first and last 40 characters) and the length 4 * ceil(512 / 3)
        let all: Vec<u8> = (0..512).map(|k| (k % 256) as u8).collect();
        let e = base64(&all);
        assert_eq!(e.len(), 684);
        assert_eq!(&e[..40], "AAECAwQFBgcICQoLDA0ODxAREhMUFRYXGBkaGxwd");
        assert_eq!(&e[e.len() - 40..], "4+Tl5ufo6err7O3u7/Dx8vP09fb3+Pn6+/z9/v8=");
    }

    #[test]
    fn ticks_are_round_and_cover_the_range() {
        let t = ticks(0.0, 3.7, 8);
        assert_eq!(t.first(), Some(&0.0));
        assert!(t.windows(2).all(|w| ((w[1] - w[0]) - 0.5).abs() < 1e-12));
        assert!(*t.last().unwrap() <= 3.7);
    }

    /// The integer rounding and floor of the pixel writer are the C library's, value for value:
    /// on random values, every exact half (where `round` goes away from zero), the neighbours of
    /// integers and halves, and ±0.
    #[test]
    fn integer_round_and_floor_match_the_library() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut vals = vec![0.0, -0.0, 0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 1e6 + 0.5, -1e6 - 0.5, 0.49999999999999994, -0.49999999999999994];
        for k in -3000..3000 {
            let h = k as f64 * 0.5;
            vals.extend([h, h.next_up(), h.next_down()]);
        }
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            vals.push(((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2e6);
        }
        for v in vals {
            assert_eq!(round_i64(v), v.round() as i64, "round {v}");
            assert_eq!(floor_i64(v), v.floor() as i64, "floor {v}");
        }
    }

    #[test]
    fn pixel_coordinates_print_as_two_decimals() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = ((x >> 11) as f64 / (1u64 << 53) as f64 - 0.3) * 3000.0;
            let (mut s, want) = (String::new(), format!("{v:.2}"));
            push_px(&mut s, v);
            // the two roundings differ only on a hundredth's exact half, where either is right
            let close = (s.parse::<f64>().unwrap() - v).abs() <= 0.005 + 1e-9;
            assert!(s == want || (close && (want.parse::<f64>().unwrap() - v).abs() >= 0.005 - 1e-9), "{v}: {s} vs {want}");
        }
        for (v, want) in [(0.0, "0.00"), (1.0, "1.00"), (-1.5, "-1.50"), (614.004, "614.00"), (0.999, "1.00"), (-10000.0, "-10000.00")] {
            let mut s = String::new();
            push_px(&mut s, v);
            assert_eq!(s, want);
        }
    }

    #[test]
    fn pixel_columns_keep_every_column_extent_and_both_ends() {
        // a 4 801-sample resonance-like curve with a sharp peak over 540 px, plus noise
        let n = 4801;
        let pts: Vec<(f64, f64)> = (0..n)
            .map(|k| {
                let x = 74.0 + 540.0 * k as f64 / (n - 1) as f64;
                let y = 300.0 - 250.0 / (1.0 + ((k as f64 - 2000.0) / 15.0).powi(2)) + 3.0 * ((k * 7919 % 13) as f64 / 13.0);
                (x, y)
            })
            .collect();
        let r = pixel_columns(&pts);
        assert!(r.len() <= 4 * 541 && r.len() < n / 2, "{} points kept", r.len());
        assert_eq!(r.first(), pts.first());
        assert_eq!(r.last(), pts.last());
        // per column: the same lowest and highest y (the peak, k = 2000, is kept exactly)
        let ext = |p: &[(f64, f64)]| {
            let mut m = std::collections::BTreeMap::new();
            for &(x, y) in p {
                let e = m.entry(x.floor() as i64).or_insert((f64::INFINITY, f64::NEG_INFINITY));
                *e = (e.0.min(y), e.1.max(y));
            }
            m
        };
        assert_eq!(ext(&r), ext(&pts));
        assert!(r.contains(&pts[2000]), "the peak sample is kept");
        // kept points are a subsequence of the curve, in order
        let mut it = pts.iter();
        assert!(r.iter().all(|p| it.any(|q| q == p)));
        // a curve going back and forth keeps its turning points
        let zig = [(10.2, 1.0), (10.8, 5.0), (10.1, 2.0), (12.5, 0.0), (10.3, 9.0)];
        assert_eq!(pixel_columns(&zig), zig.to_vec());
    }

    /// A figure of lines built from `line_columns` is the figure of the whole lines, byte for
    /// byte, where the figure's x-range is theirs: a 4 801-point peak with noise (ties in y
    /// included), a zigzag, a curve going back in x, and one broken by NaN.
    #[test]
    fn a_line_built_from_its_columns_draws_the_same_figure() {
        let n = 4801;
        let t = |k: usize| 300.0 * k as f64 / (n - 1) as f64;
        let lines: Vec<Vec<(f64, f64)>> = vec![
            (0..n).map(|k| (t(k), 2.0 / (1.0 + ((t(k) - 120.0) / 6.0).powi(2)) + 0.05 * ((k * 7919 % 13) as f64 / 13.0).round())).collect(),
            (0..n).map(|k| (t(k), if k % 2 == 0 { 1.0 } else { -1.0 } * (t(k) / 50.0).sin())).collect(),
            (0..n).map(|k| (t(k) + 20.0 * (t(k) / 9.0).sin(), (t(k) / 30.0).cos())).collect(),
            (0..n).map(|k| (t(k), if k % 700 == 350 { f64::NAN } else { (t(k) * 3.0) % 180.0 - 90.0 })).collect(),
        ];
        for (i, line) in lines.iter().enumerate() {
            let whole = Plot { title: format!("line {i}"), series: vec![Series::new("a", line.clone(), "#000")], ..Default::default() };
            let thin = Plot { series: vec![Series::new("a", line_columns(line.iter().copied()), "#000")], ..whole.clone() };
            assert!(thin.series[0].points.len() * 2 < line.len(), "line {i}: {} points kept", thin.series[0].points.len());
            assert_eq!(thin.ranges(), whole.ranges(), "line {i}");
            assert!(thin.to_svg() == whole.to_svg(), "line {i}: the figures differ");
        }
    }

    /// A dense curve (more than `THIN_ABOVE` column points) is stroked with round joins unless
    /// its written points (two decimals) turn only at right angles: a 200-step staircase (400
    /// points, each step in its own pixel column) keeps SVG's miter joins, a 400-point sine
    /// and the same staircase with one step's riser tilted by 0.1 px get round ones. (The
    /// written points are checked as written: a tilt below the 0.005 px rounding would not
    /// count.)
    #[test]
    fn dense_curves_get_round_joins_unless_axis_aligned() {
        let figure = |points: Vec<(f64, f64)>| Plot { series: vec![Series::new("a", points, "#000")], ..Default::default() }.to_svg();
        let stairs: Vec<(f64, f64)> = (0..200).flat_map(|k| [(k as f64, k as f64), (k as f64 + 1.0, k as f64)]).collect();
        let svg = figure(stairs.clone());
        assert!(svg.contains("<polyline") && !svg.contains("linejoin"), "the staircase");
        let mut tilted = stairs;
        tilted[201].0 += 0.1 * 200.0 / PW;
        assert!(figure(tilted).contains(r#"stroke-linejoin="round""#), "the tilted staircase");
        let sine: Vec<(f64, f64)> = (0..400).map(|k| (k as f64, (k as f64 / 20.0).sin())).collect();
        assert!(figure(sine).contains(r#"stroke-linejoin="round""#), "the sine");
    }

    /// Every vertex `chord_thin` drops lies within the tolerance of the chord (the segment)
    /// between the kept vertices around it, the kept ones are a subsequence with both ends, and
    /// a straight run keeps only its ends: random walks (smooth, jagged, turning back), at
    /// tolerances 0.01-1 px, checked against the distance to the segment computed apart.
    #[test]
    fn chord_thinning_keeps_every_vertex_within_the_tolerance_of_its_chord() {
        let seg_dist = |a: (f64, f64), b: (f64, f64), p: (f64, f64)| {
            let (dx, dy, px, py) = (b.0 - a.0, b.1 - a.1, p.0 - a.0, p.1 - a.1);
            let len2 = dx * dx + dy * dy;
            let u = if len2 > 0.0 { ((px * dx + py * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
            (px - u * dx).hypot(py - u * dy)
        };
        let mut x = 0x2545_F491_4F6C_DD1Du64;
        let mut rnd = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut dropped = 0;
        for case in 0..300 {
            let tol = [0.01, 0.05, 0.25, 1.0][case % 4];
            let (mut p, mut dir) = ((100.0, 100.0), 0.0f64);
            let pts: Vec<(f64, f64)> = (0..400)
                .map(|_| {
                    dir += [0.05, 0.5, 3.0][case % 3] * rnd();
                    let step = 0.05 + 2.0 * (rnd() + 0.5);
                    p = (p.0 + step * dir.cos(), p.1 + step * dir.sin());
                    p
                })
                .collect();
            let kept = chord_thin(&pts, tol);
            assert_eq!((kept.first(), kept.last()), (pts.first(), pts.last()));
            // indices of the kept vertices in `pts`, in order
            let mut at = vec![];
            let mut j = 0;
            for q in &kept {
                while pts[j] != *q {
                    j += 1;
                }
                at.push(j);
                j += 1;
            }
            for w in at.windows(2) {
                for k in w[0] + 1..w[1] {
                    let e = seg_dist(pts[w[0]], pts[w[1]], pts[k]);
                    assert!(e <= tol * (1.0 + 1e-9), "case {case}: vertex {k} is {e} px from its chord (tolerance {tol})");
                    dropped += 1;
                }
            }
        }
        assert!(dropped > 10_000, "{dropped} vertices dropped in all");
        let line: Vec<(f64, f64)> = (0..50).map(|k| (k as f64, 0.5 * k as f64)).collect();
        assert_eq!(chord_thin(&line, 0.05), vec![line[0], line[49]]);
    }

    /// Dense curves drawn thinned ([`chord_thin`] after [`pixel_columns`]) against the same
    /// curves drawn with every column point, both rasterised by resvg (at 1 and 2 device pixels
    /// a px): a passage-like figure of 4 801 samples a curve (a resonance peak, a beating
    /// oscillation a few samples a period, a noisy band like the ball angles', a straight run-up,
    /// a curve broken by NaN). The drawn path moves by at most `THIN_PX` (round joins: the
    /// stroke is the path widened by a disk, so its outline moves by as much), so the reference
    /// for the change is the whole drawing moved by `THIN_PX`: thinning must change no more
    /// pixels, by no more on average, than that move (it moves only some of the outline), and
    /// its worst pixel at most 1.5 times the move's (tiny-skia's anti-aliasing counts coverage
    /// in sub-scanlines, so a sub-pixel move can flip a pixel by a quarter, 64 levels, wherever
    /// the outline is tessellated differently, as at a dropped vertex's round join). Absolutely:
    /// the changed pixels lie next to the curves' ink, are under 1 % of the figure, and change
    /// it by under a tenth of a level on average (with a tolerance of 1 px the mean is 1.07
    /// levels). The thinned text is less than half as long.
    #[test]
    fn thinned_curves_draw_the_same_figure() {
        let n = 4801;
        let t = |k: usize| 300.0 * k as f64 / (n - 1) as f64;
        let curve = |f: &dyn Fn(usize) -> f64| (0..n).map(|k| (t(k), f(k))).collect::<Vec<_>>();
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut noise = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let band: Vec<f64> = (0..n).map(|_| noise()).collect();
        let plots = [
            Plot {
                title: "peak and beat".into(),
                series: vec![
                    Series::new("peak", curve(&|k| 2.0 / (1.0 + ((t(k) - 120.0) / 6.0).powi(2))), "#0072B2"),
                    Series::new("beat", curve(&|k| 1.0 + 0.4 * (t(k) * 2.3).sin() * (t(k) / 40.0).cos()), "#D55E00"),
                    Series::new("run-up", curve(&|k| 0.01 * t(k)), "#009E73").dashed(),
                ],
                ..Default::default()
            },
            Plot {
                title: "band and breaks".into(),
                series: vec![
                    Series::new("band", curve(&|k| 90.0 * (t(k) / 70.0).sin() + 25.0 * band[k] * (-(t(k) - 150.0).powi(2) / 900.0).exp()), "#CC79A7"),
                    Series::new("broken", curve(&|k| if k % 1000 == 999 { f64::NAN } else { (3.0 * t(k)) % 180.0 - 90.0 }), "#E69F00"),
                ],
                ..Default::default()
            },
        ];
        for p in &plots {
            // the reference's own change: every curve moved by THIN_PX (diagonally), the axes kept
            let ((x0, x1), (y0, y1)) = p.ranges();
            let (dx, dy) = (THIN_PX / SQRT_2 * (x1 - x0) / PW, THIN_PX / SQRT_2 * (y1 - y0) / PH);
            let fixed = Plot { x_range: Some((x0, x1)), y_range: Some((y0, y1)), ..p.clone() };
            let mut moved = fixed.clone();
            for se in &mut moved.series {
                se.points.iter_mut().for_each(|q| *q = (q.0 + dx, q.1 + dy));
            }
            let (thin, full, moved) = (fixed.svg_with(true, true, None).0, fixed.svg_with(true, false, None).0, moved.svg_with(true, false, None).0);
            assert!(thin.len() * 2 < full.len(), "{}: {} bytes thinned, {} whole", p.title, thin.len(), full.len());
            for scale in [1.0, 2.0] {
                let (w, h, want) = decode_rgb(&svg_to_png(&full, scale).unwrap());
                let ink = |i: usize, j: usize| want[3 * (j * w + i)..][..3].iter().any(|&v| v < 250);
                // (worst channel change, pixels changed, mean change a channel) against `want`
                let change = |svg: &str| {
                    let (_, _, got) = decode_rgb(&svg_to_png(svg, scale).unwrap());
                    let d: Vec<u8> = got.iter().zip(&want).map(|(u, v)| u.abs_diff(*v)).collect();
                    for (k, _) in d.chunks(3).enumerate().filter(|(_, c)| c.iter().any(|&v| v > 0)) {
                        // no mark of its own: ink of the reference within a pixel
                        let (i, j) = (k % w, k / w);
                        let near = (j.saturating_sub(1)..(j + 2).min(h)).any(|jj| (i.saturating_sub(1)..(i + 2).min(w)).any(|ii| ink(ii, jj)));
                        assert!(near, "{} x{scale}: pixel ({i}, {j}) changed away from the curves", p.title);
                    }
                    let changed = d.chunks(3).filter(|c| c.iter().any(|&v| v > 0)).count();
                    (d.iter().copied().max().unwrap(), changed, d.iter().map(|&v| f64::from(v)).sum::<f64>() / d.len() as f64)
                };
                let (t, m) = (change(&thin), change(&moved));
                assert!(t.0 <= m.0 + m.0 / 2 && t.1 <= m.1 && t.2 <= m.2, "{} x{scale}: thinning changed {t:?}, moving by THIN_PX {m:?}", p.title);
                assert!(t.1 * 100 < w * h && t.2 < 0.1, "{} x{scale}: thinning changed {t:?} of {} pixels", p.title, w * h);
            }
        }
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
        let js = p.to_plotly();
        assert_eq!(js["data"][0]["y"][2], Value::Null, "NaN is a gap");
        assert_eq!(p.point_count(), 4);
    }

    /// Every Plotly trace has a name and a finite point (audit 21: a simulate figure carried
    /// a curve of 601 nulls, and every figure with a second speed axis an unnamed trace of
    /// two): a curve of gaps only is left out; the second axis's trace, there only to show
    /// the axis, is named after it and runs along the plot's bottom; a series without points
    /// (a legend key, as the Campbell diagram's log-decrement classes) is kept.
    #[test]
    fn every_plotly_trace_is_named_and_has_a_finite_point() {
        let nan = f64::NAN;
        let p = Plot {
            series: vec![
                Series::new("drawn", vec![(0.0, 1.0), (1.0, 2.0)], "#000"),
                Series::new("gaps only", vec![(0.0, nan), (1.0, nan), (nan, 3.0)], "#111"),
                Series::new("key", vec![], "#222"),
            ],
            x2: Some(SecondAxis { factor: 30.0 / std::f64::consts::PI, label: "ω (rpm)".into() }),
            ..Default::default()
        };
        let js = p.to_plotly();
        let data = js["data"].as_array().unwrap();
        let names: Vec<&str> = data.iter().map(|t| t["name"].as_str().unwrap_or("")).collect();
        assert_eq!(names, ["drawn", "key", "ω (rpm)"], "{js}");
        let finite = |t: &Value| {
            let (x, y) = (t["x"].as_array().unwrap(), t["y"].as_array().unwrap());
            x.iter().zip(y).filter(|(a, b)| a.as_f64().is_some_and(f64::is_finite) && b.as_f64().is_some_and(f64::is_finite)).count()
        };
        let axis = &data[2];
        assert_eq!((axis["xaxis"].as_str(), finite(axis), axis["opacity"].as_f64()), (Some("x2"), 2, Some(0.0)), "{axis}");
        // along the bottom of the y range: no change of the drawn area
        assert_eq!(axis["y"][0], js["layout"]["yaxis"]["range"][0], "{js}");
        // the legend holds the drawn curve and the key, not the curve of gaps
        assert!(!js.to_string().contains("gaps only"), "{js}");
    }

    #[test]
    fn legend_is_wide_enough_for_its_longest_label() {
        let long = "a label much longer than the old fixed legend column could hold";
        let p = Plot { series: vec![Series::new(long, vec![(0.0, 0.0), (1.0, 1.0)], "#000")], ..Default::default() };
        let svg = p.to_svg();
        let w: f64 = svg.split("width=\"").nth(1).unwrap().split('"').next().unwrap().parse().unwrap();
        assert!(w >= ML + PW + text_width(long) + 38.0, "width {w}");
    }

    #[test]
    fn close_labels_step_down_and_far_ones_share_a_row() {
        assert_eq!(stagger(&[0.0, 0.01, 0.5, 0.505], 0.05), vec![0, 1, 0, 1]);
    }

    #[test]
    fn grouped_branches_have_one_legend_entry() {
        let p = Plot {
            series: vec![Series::new("branch", vec![(0.0, 1.0)], "#000").group("g"), Series::new("", vec![(0.0, 2.0)], "#000").group("g")],
            ..Default::default()
        };
        let js = p.to_plotly();
        assert_eq!(js["data"][0]["showlegend"], true);
        assert_eq!(js["data"][1]["showlegend"], false);
        assert_eq!(js["data"][1]["name"], "branch");
    }

    #[test]
    fn diverging_scale_is_white_at_zero_and_saturates_at_the_extent() {
        let s = ColorScale::Diverging { neg: 2.0, pos: 0.5 };
        assert_eq!(heat_color(0.0, s), [247, 247, 247]);
        assert_eq!(heat_color(-2.0, s), [33, 102, 172]);
        assert_eq!(heat_color(0.5, s), [178, 24, 43]);
        assert_eq!(heat_color(9.0, s), [178, 24, 43]);
        // colour-bar labels are the values at the tick positions: ±extent, ±extent/4
        let t = colorbar_ticks(s);
        assert_eq!(t[0].1, "-2");
        assert_eq!(t[1].1, "-0.5");
        assert_eq!(t[4].1, "0.5");
    }

    fn decode_rgb(png: &[u8]) -> (usize, usize, Vec<u8>) {
        let mut rd = png::Decoder::new(std::io::Cursor::new(png)).read_info().unwrap();
        let mut buf = vec![0; rd.output_buffer_size()];
        let info = rd.next_frame(&mut buf).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgb);
        buf.truncate(info.buffer_size());
        (info.width as usize, info.height as usize, buf)
    }

    #[test]
    fn the_diverging_tables_colours_are_heat_colors() {
        // The table against `heat_color` computed per value (the formula itself): equal for
        // every value, exactly (both are the same colours, not approximations): random values
        // over and past both sides, every bin's endpoints and their neighbouring doubles (where
        // a channel steps, the table must not take a bin's colour past its step), ±0, the
        // extremes, the non-finite.
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let up = |x: f64| f64::from_bits(x.to_bits() + 1);
        let down = |x: f64| f64::from_bits(x.to_bits().saturating_sub(1));
        for (neg, pos) in [(0.37, 2.5), (1e-12, 1e-12), (3.0, 1e-3)] {
            let scale = ColorScale::Diverging { neg, pos };
            let table = DivergingTable::new(neg, pos);
            let mut values = vec![0.0, -0.0, neg, -neg, pos, -pos, 1e300, -1e300, f64::MIN_POSITIVE, f64::INFINITY, f64::NEG_INFINITY, f64::NAN];
            for k in 0..=DivergingTable::BINS {
                for side in [-neg, pos] {
                    let v = side * k as f64 / DivergingTable::BINS as f64;
                    values.extend([v, up(v.abs()).copysign(v), down(v.abs()).copysign(v)]);
                }
            }
            for _ in 0..200_000 {
                let u = 2.4 * uniform() - 1.2;
                values.push(u * u * if u < 0.0 { -neg } else { pos });
            }
            for v in values {
                assert_eq!(table.of(v).to_vec(), heat_color(v, scale).to_vec(), "{v} on ({neg}, {pos})");
            }
            let steps = table.bins.iter().flatten().filter(|b| b.is_none()).count();
            assert!(steps < 2 * DivergingTable::BINS / 5, "{steps} bins step");
        }
    }

    #[test]
    fn an_opaque_png_written_into_its_pixmap_or_apart_decodes_to_its_pixels() {
        // The PNG of an opaque raster is written into the quarter of the pixmap its RGB bytes
        // freed, or, when it does not fit there (noise, which deflate cannot shrink to a
        // quarter), into a buffer of its own: either way the file decodes (the png crate's
        // decoder, an independent reader) to exactly the pixels painted, byte for byte.
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="97" height="61"></svg>"#;
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut noise = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state as u8
        };
        let painted: Vec<u8> = (0..97 * 61 * 3).map(|_| noise()).collect();
        for (pixels, fits) in [(vec![255u8; 97 * 61 * 3], true), (painted, false)] {
            let png = rasterise(
                svg,
                1.0,
                true,
                |pix| {
                    for (p, c) in pix.pixels_mut().iter_mut().zip(pixels.chunks_exact(3)) {
                        *p = resvg::tiny_skia::PremultipliedColorU8::from_rgba(c[0], c[1], c[2], 255).expect("opaque");
                    }
                },
                |_| {},
            )
            .unwrap();
            // (which way it went: the file against a quarter of the RGBA bytes)
            assert_eq!(png.len() <= 97 * 61, fits, "{} bytes", png.len());
            assert_eq!(decode_rgb(&png), (97, 61, pixels));
        }
    }

    #[test]
    fn a_heatmaps_png_painted_directly_is_resvgs_raster_of_the_svg() {
        // The PNG's heatmap painted cell by cell (then the rest of the figure rasterised over it)
        // against resvg's rasterisation of the SVG with its embedded raster, the reference. At
        // a cell edge the two may round a pixel's centre to different cells, so each pixel must
        // equal the reference's pixel there or at one of its 8 neighbours (an edge moved by at
        // most one pixel); away from the edges they are equal, so most pixels are identical.
        let (nx, ny) = (13, 9);
        let x: Vec<f64> = (0..nx).map(|i| -2.0 + 4.0 * i as f64 / (nx - 1) as f64).collect();
        let y: Vec<f64> = (0..ny).map(|j| 0.05 + 4.45 * j as f64 / (ny - 1) as f64).collect();
        let z: Vec<Vec<f64>> =
            (0..ny).map(|j| (0..nx).map(|i| if (i, j) == (3, 4) { f64::NAN } else { (i as f64 - 6.0) * 0.1 + (j as f64 - 3.5) * 0.07 }).collect()).collect();
        for (scale, range) in [(ColorScale::Diverging { neg: 0.8, pos: 0.7 }, None), (ColorScale::Verdict, Some((-1.0, 1.5)))] {
            let p = Plot {
                title: "map".into(),
                // no curve: a line anti-aliased over a cell edge that moved by a pixel blends
                // with the other cell's colour, which no reference pixel has
                heatmap: Some(Heatmap { x: x.clone(), y: y.clone(), z: z.clone(), scale, label: "max Re λ".into() }),
                // the second: the raster reaches outside the plot area (clipped)
                x_range: range,
                ..Default::default()
            };
            // the colour bar, painted by row (`a_maps_bar_and_boundaries_painted_directly_are_resvgs_raster`
            // compares it), is left out here: [x, y, w, h]
            let bar = p.svg_png(1.5).1.and_then(|at| at.bar).expect("a colour bar").0;
            for k in [1.0, 1.5] {
                let (w, h, fast) = decode_rgb(&p.to_png(k).unwrap());
                let (w2, h2, want) = decode_rgb(&svg_to_png(&p.to_svg(), k).unwrap());
                assert_eq!((w, h), (w2, h2));
                let px = |v: &[u8], i: usize, j: usize| [v[3 * (j * w + i)], v[3 * (j * w + i) + 1], v[3 * (j * w + i) + 2]];
                let kf = f64::from(k);
                let on_bar = |i: usize, j: usize| {
                    let (u, v) = ((i as f64 + 0.5) / kf, (j as f64 + 0.5) / kf);
                    u > bar[0] && u < bar[0] + bar[2] && v > bar[1] && v < bar[1] + bar[3]
                };
                // the bar's pixels are compared by the other test: out of the count here, so
                // that they do not pad the share of identical pixels
                let (mut same, mut total) = (0, 0);
                for j in 0..h {
                    for i in 0..w {
                        if on_bar(i, j) {
                            continue;
                        }
                        total += 1;
                        let f = px(&fast, i, j);
                        if f == px(&want, i, j) {
                            same += 1;
                            continue;
                        }
                        let near = (j.saturating_sub(1)..(j + 2).min(h)).any(|jj| (i.saturating_sub(1)..(i + 2).min(w)).any(|ii| px(&want, ii, jj) == f));
                        assert!(near, "scale {k}: pixel ({i}, {j}) {f:?} is not the reference's there or next to it ({:?})", px(&want, i, j));
                    }
                }
                assert!(same as f64 >= 0.99 * total as f64, "scale {k}: {same} of {total} pixels off the bar identical");
            }
        }
    }

    /// A cell-edge staircase along `y = f(x)` over an `n x n` grid of `[-2, 2] x [0.05, 4.5]`
    /// (its corners where `f` crosses a row), as `map::chain` gives a map's boundary.
    fn staircase(n: usize, f: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
        let (dx, dy) = (4.0 / (n - 1) as f64, 4.45 / (n - 1) as f64);
        let row = |x: f64| ((f(x) - 0.05) / dy).round().clamp(0.0, (n - 1) as f64);
        let mut pts = vec![];
        for i in 0..n {
            let x = -2.0 + i as f64 * dx;
            let y = 0.05 + (row(x) + 0.5) * dy;
            if pts.is_empty() {
                pts.push((x - dx / 2.0, y));
            } else if pts.last().is_some_and(|p: &(f64, f64)| p.1 != y) {
                pts.push((x - dx / 2.0, pts.last().unwrap().1));
                pts.push((x - dx / 2.0, y));
            }
            if i + 1 == n {
                pts.push((x + dx / 2.0, y));
            }
        }
        pts
    }

    /// A map's figure as the PNG paints it (the colour bar one colour per pixel row, the
    /// cell-edge boundaries' strokes as unions of rectangles) against resvg's raster of the
    /// same figure with the bar's 64-row raster and the boundaries as polylines in the document
    /// (miter joins), on 400 x 400 cells at the command's scale 1.5 and at 1.
    /// - Off the bar: the strokes are tiny-skia's (the same dashes, quarter-pixel edges and
    ///   coverage per sub-row), but its stroker and dasher compute some points in their own
    ///   f32 steps, which may put an edge a quarter pixel over: at most 64 of 255 (a quarter
    ///   pixel's coverage on all four sub-rows) on a pixel, and at most one pixel in 10 000
    ///   differs (measured: none at scale 1; 4 pixels, by at most 33, at 1.5).
    /// - On the bar: the colour map at each pixel row's centre against resvg's bicubic
    ///   resampling of 64 samples of it. The diverging map is piecewise linear in the bar's
    ///   height (a kink at zero): within 3 levels; the verdict's two colours meet in a sharp
    ///   edge where the resampled raster blends them over about two of its rows either side
    ///   (2 x 340 / 64 units): only there do pixels differ by more than 3 levels.
    #[test]
    fn a_maps_bar_and_boundaries_painted_directly_are_resvgs_raster() {
        let n = 400;
        let x: Vec<f64> = (0..n).map(|i| -2.0 + 4.0 * i as f64 / (n - 1) as f64).collect();
        let y: Vec<f64> = (0..n).map(|j| 0.05 + 4.45 * j as f64 / (n - 1) as f64).collect();
        let f = |x: f64| 1.4 + 0.5 * (2.0 * x).sin() + 0.3 * x;
        let g = |x: f64| 3.0 - 0.4 * x * x;
        let z: Vec<Vec<f64>> = y.iter().map(|&yv| x.iter().map(|&xv| yv - f(xv)).collect()).collect();
        let mut loops = staircase(n, f);
        // a small closed loop and a boundary ending on the plot area's top edge
        loops.extend([(f64::NAN, f64::NAN), (0.5, 2.0), (0.6, 2.0), (0.6, 2.1), (0.5, 2.1), (0.5, 2.0), (f64::NAN, f64::NAN)]);
        loops.extend([(1.2, 4.5 + 4.45 / 399.0 / 2.0), (1.2, 3.9), (1.4, 3.9), (1.4, 3.5)]);
        let dashed: Vec<(f64, f64)> = staircase(n, g).into_iter().chain([(f64::NAN, f64::NAN), (-2.0 - 2.0 / 399.0, 0.8), (2.0 + 2.0 / 399.0, 0.8)]).collect();
        for scale in [ColorScale::Verdict, ColorScale::Diverging { neg: 2.5, pos: 3.0 }] {
            let p = Plot {
                title: "Stability map, balls free".into(),
                x_label: "z̄_A".into(),
                y_label: "Ω".into(),
                series: vec![Series::new("exact stability boundary", loops.clone(), "#000000"), Series::new("003", dashed.clone(), "#CC79A7").dashed()],
                heatmap: Some(Heatmap { x: x.clone(), y: y.clone(), z: z.clone(), scale, label: "verdict".into() }),
                x_range: Some((-2.0 - 2.0 / 399.0, 2.0 + 2.0 / 399.0)),
                y_range: Some((0.05 - 4.45 / 798.0, 4.5 + 4.45 / 798.0)),
                ..Default::default()
            };
            // at 1.5 every stroke is wider than a pixel; at 1 the 1-unit ticks and frames are
            // tiny-skia's hairlines, left in the document
            let (lean1, at1) = p.svg_png(1.0);
            assert!(lean1.contains("stroke=\"#333\"") && !lean1.contains("<polyline"), "{lean1}");
            assert!(at1.is_some_and(|a| a.lines.iter().all(|l| l.color != [0x33; 3])));
            let (lean, at) = p.svg_png(1.5);
            let at = at.expect("a heatmap left out");
            assert!(!lean.contains("<polyline") && !lean.contains("<image") && at.bar.is_some(), "{lean}");
            assert!(!lean.contains("<line") && !lean.contains("stroke=\"#333\""), "ticks and frames are painted: {lean}");
            let curves = at.lines.iter().filter(|l| l.color != [0x33; 3]).count();
            assert_eq!(curves, 7, "the three solid pieces, the two dashed ones, the two legend lines");
            let (full, at_full) = p.svg_with(false, true, None);
            assert!(
                full.contains("<polyline") && full.contains("<image") && !full.contains("linejoin") && at_full.as_ref().is_some_and(|a| a.lines.is_empty())
            );
            let [bx, by, bw, bh] = at.bar.unwrap().0;
            for k in [1.0f32, 1.5] {
                let h = p.heatmap.as_ref().unwrap();
                let want = rasterise(&full, k, true, |pix| paint_heatmap(pix, h, at_full.as_ref().unwrap(), k, None), |_| {}).unwrap();
                let (w, hh, want) = decode_rgb(&want);
                let (w2, h2, got) = decode_rgb(&p.to_png(k).unwrap());
                assert_eq!((w, hh), (w2, h2));
                let kf = f64::from(k);
                let on_bar = |i: usize, j: usize| {
                    let (u, v) = ((i as f64 + 0.5) / kf, (j as f64 + 0.5) / kf);
                    u > bx && u < bx + bw && v > by && v < by + bh
                };
                let (mut differ, mut worst, mut bar_worst, mut bar_far) = (0, 0, 0, 0);
                for (m, (a, b)) in got.chunks(3).zip(want.chunks(3)).enumerate() {
                    let (i, j) = (m % w, m / w);
                    let d = a.iter().zip(b).map(|(a, b)| a.abs_diff(*b)).max().unwrap_or(0);
                    if on_bar(i, j) {
                        bar_worst = bar_worst.max(d);
                        // the verdict's edge: within two source rows of the bar's middle
                        let mid = ((j as f64 + 0.5) / kf - (by + bh / 2.0)).abs() < 2.0 * bh / 64.0;
                        if !(matches!(scale, ColorScale::Verdict) && mid) {
                            bar_far = bar_far.max(d);
                        }
                    } else {
                        worst = worst.max(d);
                        differ += usize::from(d > 0);
                    }
                }
                eprintln!("{scale:?} scale {k}: off the bar {differ} pixels differ, at most {worst}; on the bar at most {bar_worst}, away from the verdict's edge {bar_far}");
                // a quarter-pixel edge (64 levels) on at most 16 pixels: 4 measured at 1.5, 0 at 1;
                // a short stroke shifted by a quarter pixel would exceed it
                assert!(worst <= 64 && differ <= 16, "{scale:?} scale {k}: {differ} pixels differ, at most by {worst}");
                assert!(bar_far <= 3, "{scale:?} scale {k}: the bar differs by {bar_far}");
            }
        }
    }

    /// SVG's dashes `7 4` along a polyline: pieces of length 7 (the last one shorter), gaps
    /// of 4, the polyline's corners inside the pieces kept.
    #[test]
    fn dashes_are_seven_on_four_off_along_the_line() {
        let len = |p: &[(f32, f32)]| p.windows(2).map(|w| ((w[1].0 - w[0].0).powi(2) + (w[1].1 - w[0].1).powi(2)).sqrt()).sum::<f32>();
        let line = [(0.0, 0.0), (10.0, 0.0), (10.0, 5.0), (30.0, 5.0)];
        let d = dashes(&line);
        // 35 units: dashes at 0-7, 11-18, 22-29, 33-35
        let want = [7.0, 7.0, 7.0, 2.0];
        assert_eq!(d.len(), want.len());
        for (piece, w) in d.iter().zip(want) {
            assert!((len(piece) - w).abs() < 1e-5, "{piece:?}");
        }
        // the second dash turns the corner at (10, 0) and (10, 5)
        assert_eq!(d[1], vec![(10.0, 1.0), (10.0, 5.0), (13.0, 5.0)]);
        assert_eq!(d[0], vec![(0.0, 0.0), (7.0, 0.0)]);
    }

    #[test]
    fn curves_inside_the_plot_area_are_drawn_unclipped_and_nothing_past_its_edges() {
        // A map's figure: a heatmap and cell-edge boundaries (staircases whose ends lie on the
        // plot area's edges, the segment there perpendicular to the edge), drawn without the
        // clip path; the reference is the same SVG with the clip put back, both rasterised by
        // resvg. Outside the plot area every pixel is equal (a butt cap along the edge draws
        // nothing past it); inside, the clipped curves went through an 8-bit layer composited
        // over the figure, one more rounding of their anti-aliased pixels: within 2 levels of
        // 255 (measured: 2 on the 400 x 400 map's figure, 3 867 pixels of its curves).
        let (nx, ny) = (9, 7);
        let x: Vec<f64> = (0..nx).map(|i| -2.0 + 0.5 * i as f64).collect();
        let y: Vec<f64> = (0..ny).map(|j| 0.5 + 0.5 * j as f64).collect();
        let z: Vec<Vec<f64>> = (0..ny).map(|j| (0..nx).map(|i| if i + j > 7 { 0.3 } else { -0.2 }).collect()).collect();
        // cell edges: x ± 0.25, y ± 0.25; the plot area is [-2.25, 2.25] x [0.25, 3.75]
        let stair = vec![(-2.25, 1.25), (-1.25, 1.25), (-1.25, 2.25), (0.25, 2.25), (0.25, 3.25), (0.75, 3.25), (0.75, 3.75)];
        let bottom = vec![(1.25, 0.25), (1.25, 1.75), (2.25, 1.75), (f64::NAN, f64::NAN), (-0.75, 0.25), (-0.75, 0.75)];
        let p = Plot {
            title: "map".into(),
            series: vec![Series::new("exact", stair, "#000000"), Series::new("necessary", bottom, "#CC79A7").dashed()],
            heatmap: Some(Heatmap { x, y, z, scale: ColorScale::Diverging { neg: 0.2, pos: 0.3 }, label: "max Re λ".into() }),
            x_range: Some((-2.25, 2.25)),
            y_range: Some((0.25, 3.75)),
            ..Default::default()
        };
        let svg = p.to_svg();
        let open = "<g fill=\"none\" stroke-width=\"2\">";
        assert!(svg.contains(open) && !svg.contains("clip-path=\"url(#plotarea)\" fill"), "the curves' group is not clipped");
        let clipped = svg.replace(open, "<g clip-path=\"url(#plotarea)\" fill=\"none\" stroke-width=\"2\">");
        for k in [1.0, 1.5] {
            let (w, h, got) = decode_rgb(&svg_to_png(&svg, k).unwrap());
            let (w2, h2, want) = decode_rgb(&svg_to_png(&clipped, k).unwrap());
            assert_eq!((w, h), (w2, h2));
            // the plot area in pixels: [ML, ML + PW) x [44, 44 + PH) times the scale
            let kf = f64::from(k);
            let inside = |i: usize, j: usize| {
                let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
                x > ML * kf && x < (ML + PW) * kf && y > 44.0 * kf && y < (44.0 + PH) * kf
            };
            let mut differ = 0;
            for (n, (a, b)) in got.chunks(3).zip(want.chunks(3)).enumerate() {
                let (i, j) = (n % w, n / w);
                let d = a.iter().zip(b).map(|(a, b)| a.abs_diff(*b)).max().unwrap_or(0);
                assert!(d == 0 || (inside(i, j) && d <= 2), "scale {k}: pixel ({i}, {j}) {a:?} against the clipped figure's {b:?}");
                differ += usize::from(d > 0);
            }
            // only the curves' anti-aliased pixels differ, by rounding
            assert!(differ < w * h / 100, "scale {k}: {differ} pixels differ");
        }
        // a curve that crosses an edge, ends on it obliquely, or runs within half its width of
        // it keeps the clip
        for pts in [vec![(0.0, 1.0), (3.0, 2.0)], vec![(0.0, 1.0), (2.25, 2.0)], vec![(0.0, 3.74), (1.0, 3.74)]] {
            let q = Plot { series: vec![Series::new("c", pts.clone(), "#000")], x_range: p.x_range, y_range: p.y_range, ..Default::default() };
            assert!(q.to_svg().contains("<g clip-path=\"url(#plotarea)\" fill"), "{pts:?} is drawn clipped");
        }
    }

    #[test]
    fn a_stroke_is_inside_only_when_nothing_of_it_reaches_past_an_edge() {
        let area = [0.0, 100.0, 0.0, 50.0];
        // well inside; an end on the left edge with a horizontal segment; on the top edge with
        // a vertical one
        assert!(drawn_inside(&[(10.0, 10.0), (20.0, 30.0)], 1.0, area));
        assert!(drawn_inside(&[(0.0, 10.0), (20.0, 10.0), (20.0, 30.0)], 1.0, area));
        assert!(drawn_inside(&[(20.0, 30.0), (20.0, 0.0)], 1.0, area));
        // written to two decimals: 0.005 past the edge is on it
        assert!(drawn_inside(&[(-0.005, 10.0), (20.0, 10.0)], 1.0, area));
        // an oblique end on the edge, a vertex within the half-width, a corner end, outside
        assert!(!drawn_inside(&[(0.0, 10.0), (20.0, 12.0)], 1.0, area));
        assert!(!drawn_inside(&[(10.0, 10.0), (99.5, 20.0), (10.0, 30.0)], 1.0, area));
        assert!(!drawn_inside(&[(0.0, 0.0), (0.0, 10.0)], 1.0, area));
        assert!(!drawn_inside(&[(10.0, 10.0), (20.0, 51.0)], 1.0, area));
        assert!(disk_inside((10.0, 10.0), 3.5, area) && !disk_inside((2.0, 10.0), 3.5, area));
    }

    /// The RGB bytes packed in place are the plain copy of each pixel's first three bytes, for
    /// every length around the 8-pixel blocks; the opacity test finds a single translucent
    /// pixel wherever it is.
    #[test]
    fn rgba_packed_in_place_is_the_plain_copy() {
        for n in 0..40usize {
            let rgba: Vec<u8> = (0..4 * n).map(|k| (k * 37 % 251) as u8 | 1).collect();
            let want: Vec<u8> = rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
            let mut d = rgba.clone();
            let len = rgba_to_rgb_in_place(&mut d);
            assert_eq!(&d[..len], &want[..], "{n} pixels");
            let mut op: Vec<u8> = rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2], 255]).collect();
            assert!(opaque(&op), "{n} pixels");
            for k in 0..n {
                op[4 * k + 3] = 254;
                assert!(!opaque(&op), "{n} pixels, pixel {k} translucent");
                op[4 * k + 3] = 255;
            }
        }
    }

    /// The PNG as this module wrote it before its pixels were packed in place: fonts copied
    /// into the heap, a zeroed pixmap filled white, an RGB copy of every pixel, the same
    /// encoder settings. The new route must give the same bytes.
    fn png_by_copies(
        svg: &str,
        scale: f32,
        white: bool,
        under: impl FnOnce(&mut resvg::tiny_skia::Pixmap),
        over: impl FnOnce(&mut resvg::tiny_skia::Pixmap),
    ) -> Vec<u8> {
        use resvg::{tiny_skia, usvg};
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(dejavu::sans::regular().to_vec());
        db.load_font_data(dejavu::sans::bold().to_vec());
        db.set_sans_serif_family("DejaVu Sans");
        let opt = usvg::Options { fontdb: std::sync::Arc::new(db), font_family: "DejaVu Sans".into(), ..Default::default() };
        let tree = usvg::Tree::from_str(svg, &opt).unwrap();
        let size = tree.size().to_int_size().scale_by(scale).unwrap();
        let mut pix = tiny_skia::Pixmap::new(size.width(), size.height()).unwrap();
        if white {
            pix.fill(tiny_skia::Color::WHITE);
        }
        under(&mut pix);
        resvg::render(&tree, tiny_skia::Transform::from_scale(scale, scale), &mut pix.as_mut());
        over(&mut pix);
        let rgb: Vec<u8> = pix.data().chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
        assert!(pix.pixels().iter().all(|p| p.alpha() == 255), "an opaque figure");
        let mut out = vec![];
        let mut enc = png::Encoder::new(&mut out, pix.width(), pix.height());
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Fast);
        enc.write_header().unwrap().write_image_data(&rgb).unwrap();
        out
    }

    /// A figure's PNG (a heatmap painted directly, with curves, text and the colour bar; a
    /// plain figure through its SVG) is byte for byte the PNG of the copying route: the fonts
    /// borrowed from the binary, the pixmap made white in one pass and packed to RGB in place
    /// change no pixel and no byte of the file; and it decodes to the copying route's pixels.
    #[test]
    fn a_png_packed_in_place_is_the_copying_routes_bytes() {
        let (nx, ny) = (41, 37);
        let x: Vec<f64> = (0..nx).map(|i| -2.0 + 4.0 * i as f64 / (nx - 1) as f64).collect();
        let y: Vec<f64> = (0..ny).map(|j| 0.05 + 4.45 * j as f64 / (ny - 1) as f64).collect();
        let z: Vec<Vec<f64>> = (0..ny).map(|j| (0..nx).map(|i| ((i as f64 - 20.0) * 0.1).sin() + (j as f64 - 18.0) * 0.03).collect()).collect();
        let curve: Vec<(f64, f64)> = (0..60).map(|k| (-2.0 + 4.0 * k as f64 / 59.0, 2.0 + (k as f64 * 0.2).sin())).collect();
        for scale in [ColorScale::Diverging { neg: 1.3, pos: 1.6 }, ColorScale::Verdict] {
            let p = Plot {
                title: "Stability map, balls free".into(),
                x_label: "z̄_A (balancer plane from C / ρ_s)".into(),
                y_label: "Ω = ω/ω0".into(),
                series: vec![
                    Series::new("exact stability boundary", curve.clone(), "#000000"),
                    Series::new("003", curve.iter().map(|&(a, b)| (a, b - 1.0)).collect(), "#CC79A7").dashed(),
                ],
                heatmap: Some(Heatmap { x: x.clone(), y: y.clone(), z: z.clone(), scale, label: "max Re λ".into() }),
                ..Default::default()
            };
            for k in [1.0, 1.5] {
                let (svg, at) = p.svg_png(k);
                let at = at.expect("a heatmap left out of the SVG");
                let want = png_by_copies(&svg, k, true, |pix| paint_under(pix, p.heatmap.as_ref().unwrap(), &at, k, None), |pix| paint_over(pix, &at, k));
                let got = p.to_png(k).unwrap();
                assert!(got == want, "scale {k}: {} bytes against {}", got.len(), want.len());
                assert_eq!(decode_rgb(&got), decode_rgb(&want));
            }
        }
        let plain = Plot {
            title: "amplitude".into(),
            series: vec![Series::new("r", (0..50).map(|k| (k as f64, (k as f64).sqrt())).collect(), "#0072B2")],
            ..Default::default()
        };
        let svg = plain.to_svg();
        assert!(svg_to_png(&svg, 1.5).unwrap() == png_by_copies(&svg, 1.5, false, |_| {}, |_| {}));
    }

    /// A figure written both ways at once ([`Plot::to_svg_and_png`], the heatmap's colours
    /// computed once) is [`Plot::to_svg`] and [`Plot::to_png`] byte for byte: a grid wider than
    /// high (a row or column mixed up, or the rows not reversed for the raster, moves colours),
    /// NaN cells, both colour scales, two scales of the PNG; a ragged grid (no raster, no
    /// painted cells) and a figure without a heatmap likewise.
    #[test]
    fn svg_and_png_at_once_are_each_alone() {
        let (nx, ny) = (23, 9);
        let x: Vec<f64> = (0..nx).map(|i| -2.0 + 4.0 * i as f64 / (nx - 1) as f64).collect();
        let y: Vec<f64> = (0..ny).map(|j| 0.05 + 4.45 * j as f64 / (ny - 1) as f64).collect();
        let z: Vec<Vec<f64>> = (0..ny)
            .map(|j| (0..nx).map(|i| if (i + j) % 11 == 3 { f64::NAN } else { ((i as f64 - 7.0) * 0.3).sin() + (j as f64 - 4.0) * 0.2 }).collect())
            .collect();
        let mut ragged = z.clone();
        ragged[2].pop();
        for scale in [ColorScale::Diverging { neg: 1.3, pos: 0.6 }, ColorScale::Verdict] {
            for z in [z.clone(), ragged.clone()] {
                let p = Plot {
                    title: "map".into(),
                    series: vec![Series::new("boundary", (0..30).map(|k| (-2.0 + 4.0 * k as f64 / 29.0, 2.0 + (k as f64 * 0.3).sin())).collect(), "#000000")],
                    heatmap: Some(Heatmap { x: x.clone(), y: y.clone(), z, scale, label: "max Re λ".into() }),
                    ..Default::default()
                };
                // the SVG's raster against its definition: the top row the last `y`, each
                // cell `heat_color` of its value
                let h = p.heatmap.as_ref().unwrap();
                let want = (h.z.iter().all(|r| r.len() == nx))
                    .then(|| png_bytes(nx, ny, &h.z.iter().rev().flat_map(|r| r.iter().flat_map(|&v| heat_color(v, scale))).collect::<Vec<u8>>()).unwrap());
                assert!(Plot::heat_png(h, None) == want, "{scale:?}: the SVG's raster");
                for k in [1.0, 1.5] {
                    let (svg, png) = p.to_svg_and_png(k);
                    assert!(svg == p.to_svg(), "{scale:?}, scale {k}: the SVG differs");
                    assert!(png.unwrap() == p.to_png(k).unwrap(), "{scale:?}, scale {k}: the PNG differs");
                }
            }
        }
        let plain = Plot {
            title: "amplitude".into(),
            series: vec![Series::new("r", (0..50).map(|k| (k as f64, (k as f64).sqrt())).collect(), "#0072B2")],
            ..Default::default()
        };
        let (svg, png) = plain.to_svg_and_png(1.5);
        assert!(svg == plain.to_svg() && png.unwrap() == plain.to_png(1.5).unwrap());
    }

    #[test]
    fn png_has_the_svg_size_times_the_scale() {
        let p = Plot { title: "Ω̄ ΔĀ".into(), series: vec![Series::new("ψ", vec![(0.0, 0.0), (1.0, 1.0)], "#000")], ..Default::default() };
        let png = p.to_png(1.0).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        let w = u32::from_be_bytes(png[16..20].try_into().unwrap()) as f64;
        let svg = p.to_svg();
        let sw: f64 = svg.split("width=\"").nth(1).unwrap().split('"').next().unwrap().parse().unwrap();
        assert_eq!(w, sw.ceil());
        // the fast RGB encoding decodes to the rasteriser's pixels
        let dec = png::Decoder::new(std::io::Cursor::new(&png));
        let mut rd = dec.read_info().unwrap();
        let mut buf = vec![0; rd.output_buffer_size()];
        let info = rd.next_frame(&mut buf).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgb);
        let opt = resvg::usvg::Options { fontdb: fontdb().clone(), font_family: "DejaVu Sans".into(), ..Default::default() };
        let tree = resvg::usvg::Tree::from_str(&svg, &opt).unwrap();
        let mut pix = resvg::tiny_skia::Pixmap::new(info.width, info.height).unwrap();
        resvg::render(&tree, resvg::tiny_skia::Transform::identity(), &mut pix.as_mut());
        let want: Vec<u8> = pix.pixels().iter().flat_map(|p| [p.red(), p.green(), p.blue()]).collect();
        assert!(buf[..info.buffer_size()] == want[..], "decoded pixels differ");
    }

    /// What `Heatmap::drawable` checks, as its doc says: the axes (finite, rising), not the
    /// values (a non-finite `z` is a grey cell, drawn); a descending axis is left out of the
    /// figure, which is still drawn.
    #[test]
    fn a_heatmap_is_drawn_with_nan_cells_and_left_out_with_a_descending_axis() {
        let hm = |x: Vec<f64>, y: Vec<f64>, z: f64| Heatmap { z: vec![vec![z; x.len()]; y.len()], x, y, scale: ColorScale::Verdict, label: "m".into() };
        // the raster is one `<image>` (the colour bar, drawn either way, another)
        let images = |h: Heatmap| Plot { heatmap: Some(h), ..Default::default() }.to_svg().matches("<image").count();
        let up = vec![0.0, 1.0, 2.0];
        for z in [0.5, f64::NAN, f64::INFINITY] {
            let h = hm(up.clone(), up.clone(), z);
            assert!(h.drawable(), "z = {z}");
            assert_eq!(images(h), 2, "z = {z}");
        }
        let down = vec![2.0, 1.0, 0.0];
        for h in [hm(down.clone(), up.clone(), 0.5), hm(up.clone(), down.clone(), 0.5), hm(vec![0.0, f64::NAN], up.clone(), 0.5)] {
            assert!(!h.drawable());
            assert!(Plot { heatmap: Some(h.clone()), ..Default::default() }.to_png(1.0).is_ok());
            assert_eq!(images(h), 1);
        }
    }

    /// Degenerate data never panics: every kind of figure (curves, markers, shades, vertical
    /// lines, a heatmap of each scale, named ticks, a second axis) with empty, NaN-only,
    /// infinite, one-point and equal-valued data, and heatmaps with an empty x or y grid, rows
    /// missing or ragged, is written as SVG, PNG, both at once and Plotly JSON; each PNG
    /// decodes and the SVG is one document. (An empty heatmap grid panicked in `to_png`: the
    /// raster's placement divided by zero cells and indexed `n - 1`.)
    #[test]
    fn degenerate_data_of_every_kind_gives_a_figure_not_a_panic() {
        let nan = f64::NAN;
        let inf = f64::INFINITY;
        let datas: Vec<Vec<(f64, f64)>> = vec![
            vec![],
            vec![(nan, nan)],
            vec![(nan, 1.0), (2.0, nan)],
            vec![(1.0, 2.0)],
            vec![(1.0, 2.0), (1.0, 2.0)],
            vec![(inf, 1.0), (-inf, -inf)],
            vec![(0.0, 1e308), (1e-308, -1e308)],
        ];
        let grids: Vec<Vec<f64>> = vec![vec![], vec![1.0], vec![1.0, 1.0], vec![nan, nan], vec![0.0, 1.0, 2.0], vec![inf, 0.0]];
        let mut plots = vec![];
        for d in &datas {
            for (markers, dashed) in [(false, false), (true, false), (false, true)] {
                let mut s = Series::new("c", d.clone(), "#0072B2");
                s.markers = markers;
                s.dashed = dashed;
                let x = d.first().map_or(0.0, |p| p.0);
                plots.push(Plot {
                    series: vec![s],
                    shades: vec![Shade { x: (x, x), y: (None, d.first().map(|p| p.1)), color: "#ccc".into() }],
                    vlines: vec![(x, "v".into())],
                    x2: Some(SecondAxis { factor: 30.0 / std::f64::consts::PI, label: "rpm".into() }),
                    ..Default::default()
                });
            }
            plots.push(Plot { series: vec![Series::new("c", d.clone(), "#000")], y_ticks: Some(vec![]), ..Default::default() });
            plots.push(Plot { series: vec![Series::new("c", d.clone(), "#000")], y_ticks: Some(vec![(nan, "a".into())]), ..Default::default() });
            plots.push(Plot { series: vec![Series::new("c", d.clone(), "#000")], x_range: Some((1.0, 1.0)), y_range: Some((nan, inf)), ..Default::default() });
        }
        for x in &grids {
            for y in &grids {
                for zs in [
                    vec![vec![0.5; x.len()]; y.len()],
                    vec![vec![nan; x.len()]; y.len()],
                    vec![],
                    vec![vec![1.0; x.len() + 1]; y.len()],
                    vec![vec![inf; x.len()]; y.len()],
                ] {
                    for scale in [ColorScale::Verdict, ColorScale::Diverging { neg: 0.0, pos: 0.0 }, ColorScale::Diverging { neg: nan, pos: inf }] {
                        let boundary = Series::new("b", x.iter().zip(y).map(|(&a, &b)| (a, b)).collect(), "#000");
                        plots.push(Plot {
                            series: vec![boundary],
                            heatmap: Some(Heatmap { x: x.clone(), y: y.clone(), z: zs.clone(), scale, label: "m".into() }),
                            ..Default::default()
                        });
                    }
                }
            }
        }
        for p in &plots {
            let svg = p.to_svg();
            assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"), "{}", &svg[..svg.len().min(80)]);
            let png = p.to_png(1.0).expect("a PNG");
            assert!(png.starts_with(b"\x89PNG"));
            let (svg2, png2) = p.to_svg_and_png(1.0);
            assert_eq!(svg2, svg);
            assert_eq!(png2.expect("a PNG"), png);
            // every trace named, and one with points has a finite one (as the browser test
            // counts them, the second axis's trace aside: what `point_count` says the page holds)
            let js = p.to_plotly();
            let mut drawn = 0;
            for t in js["data"].as_array().unwrap() {
                assert!(t["name"].as_str().is_some_and(|n| !n.is_empty()), "{t}");
                if t["type"] == "heatmap" {
                    drawn += t["z"].as_array().unwrap().iter().flat_map(|r| r.as_array().unwrap()).filter(|v| v.is_f64()).count();
                    continue;
                }
                let (x, y) = (t["x"].as_array().unwrap(), t["y"].as_array().unwrap());
                let n = x.iter().zip(y).filter(|(a, b)| a.is_f64() && b.is_f64()).count();
                assert!(x.is_empty() || n > 0, "{t}");
                if t["xaxis"] != "x2" {
                    drawn += n;
                }
            }
            assert_eq!(drawn, p.point_count(), "{js}");
        }
        // ticks of a span past the largest float, of no target count, of NaN: finite or one
        for (lo, hi, n) in [(-1e308, 1e308, 7), (0.0, 1.0, 0), (nan, 1.0, 7), (0.0, inf, 7), (5e-324, 1e-323, 7)] {
            let t = ticks(lo, hi, n);
            assert!(!t.is_empty() && t.len() <= 12, "{lo} {hi} {n}: {t:?}");
            assert!(t.iter().all(|v| v.is_finite()) || lo.is_nan(), "{lo} {hi} {n}: {t:?}");
        }
    }
}
