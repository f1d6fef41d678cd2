//! The action genome (003 §3.2, spec §2) and its decoding with out-of-bounds correction
//! (003 eqs. 3.7–3.8, §3.3.4, Fig. 3.8; spec R1, R8).
//!
//! A genome is `S, AC_2, …, AC_{n−1}, E` stored as moves `(alpha_deg, dist_m)`. S sits at the
//! fixed start and carries an evolvable move; the action at `n − 2` is the connector whose move
//! is always recomputed to end at the fixed end station E; E carries no move. Live genes are
//! indices `0 ..= n − 3`.

use crate::geom::{Point, ZERO_LENGTH, direction_deg, polar_deg};
use rand::Rng;
use serde::Serialize;

/// One action: a move of `dist_m` metres in direction `alpha_deg` degrees from +x.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Action {
    /// `AC_α` in degrees, in [0, 360).
    pub alpha_deg: f64,
    /// `AC_dist` in metres, ≥ 0.
    pub dist_m: f64,
}

impl Action {
    /// A zero action: `AC_dist < 1e-9` m (spec R18).
    pub fn is_zero(&self) -> bool {
        self.dist_m < ZERO_LENGTH
    }
}

/// The smallest genome: S, the connector and E (spec §2.1).
pub const MIN_GENOME_LEN: usize = 3;

/// The fixed frame a genome is decoded in: stations and the map rectangle for clamping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// `S_pos`.
    pub start: Point,
    /// `E_pos`.
    pub end: Point,
    /// Lower-left corner of the map rectangle.
    pub min: Point,
    /// Upper-right corner of the map rectangle.
    pub max: Point,
}

impl Frame {
    fn clamp(&self, p: Point) -> Point {
        Point::new(p.x.clamp(self.min.x, self.max.x), p.y.clamp(self.min.y, self.max.y))
    }
}

/// Index range of the live genes of a genome of length `n` (`0 ..= n − 3`).
pub fn live(n: usize) -> std::ops::Range<usize> {
    0..n.saturating_sub(2)
}

/// Decodes the first `upto + 1` viewpoints with out-of-bounds correction and writes the
/// corrected moves of genes `0 .. upto` back (spec §2.2, R8): the unclamped chain
/// `q_{i+1} = q_i + d_i·dist_i` (eq. 3.8) is followed, every point is clamped to the map,
/// and each move whose start or end was changed is re-derived, so the next action still
/// starts from its originally intended place where possible. `points` receives the viewpoints.
pub fn decode_prefix(genome: &mut [Action], frame: &Frame, upto: usize, points: &mut Vec<Point>) {
    let n = genome.len();
    debug_assert!(n >= MIN_GENOME_LEN && upto <= n - 2);
    points.clear();
    points.push(frame.start);
    let mut q_prev = frame.start;
    let mut prev_changed = false;
    for i in 0..upto {
        let q = q_prev + direction_deg(genome[i].alpha_deg) * genome[i].dist_m;
        let p = frame.clamp(q);
        let changed = p != q;
        if changed || prev_changed {
            let (alpha, dist) = polar_deg(p - points[i], genome[i].alpha_deg);
            genome[i] = Action { alpha_deg: alpha, dist_m: dist };
        }
        points.push(p);
        q_prev = q;
        prev_changed = changed;
    }
}

/// Decodes the whole genome with correction (spec §2.2): viewpoints `0 ..= n − 2` as in
/// [`decode_prefix`], the connector's move recomputed to reach E, and E appended. After this,
/// the moves reproduce `points` exactly up to rounding.
pub fn decode(genome: &mut [Action], frame: &Frame, points: &mut Vec<Point>) {
    let n = genome.len();
    // The gene right after a clamped point is re-derived inside decode_prefix for i < n − 2;
    // the connector is re-derived unconditionally below.
    decode_prefix(genome, frame, n - 2, points);
    let last = points[n - 2];
    let (alpha, dist) = polar_deg(frame.end - last, genome[n - 2].alpha_deg);
    genome[n - 2] = Action { alpha_deg: alpha, dist_m: dist };
    genome[n - 1] = Action { alpha_deg: genome[n - 1].alpha_deg, dist_m: 0.0 };
    points.push(frame.end);
}

/// Sets the move of gene `i` so that it goes from `from` to `to` (used by crossover patches).
pub fn set_move(genome: &mut [Action], i: usize, from: Point, to: Point) {
    let (alpha, dist) = polar_deg(to - from, genome[i].alpha_deg);
    genome[i] = Action { alpha_deg: alpha, dist_m: dist };
}

/// A random action: `α ~ U[0, 360)` degrees, `dist ~ U[0, dist_max]` metres (003 §3.3.1,
/// spec §6, R2).
pub fn random_action<R: Rng + ?Sized>(rng: &mut R, dist_max: f64) -> Action {
    Action { alpha_deg: rng.random_range(0.0..360.0), dist_m: rng.random_range(0.0..=dist_max) }
}

/// A fresh random genome (`randInit`, spec §6): S, `init_actions` random actions (the last of
/// which is the connector) and E, so `G_len = init_actions + 2`. S's move is drawn too.
pub fn random_genome<R: Rng + ?Sized>(rng: &mut R, init_actions: usize, dist_max: f64, out: &mut Vec<Action>) {
    out.clear();
    for _ in 0..=init_actions {
        out.push(random_action(rng, dist_max));
    }
    out.push(Action { alpha_deg: 0.0, dist_m: 0.0 });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> Frame {
        Frame {
            start: Point::new(1.3, 1.3),
            end: Point::new(1.3, 1.3),
            min: Point::new(0.0, 0.0),
            max: Point::new(11.0, 11.0),
        }
    }

    fn a(alpha_deg: f64, dist_m: f64) -> Action {
        Action { alpha_deg, dist_m }
    }

    #[test]
    fn decode_follows_eq_3_8_and_connects_to_e() {
        let mut g = vec![a(0.0, 2.0), a(90.0, 3.0), a(0.0, 0.0), a(0.0, 0.0)];
        let mut pts = Vec::new();
        decode(&mut g, &frame(), &mut pts);
        let expect = [Point::new(1.3, 1.3), Point::new(3.3, 1.3), Point::new(3.3, 4.3), Point::new(1.3, 1.3)];
        for (p, e) in pts.iter().zip(expect) {
            assert!((p - e).norm() < 1e-12);
        }
        // The connector now points from (3.3, 4.3) back to E.
        assert!((g[2].dist_m - 13f64.sqrt()).abs() < 1e-12);
        assert_eq!(g[3].dist_m, 0.0);
    }

    #[test]
    fn out_of_bounds_move_is_shortened_and_the_next_keeps_its_intended_start() {
        // Fig. 3.8: a move leaves the map; it is cut at the edge, and the next move is rebuilt so
        // that the action after it starts where it was meant to.
        let mut g = vec![a(0.0, 12.0), a(90.0, 2.0), a(180.0, 5.0), a(0.0, 0.0), a(0.0, 0.0)];
        let mut pts = Vec::new();
        decode(&mut g, &frame(), &mut pts);
        assert!((pts[1] - Point::new(11.0, 1.3)).norm() < 1e-12, "clamped to the edge");
        // Intended q2 = (13.3, 3.3) → clamped (11, 3.3); q3 = (8.3, 3.3) is inside: kept.
        assert!((pts[2] - Point::new(11.0, 3.3)).norm() < 1e-12);
        assert!((pts[3] - Point::new(8.3, 3.3)).norm() < 1e-12);
        assert!((g[0].dist_m - 9.7).abs() < 1e-12);
        assert!((g[2].dist_m - 2.7).abs() < 1e-12 && (g[2].alpha_deg - 180.0).abs() < 1e-9);
        // Written back: decoding again changes nothing.
        let before = g.clone();
        let mut again = Vec::new();
        decode(&mut g, &frame(), &mut again);
        for (x, y) in pts.iter().zip(&again) {
            assert!((x - y).norm() < 1e-9);
        }
        for (x, y) in before.iter().zip(&g) {
            assert!((x.dist_m - y.dist_m).abs() < 1e-9);
        }
    }

    #[test]
    fn random_genome_has_init_plus_two_actions() {
        let mut rng = crate::ga::rng::stream(5, crate::ga::rng::Purpose::Main, &[]);
        let mut g = Vec::new();
        random_genome(&mut rng, 50, 50.0, &mut g);
        assert_eq!(g.len(), 52);
        assert!(g.iter().all(|x| (0.0..360.0).contains(&x.alpha_deg) && (0.0..=50.0).contains(&x.dist_m)));
        assert_eq!(live(52), 0..50);
    }
}
