//! Modified dual-point crossover with locality-changing and locality-preserving children
//! (003 §3.3.2, eqs. 3.20–3.22, Figs. 3.6–3.7; thesis-ga §7, R12–R14).

use super::genome::{Action, Frame, decode_prefix, set_move};
use crate::geom::Point;
use rand::Rng;
use serde::{Deserialize, Serialize};

/// `C_child`: which children a crossover produces (thesis-ga §7.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ChildMode {
    /// `C_child = 0`: two locality-changing children.
    Changing,
    /// `C_child = 1`: two locality-preserving children.
    Preserving,
    /// `C_child = 2`: both interpretations of the same cut points, four children.
    Both,
}

impl ChildMode {
    /// From the thesis's number 0, 1, 2.
    pub fn from_index(i: u8) -> Option<Self> {
        [ChildMode::Changing, ChildMode::Preserving, ChildMode::Both].get(i as usize).copied()
    }
    /// The thesis's number.
    pub fn index(self) -> u8 {
        self as u8
    }
    /// Children per crossover.
    pub fn children(self) -> usize {
        if self == ChildMode::Both { 4 } else { 2 }
    }
}

/// `absShare = max(1, ⌊C_len·G_len⌋)` (003 eq. 3.20, integer form of R12).
pub fn abs_share(n: usize, c_len: f64) -> usize {
    ((c_len * n as f64).floor() as usize).max(1)
}

/// What crossover does with parents too short for the cut-point ranges of 003 eqs. 3.21–3.22.
///
/// Read literally, those equations leave two traps for short genomes. When `C_len·n < 2` the
/// block of eq. 3.22 is always one gene long, so both children keep their parents' lengths and
/// crossover can no longer change a genome's length. When `n < absShare + 3` the range of
/// `CP_1` is empty and there is no crossover at all; with Elite families and `P_mI = 0` a
/// population of such genomes then stops changing (with `C_len = 0.8` and 50 m initial moves,
/// evaluations stop at iteration ~100). The thesis does not say what its operator does there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShortGenomes {
    /// The default: the block bound is clamped into `[2, n − 3]` ([`clamped_share`]), so every
    /// parent with at least one live gene after the first can cross, and blocks of one or two
    /// genes let lengths change. Genomes long enough for eqs. 3.21–3.22 are untouched.
    #[default]
    Clamp,
    /// eqs. 3.20–3.22 as printed (R12): one-gene blocks when `C_len·n < 2`, no crossover
    /// when `n < absShare + 3`.
    Literal,
}

impl ShortGenomes {
    /// The name as written in experiment files.
    pub fn name(self) -> &'static str {
        match self {
            ShortGenomes::Clamp => "clamp",
            ShortGenomes::Literal => "literal",
        }
    }

    /// The block bound used for a parent of length `n`; `None` when it cannot cross.
    pub fn share(self, n: usize, c_len: f64) -> Option<usize> {
        match self {
            ShortGenomes::Literal => Some(abs_share(n, c_len)).filter(|&share| n >= share + 3),
            ShortGenomes::Clamp => clamped_share(n, c_len),
        }
    }
}

/// `absShare` clamped into `[2, n − 3]` (`[1, 1]` for `n = 4`): the largest bound for which the
/// `CP_1` range of eq. 3.21 is not empty, and at least two so that blocks of different lengths
/// exist. `None` for `n < 4`, where no gene lies strictly between the first gene and the
/// connector.
pub fn clamped_share(n: usize, c_len: f64) -> Option<usize> {
    if n < 4 {
        return None;
    }
    Some(abs_share(n, c_len).max(2).min(n - 3))
}

/// Draws a shared block for a parent of length `n` (003 eqs. 3.21–3.22, 1-based
/// `CP_1 ∈ {2, …, n − absShare − 1}`, `CP_2 ∈ {CP_1 + 1, …, CP_1 + absShare}`), returned
/// 0-based half-open as `[CP_1 − 1, CP_2 − 1)`, with `absShare` from `short`. `None` when the
/// parent cannot cross.
pub fn draw_block<R: Rng + ?Sized>(n: usize, c_len: f64, short: ShortGenomes, rng: &mut R) -> Option<(usize, usize)> {
    let share = short.share(n, c_len)?;
    let cp1 = rng.random_range(2..=n - share - 1);
    let cp2 = rng.random_range(cp1 + 1..=cp1 + share);
    Some((cp1 - 1, cp2 - 1))
}

/// A parent as crossover sees it: its genome and decoded viewpoints.
#[derive(Clone, Copy, Debug)]
pub struct Parent<'a> {
    /// The genome.
    pub genome: &'a [Action],
    /// Its decoded, corrected viewpoints.
    pub points: &'a [Point],
    /// Its stable prefix (see [`super::genome::decode`]): a child that starts with these genes
    /// is decoded from the end of the ones it shares. 0 is always safe.
    pub stable: usize,
}

/// Where [`crossover_into`] writes a child: its genome and room for viewpoints, both reused
/// (a recycled member's buffers).
pub trait ChildBuffers {
    /// The child's genome (overwritten) and a viewpoint scratch (overwritten; of no use after).
    fn buffers(&mut self) -> (&mut Vec<Action>, &mut Vec<Point>);
}

impl ChildBuffers for (Vec<Action>, Vec<Point>) {
    fn buffers(&mut self) -> (&mut Vec<Action>, &mut Vec<Point>) {
        (&mut self.0, &mut self.1)
    }
}

/// Writes `a[..a0] ++ b[b0..b1] ++ a[a1..]` into `child`.
fn splice_into(
    child: &mut Vec<Action>,
    a: &[Action],
    (a0, a1): (usize, usize),
    b: &[Action],
    (b0, b1): (usize, usize),
) {
    child.clear();
    child.extend_from_slice(&a[..a0]);
    child.extend_from_slice(&b[b0..b1]);
    child.extend_from_slice(&a[a1..]);
}

/// Locality-changing child of receiver `a` with donor block `b[b0..b1]` (thesis-ga §7.3): the
/// inserted genes keep their relative moves; the first gene after the block is re-aimed at the
/// receiver's next viewpoint, so the rest of the receiver stays in place.
pub fn changing_child(
    a: Parent,
    block_a: (usize, usize),
    b: Parent,
    block_b: (usize, usize),
    frame: &Frame,
) -> Vec<Action> {
    let mut child = Vec::new();
    changing_child_into(a, block_a, b, block_b, frame, &mut child, &mut Vec::new());
    child
}

/// [`changing_child`] written into `child`, with `points` as the viewpoint scratch.
pub fn changing_child_into(
    a: Parent,
    (a0, a1): (usize, usize),
    b: Parent,
    (b0, b1): (usize, usize),
    frame: &Frame,
    child: &mut Vec<Action>,
    points: &mut Vec<Point>,
) {
    splice_into(child, a.genome, (a0, a1), b.genome, (b0, b1));
    let k = a0 + (b1 - b0);
    if k < child.len() - 2 {
        // The child starts with the receiver's genes 0 .. a0: those of its stable prefix
        // decode to its viewpoints.
        let shared = a0.min(a.stable);
        points.clear();
        points.push(frame.start);
        points.extend_from_slice(&a.points[1..=shared]);
        decode_prefix(child, frame, k, points);
        set_move(child, k, points[k], a.points[a1 + 1]);
    }
}

/// Locality-preserving child (thesis-ga §7.4): the inserted genes keep the donor's absolute
/// viewpoints; the gene before the block is re-aimed at the donor block's start and the gene
/// after it from the block's end to the receiver's next viewpoint.
pub fn preserving_child(a: Parent, block_a: (usize, usize), b: Parent, block_b: (usize, usize)) -> Vec<Action> {
    let mut child = Vec::new();
    preserving_child_into(a, block_a, b, block_b, &mut child);
    child
}

/// [`preserving_child`] written into `child`.
pub fn preserving_child_into(
    a: Parent,
    (a0, a1): (usize, usize),
    b: Parent,
    (b0, b1): (usize, usize),
    child: &mut Vec<Action>,
) {
    splice_into(child, a.genome, (a0, a1), b.genome, (b0, b1));
    set_move(child, a0 - 1, a.points[a0 - 1], b.points[b0]);
    let k = a0 + (b1 - b0);
    if k < child.len() - 2 {
        set_move(child, k, b.points[b1], a.points[a1 + 1]);
    }
}

/// Crossover of two parents (thesis-ga §7): draws blocks for both, redrawing up to 10 times while a
/// child would exceed `max_len` (R14); `None` means "no crossover" (children = copies).
#[allow(clippy::too_many_arguments)]
pub fn crossover<R: Rng + ?Sized>(
    a: Parent,
    b: Parent,
    c_len: f64,
    short: ShortGenomes,
    mode: ChildMode,
    max_len: usize,
    frame: &Frame,
    rng: &mut R,
) -> Option<Vec<Vec<Action>>> {
    let mut kids = vec![(Vec::new(), Vec::new()); mode.children()];
    crossover_into(a, b, c_len, short, mode, max_len, frame, rng, &mut kids)
        .then(|| kids.into_iter().map(|(genome, _)| genome).collect())
}

/// [`crossover`] written into `kids`, one per child (`mode.children()` of them), in the order
/// changing A←B, changing B←A, preserving A←B, preserving B←A (those of `mode`). Returns
/// false when no child could be made; `kids` then hold nothing of use. Draws exactly what
/// [`crossover`] draws.
#[allow(clippy::too_many_arguments)]
pub fn crossover_into<R: Rng + ?Sized, K: ChildBuffers>(
    a: Parent,
    b: Parent,
    c_len: f64,
    short: ShortGenomes,
    mode: ChildMode,
    max_len: usize,
    frame: &Frame,
    rng: &mut R,
    kids: &mut [K],
) -> bool {
    assert_eq!(kids.len(), mode.children(), "one buffer per child");
    let (na, nb) = (a.genome.len(), b.genome.len());
    for _ in 0..10 {
        let Some(ba) = draw_block(na, c_len, short, rng) else { return false };
        let Some(bb) = draw_block(nb, c_len, short, rng) else { return false };
        let (la, lb) = (ba.1 - ba.0, bb.1 - bb.0);
        if na - la + lb > max_len || nb - lb + la > max_len {
            continue;
        }
        let mut slots = kids.iter_mut().map(ChildBuffers::buffers);
        if mode != ChildMode::Preserving {
            let (child, points) = slots.next().expect("a buffer per child");
            changing_child_into(a, ba, b, bb, frame, child, points);
            let (child, points) = slots.next().expect("a buffer per child");
            changing_child_into(b, bb, a, ba, frame, child, points);
        }
        if mode != ChildMode::Changing {
            let (child, _) = slots.next().expect("a buffer per child");
            preserving_child_into(a, ba, b, bb, child);
            let (child, _) = slots.next().expect("a buffer per child");
            preserving_child_into(b, bb, a, ba, child);
        }
        return true;
    }
    false
}

#[cfg(test)]
mod tests;
