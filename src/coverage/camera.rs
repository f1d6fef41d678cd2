//! The camera coverage model of 000 (§II-C.1, eq. 1, Fig. 4; waypoint §5, W8–W9): a forward
//! camera with depth range `[d_min, d_max]` and horizontal field of view `θ_fov`, split into
//! `m` angular sections; each section sees up to its first obstacle. [`ViewShape::Fan`] draws
//! the view as the authors' public code does (a polygon through the section depths).

use frame::Frame;

/// Camera parameters in pixel units (ranges) and radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// `d_min` in px.
    pub d_min: f64,
    /// `d_max` in px.
    pub d_max: f64,
    /// `θ_fov` in radians.
    pub fov: f64,
    /// `m`, the number of sections.
    pub sections: usize,
    /// How the section depths become a viewed area.
    pub shape: ViewShape,
}

/// How a pose's section depths `d_view,i` (eq. 1) become the set of viewed pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ViewShape {
    /// 000 eq. 1 as written (W9): a pixel is seen when it lies in a section, at a range
    /// between `d_min` and that section's first obstacle.
    #[default]
    Sections,
    /// The authors' code (`mappy.py`, frustum precomputation): one ray per section at the
    /// section's first bearing with the section's depth, and the filled polygon through the ray
    /// ends and the two `d_min` points of the outer rays. Between two rays the edge is a straight
    /// chord instead of an arc cut at each section's nearest obstacle, the bearings past the last
    /// ray (one section's width) are not seen, and where neighbouring depths differ (a door, a
    /// corner) a chord can cross a wall.
    Fan,
}

/// `C = α·C_open + (1 − α)·C_walls` (000 eq. 2): the camera coverage of open floor and walls
/// blended by the weight `α` of the open floor.
pub fn blended_coverage(alpha: f64, open: f64, walls: f64) -> f64 {
    alpha * open + (1.0 - alpha) * walls
}

/// `wrap(θ)` into (−π, π].
pub fn wrap(a: f64) -> f64 {
    let mut x = a.rem_euclid(std::f64::consts::TAU);
    if x > std::f64::consts::PI {
        x -= std::f64::consts::TAU;
    }
    x
}

/// `d_view,i = max(min(d_max, min d_obs,i), d_min)` (000 eq. 1).
pub fn d_view(d_max: f64, d_min: f64, nearest_obstacle: f64) -> f64 {
    d_max.min(nearest_obstacle).max(d_min)
}

impl Camera {
    /// Section of a relative bearing `φ` (W9), or `None` outside the field of view.
    pub fn section(&self, phi: f64) -> Option<usize> {
        let half = 0.5 * self.fov;
        if phi.abs() > half {
            return None;
        }
        Some((((phi + half) / (self.fov / self.sections as f64)).floor() as usize).min(self.sections - 1))
    }

    /// The depth range a view from `pos` on a `width × height` raster is computed with: with
    /// [`ViewShape::Sections`], `d_max` capped at two pixels beyond the raster corner farthest
    /// from `pos`, so that a `d_max` far beyond the map costs no more than one spanning it.
    /// The views are the same: every raster pixel lies within that distance of `pos`, and an
    /// occluder beyond it (off the raster) only caps a section's depth at a range where no
    /// raster pixel lies. A fan's chords depend on the ray ends, so a fan keeps `d_max`.
    pub fn effective_d_max(&self, width: usize, height: usize, pos: (f64, f64)) -> f64 {
        match self.shape {
            ViewShape::Sections => {
                let dx = pos.0.abs().max((width as f64 - pos.0).abs());
                let dy = pos.1.abs().max((height as f64 - pos.1).abs());
                self.d_max.min(dx.hypot(dy) + 2.0)
            }
            ViewShape::Fan => self.d_max,
        }
    }

    /// Calls `visible(index)` for every explorable pixel seen from `pos` (px) with heading `psi`:
    /// in the field of view, at range `d_min ≤ r ≤ d_view` of its section. `occluded(col, row)`
    /// must be true outside the raster.
    ///
    /// A pixel belongs to the section of its centre's bearing (W9). Closer than about
    /// `m / θ_fov` pixels (12.4 px for 000's camera: 15 sections over 69.4°) a pixel spans more
    /// than a section, so a section can hold no centre of a one-pixel-thick wall in front of it
    /// and sees past the wall, as eq. 1 read pixel by pixel implies. Beyond that range, or
    /// behind walls several pixels thick, a section holds some wall centre in practice.
    pub fn view(
        &self,
        width: usize,
        height: usize,
        occluded: impl Fn(i64, i64) -> bool,
        pos: (f64, f64),
        psi: f64,
        visible: impl FnMut(usize),
    ) {
        self.view_filtered(width, height, occluded, pos, psi, true, true, |_| false, visible);
    }

    /// Adds the pixels of [`Self::view`] to the union `seen` (one flag per raster pixel). A
    /// pixel already in the union is passed over before its range and bearing are computed:
    /// it could only be marked again, so the union is the same as marking every view in full
    /// (tested), at a fraction of the cost along densely posed paths.
    pub fn view_into(
        &self,
        width: usize,
        height: usize,
        occluded: impl Fn(i64, i64) -> bool,
        pos: (f64, f64),
        psi: f64,
        seen: &mut [bool],
    ) {
        assert_eq!(seen.len(), width * height, "one flag per raster pixel");
        self.add_view(width, height, occluded, (pos, psi), seen, |s, i| s[i], |s, i| s[i] = true);
    }

    /// Adds the pixels of [`Self::view`] to the bitset `bits` (bit `i % 64` of word `i / 64` for
    /// pixel `i`), pushing onto `touched` each word it turns from zero to non-zero. As in
    /// [`Self::view_into`], a pixel already set is passed over before its range and bearing
    /// are computed, which cannot change the union (tested).
    #[allow(clippy::too_many_arguments)]
    pub fn view_into_bits(
        &self,
        width: usize,
        height: usize,
        occluded: impl Fn(i64, i64) -> bool,
        pos: (f64, f64),
        psi: f64,
        bits: &mut [u64],
        touched: &mut Vec<u32>,
    ) {
        assert_eq!(bits.len(), (width * height).div_ceil(64), "one bit per raster pixel");
        self.add_view(
            width,
            height,
            occluded,
            (pos, psi),
            (bits, touched),
            |(bits, _), i| bits[i / 64] >> (i % 64) & 1 == 1,
            |(bits, touched), i| {
                if bits[i / 64] == 0 {
                    touched.push((i / 64) as u32);
                }
                bits[i / 64] |= 1 << (i % 64);
            },
        );
    }

    /// Adds the pixels of the view from `pose` (position, heading) to a union, passing over
    /// the pixels `has` finds in it before their range and bearing are computed.
    #[allow(clippy::too_many_arguments)]
    fn add_view<U>(
        &self,
        width: usize,
        height: usize,
        occluded: impl Fn(i64, i64) -> bool,
        pose: ((f64, f64), f64),
        union: U,
        has: impl Fn(&U, usize) -> bool,
        mut add: impl FnMut(&mut U, usize),
    ) {
        let union = std::cell::RefCell::new(union);
        let (pos, psi) = pose;
        self.view_filtered(
            width,
            height,
            occluded,
            pos,
            psi,
            true,
            true,
            |i| has(&union.borrow(), i),
            |i| add(&mut union.borrow_mut(), i),
        );
    }

    /// [`Self::view`]; with `prefilter`, pixels that are certainly out of range or out of the
    /// field of view are passed over before their exact range and bearing (`hypot`, `atan2`)
    /// are computed. The margins are far above rounding (1e-9 relative), so no pixel on a
    /// border is ever passed over: the result is the same either way (tested).
    #[allow(clippy::too_many_arguments)]
    fn view_filtered(
        &self,
        width: usize,
        height: usize,
        occluded: impl Fn(i64, i64) -> bool,
        pos: (f64, f64),
        psi: f64,
        prefilter: bool,
        capped: bool,
        already_seen: impl Fn(usize) -> bool,
        mut visible: impl FnMut(usize),
    ) {
        let frame = Frame::new(self, (width, height), (pos, psi), prefilter, capped);
        let nearest = frame.nearest_occluders(self, &occluded);
        let ((pc, pr), reach, (cols, rows)) = (frame.pixel, frame.reach, (&frame.cols, &frame.rows));
        let limit: Vec<f64> = nearest.iter().map(|&o| d_view(frame.d_max, self.d_min, o)).collect();
        if self.shape == ViewShape::Fan {
            self.fill_fan(width, height, &occluded, pos, psi, &limit, visible);
            return;
        }
        // No pixel farther than the deepest section is seen: its ring lies beyond that depth + ½.
        let deepest = limit.iter().fold(0.0f64, |a, &l| a.max(l));
        let seen_reach = if prefilter { ((deepest + 0.5).floor() as i64 + 1).min(reach) } else { reach };
        let rows =
            (*rows.start()).max(pr - seen_reach).max(0)..=(*rows.end()).min(pr + seen_reach).min(height as i64 - 1);
        let cols =
            (*cols.start()).max(pc - seen_reach).max(0)..=(*cols.end()).min(pc + seen_reach).min(width as i64 - 1);
        for r in rows {
            // Nor any outside the field of view's wedge.
            let (lo, hi) = frame.wedge.as_ref().map_or((i64::MIN, i64::MAX), |w| w.cols(r, deepest + 1.0));
            for c in (*cols.start()).max(lo)..=(*cols.end()).min(hi) {
                if occluded(c, r) || already_seen(r as usize * width + c as usize) || frame.passed_over(c, r) {
                    continue;
                }
                let (d, phi) = frame.polar(c, r);
                if let Some(i) = self.section(phi)
                    && d >= self.d_min
                    && d <= limit[i]
                    && d < nearest[i]
                {
                    visible(r as usize * width + c as usize);
                }
            }
        }
    }
}

impl Camera {
    /// The polygon of [`ViewShape::Fan`] for depths `limit` (px): ray ends at bearings
    /// `−θ_fov/2 + i·θ_fov/m`, then the `d_min` points of the last and first rays.
    pub fn fan_polygon(&self, pos: (f64, f64), psi: f64, limit: &[f64]) -> Vec<(f64, f64)> {
        let step = self.fov / self.sections as f64;
        let at = |bearing: f64, range: f64| {
            let a = psi - 0.5 * self.fov + bearing;
            (pos.0 + range * a.cos(), pos.1 + range * a.sin())
        };
        let mut poly: Vec<(f64, f64)> = limit.iter().enumerate().map(|(i, &d)| at(i as f64 * step, d)).collect();
        poly.push(at((self.sections - 1) as f64 * step, self.d_min));
        poly.push(at(0.0, self.d_min));
        poly
    }

    /// Calls `visible` for every explorable pixel whose centre lies inside the fan polygon
    /// (even–odd rule, one scanline per pixel row).
    #[allow(clippy::too_many_arguments)]
    fn fill_fan(
        &self,
        width: usize,
        height: usize,
        occluded: &impl Fn(i64, i64) -> bool,
        pos: (f64, f64),
        psi: f64,
        limit: &[f64],
        mut visible: impl FnMut(usize),
    ) {
        let poly = self.fan_polygon(pos, psi, limit);
        let (lo, hi) = poly.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p.1), h.max(p.1)));
        let mut xs = Vec::with_capacity(poly.len());
        let rows = (lo.floor().max(0.0) as i64)..=(hi.ceil().min(height as f64 - 1.0) as i64);
        for r in rows {
            let y = r as f64 + 0.5;
            xs.clear();
            for (k, a) in poly.iter().enumerate() {
                let b = poly[(k + 1) % poly.len()];
                if (a.1 <= y) != (b.1 <= y) {
                    xs.push(a.0 + (y - a.1) * (b.0 - a.0) / (b.1 - a.1));
                }
            }
            xs.sort_by(f64::total_cmp);
            for span in xs.chunks_exact(2) {
                let first = (span[0] - 0.5).ceil().max(0.0) as i64;
                let last = ((span[1] - 0.5).floor()).min(width as f64 - 1.0) as i64;
                for c in first..=last {
                    if !occluded(c, r) {
                        visible(r as usize * width + c as usize);
                    }
                }
            }
        }
    }
}

mod frame;
mod sector;
#[cfg(test)]
mod tests;
