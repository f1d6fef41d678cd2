use super::*;
use crate::map::presets::preset;

#[test]
fn lanes_half_a_width_off_the_wall_fit() {
    let m = preset("thesis-1").unwrap();
    let c = Clearance::new(&m, 0.6);
    assert!(c.fits(Point::new(1.3, 1.3)));
    assert!(!c.fits(Point::new(1.2, 5.0)));
    let iv = c.fitting_intervals(Point::new(0.0, 5.0), Point::new(11.0, 5.0), 0.2);
    assert_eq!(iv.len(), 1);
    assert!((iv[0].0 * 11.0 - 1.3).abs() < 1e-5 && (iv[0].1 * 11.0 - 9.7).abs() < 1e-5);
}

proptest::proptest! {
    /// The row index answers as the scan of the whole window, at random points on and
    /// off the map (cell borders included) of a cluttered map, for several widths and slacks.
    #[test]
    fn row_index_answers_as_the_full_window(
        x in -0.5f64..30.5, y in -0.5f64..20.5, on_border in proptest::bool::ANY,
        width in 0.05f64..1.2, slack in 0.0f64..0.05,
    ) {
        let m = preset("office").unwrap();
        let c = Clearance::new(&m, width);
        let snap = |v: f64| if on_border { (v / m.resolution()).round() * m.resolution() } else { v };
        let p = Point::new(snap(x), snap(y));
        proptest::prop_assert_eq!(c.clear_of_cells_within(p, slack), c.clear_of_cells_within_full(p, slack));
        proptest::prop_assert_eq!(c.nearest_cell_d2(p).to_bits(), c.nearest_cell_d2_full(p).to_bits());
    }
}

#[test]
fn connection_goes_around_the_disc() {
    let m = preset("thesis-2").unwrap();
    let c = Clearance::new(&m, 0.6);
    let (a, b) = (Point::new(2.0, 5.5), Point::new(9.0, 5.5));
    assert!(!c.segment_fits(a, b));
    let route = c.connect(a, b).unwrap();
    assert_eq!(*route.last().unwrap(), b);
    let mut prev = a;
    for &p in &route {
        assert!(c.segment_fits(prev, p));
        prev = p;
    }
}

impl Clearance<'_> {
    /// [`Clearance::nearest_cell_d2`] over every cell of the window, in scan order.
    fn nearest_cell_d2_full(&self, p: Point) -> f64 {
        let m = &*self.map;
        let (ox, oy, res) = (m.origin().x, m.origin().y, m.resolution());
        let (cc, cr) = (((p.x - ox) / res).floor() as isize, ((p.y - oy) / res).floor() as isize);
        let mut best = f64::INFINITY;
        for r in (cr - self.window).max(0)..=(cr + self.window).min(m.rows() as isize - 1) {
            for c in (cc - self.window).max(0)..=(cc + self.window).min(m.cols() as isize - 1) {
                if !m.is_free(r as usize, c as usize) {
                    let (x0, y0) = (ox + c as f64 * res, oy + r as f64 * res);
                    let dx = (x0 - p.x).max(0.0).max(p.x - x0 - res);
                    let dy = (y0 - p.y).max(0.0).max(p.y - y0 - res);
                    best = best.min(dx * dx + dy * dy);
                }
            }
        }
        best
    }

    /// [`Clearance::clear_of_cells_within`] scanning every cell of the window: the reference
    /// for the row index.
    fn clear_of_cells_within_full(&self, p: Point, slack: f64) -> bool {
        let m = &*self.map;
        let (ox, oy, res) = (m.origin().x, m.origin().y, m.resolution());
        let lim = self.radius - CLEARANCE_EPS - slack;
        let (cc, cr) = (((p.x - ox) / res).floor() as isize, ((p.y - oy) / res).floor() as isize);
        for r in (cr - self.window).max(0)..=(cr + self.window).min(m.rows() as isize - 1) {
            for c in (cc - self.window).max(0)..=(cc + self.window).min(m.cols() as isize - 1) {
                if m.is_free(r as usize, c as usize) {
                    continue;
                }
                let (x0, y0) = (ox + c as f64 * res, oy + r as f64 * res);
                let dx = (x0 - p.x).max(0.0).max(p.x - x0 - res);
                let dy = (y0 - p.y).max(0.0).max(p.y - y0 - res);
                if dx * dx + dy * dy < lim * lim {
                    return false;
                }
            }
        }
        true
    }
}
