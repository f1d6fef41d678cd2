//! Where a view's pixels can lie: square rings about the pose's pixel (the order occluders
//! are searched in), the box around the field of view, and the columns of a pixel row or the
//! rows of a pixel column inside the field of view's wedge ([`Wedge`]). Each is a superset
//! of the pixels the exact test of [`Camera::view`](super::Camera::view) can accept, so
//! restricting the scan to it changes no view.

use super::wrap;

/// The pixels of the square ring `k` about pixel `(pc, pr)` (ring 0 is the pixel itself)
/// that lie within `cols × rows`.
pub(super) fn ring(
    pc: i64,
    pr: i64,
    k: i64,
    cols: &std::ops::RangeInclusive<i64>,
    rows: &std::ops::RangeInclusive<i64>,
) -> impl Iterator<Item = (i64, i64)> {
    let (c0, c1, r0, r1) = (*cols.start(), *cols.end(), *rows.start(), *rows.end());
    let row_span = move |r: i64| {
        let lo = (pc - k).max(c0);
        let hi = (pc + k).min(c1);
        let on = r >= r0 && r <= r1;
        (lo..=hi).filter(move |_| on).map(move |c| (c, r))
    };
    let side = move |c: i64| {
        let on = c >= c0 && c <= c1;
        ((pr - k + 1).max(r0)..=(pr + k - 1).min(r1)).filter(move |_| on).map(move |r| (c, r))
    };
    let top = row_span(pr + k);
    let bottom = (k > 0).then(|| row_span(pr - k)).into_iter().flatten();
    let sides = (k > 0).then(|| side(pc - k).chain(side(pc + k))).into_iter().flatten();
    top.chain(bottom).chain(sides)
}

/// The box `(x0, y0, x1, y1)` around the sector of `radius` about `pos` between the headings
/// `psi ± half` (`half` below a quarter turn): the apex, the two arc ends, and the arc's points
/// in the axis directions the sector holds (with a hair of slack on the headings).
pub(super) fn sector_box(pos: (f64, f64), psi: f64, half: f64, radius: f64) -> (f64, f64, f64, f64) {
    let mut b = (pos.0, pos.1, pos.0, pos.1);
    let mut add = |a: f64| {
        let (y, x) = a.sin_cos();
        let (px, py) = (pos.0 + radius * x, pos.1 + radius * y);
        b = (b.0.min(px), b.1.min(py), b.2.max(px), b.3.max(py));
    };
    add(psi - half);
    add(psi + half);
    for k in 0..4 {
        let axis = k as f64 * 0.5 * std::f64::consts::PI;
        if wrap(axis - psi).abs() <= half + 1e-6 {
            add(axis);
        }
    }
    b
}

/// Radians the field of view's edges are widened by, so that a pixel the pre-filter keeps (an
/// edge margin of 1e-9 of its range) is never outside the wedge: 1e-6 of the range is
/// above that margin beyond a thousandth of a pixel from the pose, and the pixels nearer
/// than that lie in the 3 × 3 block about the pose's pixel, which is scanned whole.
const WIDEN_RAD: f64 = 1e-6;

/// Slopes below this leave a span unbounded on that side (conservative): a bound `−b/a` is
/// computed only where rounding moves it by far less than the pixel of slack added.
const MIN_SLOPE: f64 = 1e-6;

/// The field of view about a pose (px) as the two half-planes through the pose bounded by
/// its widened edges; only for a field of view below a half turn, where their intersection is
/// the wedge.
pub(super) struct Wedge {
    pos: (f64, f64),
    /// The pixel holding the pose.
    pixel: (i64, i64),
    /// Unit vectors along the right edge (`ψ − half`) and the left edge (`ψ + half`).
    right: (f64, f64),
    left: (f64, f64),
}

/// `a × b` (z component).
fn cross(a: (f64, f64), b: (f64, f64)) -> f64 {
    a.0 * b.1 - a.1 * b.0
}

impl Wedge {
    /// The wedge at `pos` between the headings `from` and `to` (`from < to < from + π`),
    /// widened by [`WIDEN_RAD`] on each side.
    pub(super) fn new(pos: (f64, f64), from: f64, to: f64) -> Self {
        let (sr, cr) = (from - WIDEN_RAD).sin_cos();
        let (sl, cl) = (to + WIDEN_RAD).sin_cos();
        Self { pos, pixel: (pos.0.floor() as i64, pos.1.floor() as i64), right: (cr, sr), left: (cl, sl) }
    }

    /// The interval of `t` for which `base + t·e` (offsets from the pose, `e` a unit axis
    /// perpendicular to `base`) lies in the wedge within `radius`, or `None`.
    fn span(&self, base: (f64, f64), e: (f64, f64), radius: f64) -> Option<(f64, f64)> {
        let chord2 = radius * radius - (base.0 * base.0 + base.1 * base.1);
        if chord2 < 0.0 {
            return None;
        }
        let half_chord = chord2.sqrt();
        let (mut lo, mut hi) = (-half_chord, half_chord);
        // Inside: right × p ≥ 0 and p × left ≥ 0, each `a·t + b ≥ 0` along the line.
        for (a, b) in [(cross(self.right, e), cross(self.right, base)), (cross(e, self.left), cross(base, self.left))] {
            if a >= MIN_SLOPE {
                lo = lo.max(-b / a);
            } else if a <= -MIN_SLOPE {
                hi = hi.min(-b / a);
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// The columns (with a pixel of slack on each side) of row `r` whose pixel centres can lie
    /// in the wedge within `radius`; empty when `lo > hi`. Rows next to the pose's row also
    /// hold the 3 × 3 block about the pose's pixel.
    pub(super) fn cols(&self, r: i64, radius: f64) -> (i64, i64) {
        let base = (0.0, r as f64 + 0.5 - self.pos.1);
        let span = self.span(base, (1.0, 0.0), radius).map(|(t0, t1)| pixels(self.pos.0, t0, t1));
        self.with_block(span, r - self.pixel.1, self.pixel.0)
    }

    /// [`Self::cols`] for the rows of column `c`.
    pub(super) fn rows(&self, c: i64, radius: f64) -> (i64, i64) {
        let base = (c as f64 + 0.5 - self.pos.0, 0.0);
        let span = self.span(base, (0.0, 1.0), radius).map(|(t0, t1)| pixels(self.pos.1, t0, t1));
        self.with_block(span, c - self.pixel.0, self.pixel.1)
    }

    /// `span` widened to hold the three pixels about `centre` when the line is at most one
    /// pixel (`off`) from the pose's pixel.
    fn with_block(&self, span: Option<(i64, i64)>, off: i64, centre: i64) -> (i64, i64) {
        match span {
            _ if off.abs() > 1 => span.unwrap_or((1, 0)),
            Some((lo, hi)) => (lo.min(centre - 1), hi.max(centre + 1)),
            None => (centre - 1, centre + 1),
        }
    }
}

/// The pixels whose centres lie between `origin + t0` and `origin + t1`, and one more on each
/// side.
fn pixels(origin: f64, t0: f64, t1: f64) -> (i64, i64) {
    ((origin + t0 - 0.5).floor() as i64 - 1, (origin + t1 - 0.5).ceil() as i64 + 1)
}
