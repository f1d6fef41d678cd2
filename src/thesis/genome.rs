//! The action genome (003 §3.2, thesis-ga §2) and its decoding with out-of-bounds correction
//! (003 eqs. 3.7–3.8, §3.3.4, Fig. 3.8; R1, R8).
//!
//! A genome is `S, AC_2, …, AC_{n−1}, E` stored as moves `(alpha_deg, dist_m)`. S sits at the
//! fixed start and carries an evolvable move; the action at `n − 2` is the connector whose move
//! is always recomputed to end at the fixed end station E; E carries no move. Live genes are
//! indices `0 ..= n − 3`.

use crate::geom::{Point, Vector, ZERO_LENGTH, direction_deg, polar_deg};
use rand::Rng;
use serde::Serialize;

/// One action: a move of `dist_m` metres in direction `alpha_deg` degrees from +x.
///
/// The unit vector of the heading is computed once, when the heading is set, so decoding a
/// genome needs no trigonometry for genes it has decoded before; the fields are private to
/// keep it in step with the heading.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Action {
    alpha_deg: f64,
    dist_m: f64,
    #[serde(skip)]
    direction: Vector,
}

impl Action {
    /// The move of `dist_m` metres in direction `alpha_deg` (degrees, in [0, 360)).
    pub fn new(alpha_deg: f64, dist_m: f64) -> Self {
        Self { alpha_deg, dist_m, direction: direction_deg(alpha_deg) }
    }
    /// The same heading with another distance.
    pub fn with_dist(self, dist_m: f64) -> Self {
        Self { dist_m, ..self }
    }
    /// `AC_α` in degrees, in [0, 360).
    pub fn alpha_deg(&self) -> f64 {
        self.alpha_deg
    }
    /// `AC_dist` in metres, ≥ 0.
    pub fn dist_m(&self) -> f64 {
        self.dist_m
    }
    /// The unit vector of the heading (003 eq. 3.7), as [`direction_deg`] gives it.
    pub fn direction(&self) -> Vector {
        self.direction
    }
    /// A zero action: `AC_dist < 1e-9` m (R18).
    pub fn is_zero(&self) -> bool {
        self.dist_m < ZERO_LENGTH
    }
}

/// The smallest genome: S, the connector and E (thesis-ga §2.1).
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
    /// A frame whose clamping rectangle is `[min, max]` shrunk to the viewpoint lattice, so
    /// that clamped viewpoints are lattice points too (see [`snap`]).
    pub fn new(start: Point, end: Point, min: Point, max: Point) -> Self {
        let inward = |v: f64, up: bool| {
            let s = snap(v);
            if up && s < v {
                s + LATTICE_M
            } else if !up && s > v {
                s - LATTICE_M
            } else {
                s
            }
        };
        Self {
            start,
            end,
            min: Point::new(inward(min.x, true), inward(min.y, true)),
            max: Point::new(inward(max.x, false), inward(max.y, false)),
        }
    }

    fn clamp(&self, p: Point) -> Point {
        Point::new(p.x.clamp(self.min.x, self.max.x), p.y.clamp(self.min.y, self.max.y))
    }
}

/// Spacing of the viewpoint lattice: 2⁻³⁶ m ≈ 1.5·10⁻¹¹ m.
pub const LATTICE_M: f64 = 1.0 / (1u64 << 36) as f64;

/// Rounds a coordinate to the nearest multiple of [`LATTICE_M`] (ties to even).
///
/// Decoded viewpoints live on this lattice so that a move re-aimed at a viewpoint lands on it
/// bit for bit: `p + polar(q − p)` reproduces `q` only up to a rounding error of about
/// `10⁻¹⁵·|q − p|`, far below half the lattice spacing, and snapping removes it. Genes that a
/// crossover copied therefore decode to exactly the viewpoints they had in the parent, which is
/// what lets a child be evaluated as its parent plus the changed segments. The lattice is
/// eleven orders of magnitude below any cell size and moves no viewpoint meaningfully.
/// Coordinates beyond ±32 km are left as they are.
#[inline(always)]
pub fn snap(x: f64) -> f64 {
    const SCALE: f64 = (1u64 << 36) as f64;
    // Adding and removing 1.5·2⁵² rounds to the nearest integer in one addition each.
    const MAGIC: f64 = 6_755_399_441_055_744.0;
    let v = x * SCALE;
    if v.abs() < 2_251_799_813_685_248.0 { ((v + MAGIC) - MAGIC) / SCALE } else { x }
}

/// A point with both coordinates on the viewpoint lattice.
#[inline(always)]
fn snap_point(p: Point) -> Point {
    Point::new(snap(p.x), snap(p.y))
}

/// Index range of the live genes of a genome of length `n` (`0 ..= n − 3`).
pub fn live(n: usize) -> std::ops::Range<usize> {
    0..n.saturating_sub(2)
}

/// Decodes viewpoints up to `upto` with out-of-bounds correction and writes the corrected
/// moves of the genes decoded back (thesis-ga §2.2, R8): the unclamped chain
/// `q_{i+1} = q_i + d_i·dist_i` (eq. 3.8) is followed on the viewpoint lattice ([`snap`]),
/// every point is clamped to the map,
/// and each move whose start or end was changed is re-derived, so the next action still
/// starts from its originally intended place where possible.
///
/// `points` holds the viewpoints already known and receives the rest: `[S]` to decode from the
/// start, or viewpoints `0 ..= k` of a genome whose first `k` genes equal (bit for bit) those of
/// a genome with a stable prefix of at least `k` genes (see [`decode`]), `k ≤ upto`; both give
/// the same result.
pub fn decode_prefix(genome: &mut [Action], frame: &Frame, upto: usize, points: &mut Vec<Point>) {
    debug_assert!(!points.is_empty() && points.len() <= upto + 1 && upto <= genome.len() - 2);
    decode_span(genome, frame, upto, points);
}

/// Continues [`decode_prefix`] from the last of `points` (the viewpoints of a stable prefix,
/// see [`decode`]) up to viewpoint `upto`. Returns the length of the stable prefix after it.
///
/// A gene decoded without correction re-decodes with the same arithmetic on the same inputs. A
/// re-derived gene is stable when decoding its new move from its start lands on its viewpoint
/// bit for bit (the lattice makes this the rule; a re-derived move shorter than a zero action
/// is the exception, as it would not move at all when decoded again).
fn decode_span(genome: &mut [Action], frame: &Frame, upto: usize, points: &mut Vec<Point>) -> usize {
    let from = points.len() - 1;
    let mut q_prev = points[from];
    let mut prev_changed = false;
    let mut stable = from;
    for i in from..upto {
        // A zero action (R18) does not move at all, so deleting it later cannot move the path.
        let q = if genome[i].is_zero() { q_prev } else { snap_point(q_prev + genome[i].direction * genome[i].dist_m) };
        let p = frame.clamp(q);
        let changed = p != q;
        let mut holds = true;
        if changed || prev_changed {
            let (alpha, dist) = polar_deg(p - points[i], genome[i].alpha_deg);
            let gene = Action::new(alpha, dist);
            genome[i] = gene;
            let again = if gene.is_zero() { points[i] } else { snap_point(points[i] + gene.direction * gene.dist_m) };
            holds = again == p;
        }
        if holds && stable == i {
            stable = i + 1;
        }
        points.push(p);
        q_prev = q;
        prev_changed = changed;
    }
    stable
}

/// Decodes the whole genome with correction (thesis-ga §2.2): viewpoints `0 ..= n − 2` as in
/// [`decode_prefix`], the connector's move recomputed to reach E, and E appended. After this,
/// the moves reproduce `points` exactly up to rounding.
///
/// Returns the stable prefix: the number of leading live genes whose corrected moves, decoded
/// again from S, give the same viewpoints bit for bit and need no correction. A genome that
/// shares those genes decodes to the same first viewpoints, so [`decode_from`] may start after
/// them.
pub fn decode(genome: &mut [Action], frame: &Frame, points: &mut Vec<Point>) -> usize {
    points.clear();
    points.push(frame.start);
    decode_from(genome, frame, points, None)
}

/// [`decode`] resumed after a stable prefix: `points` holds viewpoints `0 ..= k` of a genome
/// whose first `k` genes equal (bit for bit) the first `k` of a genome with a stable prefix of
/// at least `k` genes, `k ≤ n − 2`. The result equals [`decode`]'s, the returned stable prefix
/// included.
///
/// `connector`: the last live viewpoint and the connector of a genome decoded in the same
/// frame (the receiving parent's). A connector from the same viewpoint is the same move unless
/// it has zero length (it then keeps its own heading), so it is copied instead of derived.
pub fn decode_from(
    genome: &mut [Action],
    frame: &Frame,
    points: &mut Vec<Point>,
    connector: Option<(Point, Action)>,
) -> usize {
    let n = genome.len();
    debug_assert!(n >= MIN_GENOME_LEN && !points.is_empty() && points.len() < n);
    // The gene right after a clamped point is re-derived inside decode_span for i < n − 2;
    // the connector is re-derived unconditionally below.
    let stable = decode_span(genome, frame, n - 2, points);
    let last = points[n - 2];
    genome[n - 2] = match connector {
        Some((from, known)) if from == last && !known.is_zero() => known,
        _ => {
            let (alpha, dist) = polar_deg(frame.end - last, genome[n - 2].alpha_deg);
            Action::new(alpha, dist)
        }
    };
    genome[n - 1] = genome[n - 1].with_dist(0.0);
    points.push(frame.end);
    stable
}

/// Whether two actions are the same bit for bit (the direction follows from the heading).
pub fn same_bits(a: &Action, b: &Action) -> bool {
    (a.alpha_deg.to_bits() == b.alpha_deg.to_bits()) & (a.dist_m.to_bits() == b.dist_m.to_bits())
}

/// Sets the move of gene `i` so that it goes from `from` to `to` (used by crossover patches).
pub fn set_move(genome: &mut [Action], i: usize, from: Point, to: Point) {
    let (alpha, dist) = polar_deg(to - from, genome[i].alpha_deg);
    genome[i] = Action::new(alpha, dist);
}

/// A random action: `α ~ U[0, 360)` degrees, `dist ~ U[0, dist_max]` metres (003 §3.3.1,
/// thesis-ga §6, R2).
pub fn random_action<R: Rng + ?Sized>(rng: &mut R, dist_max: f64) -> Action {
    let alpha_deg = rng.random_range(0.0..360.0);
    Action::new(alpha_deg, rng.random_range(0.0..=dist_max))
}

/// A fresh random genome (`randInit`, thesis-ga §6): S, `init_actions` random actions (the last of
/// which is the connector) and E, so `G_len = init_actions + 2`. S's move is drawn too.
pub fn random_genome<R: Rng + ?Sized>(rng: &mut R, init_actions: usize, dist_max: f64, out: &mut Vec<Action>) {
    out.clear();
    for _ in 0..=init_actions {
        out.push(random_action(rng, dist_max));
    }
    out.push(Action::new(0.0, 0.0));
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
        Action::new(alpha_deg, dist_m)
    }

    #[test]
    fn decode_follows_eq_3_8_and_connects_to_e() {
        let mut g = vec![a(0.0, 2.0), a(90.0, 3.0), a(0.0, 0.0), a(0.0, 0.0)];
        let mut pts = Vec::new();
        decode(&mut g, &frame(), &mut pts);
        let expect = [Point::new(1.3, 1.3), Point::new(3.3, 1.3), Point::new(3.3, 4.3), Point::new(1.3, 1.3)];
        for (p, e) in pts.iter().zip(expect) {
            assert!((p - e).norm() < 1e-10);
        }
        // The connector now points from (3.3, 4.3) back to E.
        assert!((g[2].dist_m() - 13f64.sqrt()).abs() < 1e-10);
        assert_eq!(g[3].dist_m(), 0.0);
    }

    #[test]
    fn out_of_bounds_move_is_shortened_and_the_next_keeps_its_intended_start() {
        // Fig. 3.8: a move leaves the map; it is cut at the edge, and the next move is rebuilt so
        // that the action after it starts where it was meant to.
        let mut g = vec![a(0.0, 12.0), a(90.0, 2.0), a(180.0, 5.0), a(0.0, 0.0), a(0.0, 0.0)];
        let mut pts = Vec::new();
        decode(&mut g, &frame(), &mut pts);
        assert!((pts[1] - Point::new(11.0, 1.3)).norm() < 1e-10, "clamped to the edge");
        // Intended q2 = (13.3, 3.3) → clamped (11, 3.3); q3 = (8.3, 3.3) is inside: kept.
        assert!((pts[2] - Point::new(11.0, 3.3)).norm() < 1e-10);
        assert!((pts[3] - Point::new(8.3, 3.3)).norm() < 1e-10);
        assert!((g[0].dist_m() - 9.7).abs() < 1e-10);
        assert!((g[2].dist_m() - 2.7).abs() < 1e-10 && (g[2].alpha_deg() - 180.0).abs() < 1e-9);
        // Written back: decoding again changes nothing, bit for bit.
        let before = g.clone();
        let mut again = Vec::new();
        decode(&mut g, &frame(), &mut again);
        assert_eq!(pts, again);
        assert_eq!(before, g);
    }

    #[test]
    fn a_connector_of_zero_length_keeps_its_own_heading() {
        // All moves are zero, so the last live viewpoint is S = E and the connector has no
        // direction of its own: polar_deg keeps the connector's heading, not a neighbour's.
        let mut g = vec![a(0.0, 0.0), a(10.0, 0.0), a(20.0, 0.0), a(77.0, 0.0), a(0.0, 0.0)];
        let mut pts = Vec::new();
        decode(&mut g, &frame(), &mut pts);
        assert_eq!(pts, vec![frame().start; 5]);
        assert_eq!((g[3].alpha_deg(), g[3].dist_m()), (77.0, 0.0));
        assert_eq!(g[2].alpha_deg(), 20.0);
    }

    #[test]
    fn a_known_connector_of_zero_length_is_not_copied() {
        // The parent's connector leads from S = E to E: zero length, heading 77°. A child
        // from the same viewpoint with a connector heading 40° keeps its 40°, as decoding it
        // from S does; only a connector of non-zero length is the same move whoever owns it.
        let parent = [a(0.0, 0.0), a(10.0, 0.0), a(20.0, 0.0), a(77.0, 0.0), a(0.0, 0.0)];
        let mut child = parent;
        child[3] = a(40.0, 0.0);
        let start = frame().start;
        let mut pts = vec![start; 4];
        decode_from(&mut child, &frame(), &mut pts, Some((start, parent[3])));
        assert_eq!((child[3].alpha_deg(), child[3].dist_m()), (40.0, 0.0));
        // A known connector of non-zero length from the same viewpoint is copied bit for bit.
        let far = Frame::new(start, Point::new(4.3, 5.3), Point::new(0.0, 0.0), Point::new(11.0, 11.0));
        let mut own = vec![start];
        let mut parent = parent;
        decode(&mut parent, &far, &mut own);
        let mut child = parent;
        child[3] = a(40.0, 0.0);
        let mut pts = vec![start; 4];
        decode_from(&mut child, &far, &mut pts, Some((start, parent[3])));
        assert!(same_bits(&child[3], &parent[3]) && child[3].dist_m() == 5.0, "{:?}", child[3]);
    }

    #[test]
    fn zero_actions_are_those_shorter_than_a_nanometre() {
        // R18: strictly below 1e-9 m.
        for (dist, zero) in [(0.0, true), (0.999e-9, true), (1e-9, false), (1e-6, false)] {
            assert_eq!(a(30.0, dist).is_zero(), zero, "dist {dist}");
        }
    }

    #[test]
    fn snap_rounds_to_the_lattice() {
        assert_eq!(snap(1.3), (1.3 * 68_719_476_736.0f64).round() / 68_719_476_736.0);
        assert_eq!(snap(11.0), 11.0);
        assert_eq!(snap(-12.2), (-12.2 * 68_719_476_736.0f64).round() / 68_719_476_736.0);
        assert_eq!(snap(0.5 * LATTICE_M), 0.0, "ties to even");
        assert_eq!(snap(1e6), 1e6, "beyond the lattice range: unchanged");
        let f = Frame::new(Point::new(0.0, 0.0), Point::new(0.0, 0.0), Point::new(-12.2, 0.1), Point::new(7.7, 9.0));
        assert!(f.min.x >= -12.2 && f.min.x - -12.2 < LATTICE_M && f.max.x <= 7.7 && 7.7 - f.max.x < LATTICE_M);
        assert_eq!((snap(f.min.y), snap(f.max.x)), (f.min.y, f.max.x));
    }

    proptest::proptest! {
        /// The property incremental evaluation relies on: a corrected genome decodes to the
        /// same viewpoints bit for bit, and a move re-aimed at a viewpoint lands on it exactly.
        #[test]
        fn corrected_genomes_decode_to_identical_viewpoints(seed in 0u64..20_000, n in 3usize..80, dist_max in 0.5..30.0f64) {
            let mut rng = crate::ga::rng::stream(seed, crate::ga::rng::Purpose::Main, &[]);
            let mut g = Vec::new();
            random_genome(&mut rng, n - 2, dist_max, &mut g);
            let f = Frame::new(Point::new(1.3, 1.3), Point::new(9.7, 2.1), Point::new(0.0, 0.0), Point::new(11.0, 11.0));
            let (mut first, mut again) = (Vec::new(), Vec::new());
            decode(&mut g, &f, &mut first);
            let corrected = g.clone();
            decode(&mut g, &f, &mut again);
            proptest::prop_assert_eq!(&first, &again);
            proptest::prop_assert_eq!(&corrected, &g);
            // The connector (gene n − 2) leads from the last live viewpoint to E.
            let connector_end = first[n - 2] + g[n - 2].direction() * g[n - 2].dist_m();
            proptest::prop_assert!((connector_end - f.end).norm() < 1e-9, "connector ends at {connector_end}");
            // Re-aim gene 0 at viewpoint j and append the rest from j: it lands on it exactly.
            let j = rng.random_range(1..n - 1);
            let mut child: Vec<Action> = std::iter::once(g[0]).chain(g[j..].iter().copied()).collect();
            set_move(&mut child, 0, first[0], first[j]);
            let mut pts = Vec::new();
            decode(&mut child, &f, &mut pts);
            proptest::prop_assert_eq!(&pts[1..], &first[j..]);
        }
    }

    #[test]
    fn a_re_derived_move_shorter_than_a_zero_action_ends_the_stable_prefix() {
        // Gene 0 leaves the map and is cut at x = 11 (stable: decoded again it lands there).
        // Gene 1 was meant to start at the unclamped x = 13.3 and end 0.5 nm inside the edge;
        // re-aimed from the cut point it is 0.5 nm long, a zero action, which decoded again
        // would not move: the stable prefix ends before it.
        let mut g = vec![a(0.0, 12.0), a(180.0, 2.3 + 5e-10), a(90.0, 1.0), a(0.0, 0.0), a(0.0, 0.0)];
        let mut pts = Vec::new();
        assert_eq!(decode(&mut g, &frame(), &mut pts), 1);
        assert_eq!(pts[1], Point::new(11.0, snap(1.3)));
        assert!(g[1].is_zero() && pts[2] != pts[1]);
        let mut again = Vec::new();
        decode(&mut g, &frame(), &mut again);
        assert_eq!(again[2], pts[1], "decoded again, the zero action stays put: not the same path");
        // Without the cut, every gene is stable.
        let mut inside = vec![a(0.0, 2.0), a(90.0, 3.0), a(180.0, 1.0), a(0.0, 0.0), a(0.0, 0.0)];
        assert_eq!(decode(&mut inside, &frame(), &mut pts), 3);
    }

    proptest::proptest! {
        /// A genome that shares a stable prefix with a decoded one, decoded from the end of
        /// the shared genes, equals its decoding from S: viewpoints, corrected moves and stable
        /// prefix.
        #[test]
        fn decoding_from_a_stable_prefix_equals_decoding_from_s(seed in 0u64..20_000, n in 3usize..60, m in 3usize..60, dist_max in 0.5..30.0f64) {
            let mut rng = crate::ga::rng::stream(seed, crate::ga::rng::Purpose::Main, &[]);
            let f = Frame::new(Point::new(1.3, 1.3), Point::new(9.7, 2.1), Point::new(0.0, 0.0), Point::new(11.0, 11.0));
            let mut parent = Vec::new();
            random_genome(&mut rng, n - 2, dist_max, &mut parent);
            let mut points = Vec::new();
            let stable = decode(&mut parent, &f, &mut points);
            proptest::prop_assert!(stable <= n - 2);
            // The child: the parent's first k genes, then genes of its own.
            let k = rng.random_range(0..=stable.min(m - 2));
            let mut tail = Vec::new();
            random_genome(&mut rng, m - 2, dist_max, &mut tail);
            let child: Vec<Action> = parent[..k].iter().chain(&tail[k..]).copied().collect();
            let (mut whole, mut resumed) = (child.clone(), child);
            let mut from_s = Vec::new();
            let s_whole = decode(&mut whole, &f, &mut from_s);
            let connector = Some((points[n - 2], parent[n - 2]));
            let mut from_k = points[..=k].to_vec();
            let s_resumed = decode_from(&mut resumed, &f, &mut from_k, connector);
            proptest::prop_assert_eq!(from_s, from_k);
            proptest::prop_assert_eq!(whole, resumed);
            proptest::prop_assert_eq!(s_whole, s_resumed);
            // The parent itself, resumed after its stable prefix with its own connector given.
            let mut again = parent.clone();
            let mut from_stable = points[..=stable].to_vec();
            let mut from_s = Vec::new();
            let mut fresh = parent.clone();
            proptest::prop_assert_eq!(decode_from(&mut again, &f, &mut from_stable, connector), decode(&mut fresh, &f, &mut from_s));
            proptest::prop_assert_eq!(again, fresh);
            proptest::prop_assert_eq!(from_stable, from_s);
        }
    }

    #[test]
    fn random_genome_has_init_plus_two_actions() {
        let mut rng = crate::ga::rng::stream(5, crate::ga::rng::Purpose::Main, &[]);
        let mut g = Vec::new();
        random_genome(&mut rng, 50, 50.0, &mut g);
        assert_eq!(g.len(), 52);
        assert!(g.iter().all(|x| (0.0..360.0).contains(&x.alpha_deg()) && (0.0..=50.0).contains(&x.dist_m())));
        assert_eq!(live(52), 0..50);
    }
}
