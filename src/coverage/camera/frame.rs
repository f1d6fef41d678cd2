//! One pose's view geometry ([`Frame`]): the depth range, the pixels that can count, the
//! pre-filter that passes over pixels certainly out of range or out of the field of view, and
//! the search for each section's nearest occluder (000 eq. 1).

use super::sector::{Wedge, ring, sector_box};
use super::{Camera, wrap};
use std::ops::RangeInclusive;

/// The geometry of a view from one pose (px, radians), computed once per pose.
pub(super) struct Frame {
    pos: (f64, f64),
    psi: f64,
    /// The pixel holding the pose.
    pub(super) pixel: (i64, i64),
    /// `d_max` as computed with (capped at the raster or not).
    pub(super) d_max: f64,
    /// Rings (and box half-widths) that can hold a pixel within `d_max`.
    pub(super) reach: i64,
    /// Whether pixels certainly out of range or view are passed over.
    prefilter: bool,
    /// `(max(d_max, d_min)·(1 + 1e-9))²`: no pixel farther counts.
    range_skip: f64,
    half: f64,
    sin_cos_psi: (f64, f64),
    sin_cos_half: (f64, f64),
    /// The wedge of the field of view, where the pre-filter applies and the field of view is
    /// below a half turn.
    pub(super) wedge: Option<Wedge>,
    /// The columns and rows that can hold a pixel other than passed over.
    pub(super) cols: RangeInclusive<i64>,
    pub(super) rows: RangeInclusive<i64>,
}

impl Frame {
    /// The frame of `camera` at `pos` with heading `psi` on a `width × height` raster.
    pub(super) fn new(
        camera: &Camera,
        (width, height): (usize, usize),
        (pos, psi): ((f64, f64), f64),
        prefilter: bool,
        capped: bool,
    ) -> Self {
        let d_max = if capped { camera.effective_d_max(width, height, pos) } else { camera.d_max };
        let reach = d_max.ceil() as i64 + 1;
        let (pc, pr) = (pos.0.floor() as i64, pos.1.floor() as i64);
        // No pixel beyond d_max counts, and none is seen beyond max(d_max, d_min) (eq. 1).
        let range_skip = (d_max.max(camera.d_min) * (1.0 + 1e-9)).powi(2);
        let half = 0.5 * camera.fov;
        let cone = prefilter && half < 0.5 * std::f64::consts::PI - 1e-6;
        // With the pre-filter, only the pixels of the box around the field of view out to the
        // range (a pixel wider on every side) can be other than passed over.
        let (cols, rows) = if cone {
            let (x0, y0, x1, y1) = sector_box(pos, psi, half, range_skip.sqrt());
            let span = |lo: f64, hi: f64, p: i64| {
                ((lo - 0.5).floor() as i64 - 1).max(p - reach)..=((hi - 0.5).ceil() as i64 + 1).min(p + reach)
            };
            (span(x0, x1, pc), span(y0, y1, pr))
        } else {
            (pc - reach..=pc + reach, pr - reach..=pr + reach)
        };
        Self {
            pos,
            psi,
            pixel: (pc, pr),
            d_max,
            reach,
            prefilter,
            range_skip,
            half,
            sin_cos_psi: psi.sin_cos(),
            sin_cos_half: half.sin_cos(),
            wedge: cone.then(|| Wedge::new(pos, psi - half, psi + half)),
            cols,
            rows,
        }
    }

    /// Range and bearing relative to the heading of pixel `(c, r)`'s centre.
    pub(super) fn polar(&self, c: i64, r: i64) -> (f64, f64) {
        let (dx, dy) = (c as f64 + 0.5 - self.pos.0, r as f64 + 0.5 - self.pos.1);
        (dx.hypot(dy), wrap(dy.atan2(dx) - self.psi))
    }

    /// With the pre-filter, whether pixel `(c, r)` is certainly beyond the range or outside
    /// the field of view; the margins (1e-9 relative) are far above rounding.
    pub(super) fn passed_over(&self, c: i64, r: i64) -> bool {
        let (dx, dy) = (c as f64 + 0.5 - self.pos.0, r as f64 + 0.5 - self.pos.1);
        let d2 = dx * dx + dy * dy;
        if !self.prefilter || d2 <= 1e-18 {
            return false;
        }
        if d2 > self.range_skip {
            return true;
        }
        // With θ the angle from the heading, `sin(θ − half)·d`: positive past the edge of
        // the field of view (for a field of view below a half turn).
        let ((sin_psi, cos_psi), (sin_half, cos_half)) = (self.sin_cos_psi, self.sin_cos_half);
        let along = dx * cos_psi + dy * sin_psi;
        let across = (dy * cos_psi - dx * sin_psi).abs();
        self.wedge.is_some() && across * cos_half - along * sin_half > 1e-9 * (dx.abs() + dy.abs() + 1.0)
    }

    /// Each section's nearest occluder within `d_max` (`min d_obs,i` of eq. 1; infinite where
    /// none), searched ring by ring outwards (square rings about the pose's pixel). A pixel of
    /// ring k lies at least k − ½ px away, so a section whose occluder is nearer is closed:
    /// once all are, the search stops, and from ring 2 on, with the pre-filter, each side of
    /// a ring is cut to the wedge of the sections still open (a pixel outside it belongs to a
    /// closed section, whose depth it cannot change).
    pub(super) fn nearest_occluders(&self, camera: &Camera, occluded: &impl Fn(i64, i64) -> bool) -> Vec<f64> {
        let mut nearest = vec![f64::INFINITY; camera.sections];
        let see = |c: i64, r: i64, nearest: &mut [f64]| {
            if occluded(c, r) && !self.passed_over(c, r) {
                let (d, phi) = self.polar(c, r);
                if d <= self.d_max
                    && let Some(i) = camera.section(phi)
                {
                    nearest[i] = nearest[i].min(d);
                }
            }
        };
        let ((pc, pr), (cols, rows)) = (self.pixel, (&self.cols, &self.rows));
        let radius = self.range_skip.sqrt() + 1.0;
        let step = camera.fov / camera.sections as f64;
        let mut open: Option<((usize, usize), Wedge)> = None;
        for k in 0..=self.reach {
            if k > 1 && self.wedge.is_some() {
                let closed_below = k as f64 - 0.5 - 1e-9;
                let first = nearest.iter().position(|&o| o >= closed_below).unwrap_or(0);
                let last = nearest.iter().rposition(|&o| o >= closed_below).unwrap_or(camera.sections - 1);
                if open.as_ref().is_none_or(|(span, _)| *span != (first, last)) {
                    let from = self.psi - self.half;
                    let wedge = Wedge::new(self.pos, from + first as f64 * step, from + (last + 1) as f64 * step);
                    open = Some(((first, last), wedge));
                }
            }
            match &open {
                Some((_, w)) if k > 1 => {
                    for r in [pr - k, pr + k].into_iter().filter(|r| rows.contains(r)) {
                        let (lo, hi) = w.cols(r, radius);
                        let span = lo.max(pc - k).max(*cols.start())..=hi.min(pc + k).min(*cols.end());
                        span.for_each(|c| see(c, r, &mut nearest));
                    }
                    for c in [pc - k, pc + k].into_iter().filter(|c| cols.contains(c)) {
                        let (lo, hi) = w.rows(c, radius);
                        let span = lo.max(pr - k + 1).max(*rows.start())..=hi.min(pr + k - 1).min(*rows.end());
                        span.for_each(|r| see(c, r, &mut nearest));
                    }
                }
                _ => ring(pc, pr, k, cols, rows).for_each(|(c, r)| see(c, r, &mut nearest)),
            }
            let closed = k as f64 + 0.5 - 1e-9;
            if self.prefilter && nearest.iter().all(|&o| o < closed) {
                break;
            }
        }
        nearest
    }
}
