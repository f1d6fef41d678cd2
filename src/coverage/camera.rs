//! The camera coverage model of 000 (§II-C.1, eq. 1, Fig. 4; spec §5, W8–W9): a forward
//! camera with depth range `[d_min, d_max]` and horizontal field of view `θ_fov`, split into
//! `m` angular sections; each section sees up to its first obstacle.

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

    /// Calls `visible(index)` for every explorable pixel seen from `pos` (px) with heading `psi`:
    /// in the field of view, at range `d_min ≤ r ≤ d_view` of its section. `occluded(col, row)`
    /// must be true outside the raster.
    pub fn view(
        &self,
        width: usize,
        height: usize,
        occluded: impl Fn(i64, i64) -> bool,
        pos: (f64, f64),
        psi: f64,
        mut visible: impl FnMut(usize),
    ) {
        let reach = self.d_max.ceil() as i64 + 1;
        let (pc, pr) = (pos.0.floor() as i64, pos.1.floor() as i64);
        let mut nearest = vec![f64::INFINITY; self.sections];
        let polar = |c: i64, r: i64| {
            let (dx, dy) = (c as f64 + 0.5 - pos.0, r as f64 + 0.5 - pos.1);
            (dx.hypot(dy), wrap(dy.atan2(dx) - psi))
        };
        for r in pr - reach..=pr + reach {
            for c in pc - reach..=pc + reach {
                if occluded(c, r) {
                    let (d, phi) = polar(c, r);
                    if d <= self.d_max
                        && let Some(i) = self.section(phi)
                    {
                        nearest[i] = nearest[i].min(d);
                    }
                }
            }
        }
        let limit: Vec<f64> = nearest.iter().map(|&o| d_view(self.d_max, self.d_min, o)).collect();
        for r in (pr - reach).max(0)..=(pr + reach).min(height as i64 - 1) {
            for c in (pc - reach).max(0)..=(pc + reach).min(width as i64 - 1) {
                if occluded(c, r) {
                    continue;
                }
                let (d, phi) = polar(c, r);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> Camera {
        Camera { d_min: 1.0, d_max: 20.0, fov: 60f64.to_radians(), sections: 7 }
    }

    #[test]
    fn eq_1_cuts_each_section_at_its_obstacle() {
        assert_eq!(d_view(20.0, 1.0, f64::INFINITY), 20.0);
        assert_eq!(d_view(20.0, 1.0, 5.0), 5.0);
        assert_eq!(d_view(20.0, 1.0, 0.5), 1.0);
        assert_eq!(cam().section(0.0), Some(3));
        assert_eq!(cam().section(-30f64.to_radians()), Some(0));
        assert_eq!(cam().section(30f64.to_radians()), Some(6));
        assert_eq!(cam().section(31f64.to_radians()), None);
    }

    #[test]
    fn a_camera_facing_a_wall_sees_nothing_behind_it() {
        // 40 x 40 free raster with a wall at column 20; camera at (10.5, 20.5) facing +x.
        let (w, h) = (40usize, 40usize);
        let occ = |c: i64, r: i64| c < 0 || r < 0 || c >= w as i64 || r >= h as i64 || c == 20;
        let mut seen = Vec::new();
        cam().view(w, h, occ, (10.5, 20.5), 0.0, |i| seen.push(i));
        assert!(!seen.is_empty());
        assert!(seen.iter().all(|&i| i % w < 20), "nothing at or behind the wall");
        assert!(seen.iter().any(|&i| i % w == 19), "up to the wall");
        // Facing away from the wall it sees the open side only, up to d_max.
        let mut back = Vec::new();
        cam().view(w, h, occ, (10.5, 20.5), std::f64::consts::PI, |i| back.push(i));
        assert!(back.iter().all(|&i| i % w <= 10));
        // Nothing closer than d_min.
        assert!(seen.iter().all(|&i| ((i % w) as f64 + 0.5 - 10.5).hypot((i / w) as f64 + 0.5 - 20.5) >= 1.0));
    }
}
