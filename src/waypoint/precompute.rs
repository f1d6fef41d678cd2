//! Per-traversal precomputation (000 §II-D, waypoint §7): for every directed edge its length,
//! heading, and the departure and arrival camera views as compact bitsets, so that evaluating a
//! path is OR-ing masks and counting bits. With [`Sensing::Footprint`] (an option beyond 000,
//! for the ablation's search-versus-objective comparison) a traversal's mask is instead the
//! free pixels the ground robot's footprint sweeps along the edge (003 §3.1's swept rectangle).

use super::graph::Graph;
use crate::coverage::camera::Camera;
use crate::coverage::work_map::WorkMap;

/// A bitset over the raster stored as the words between its first and last set bit.
#[derive(Clone, Debug, Default)]
pub struct Mask {
    /// Index of the first word.
    pub first: u32,
    /// The words.
    pub words: Vec<u64>,
}

impl Mask {
    fn from_indices(idx: &mut [usize]) -> Self {
        if idx.is_empty() {
            return Self::default();
        }
        idx.sort_unstable();
        let (lo, hi) = (idx[0] / 64, idx[idx.len() - 1] / 64);
        let mut words = vec![0u64; hi - lo + 1];
        for &i in idx.iter() {
            words[i / 64 - lo] |= 1 << (i % 64);
        }
        Self { first: lo as u32, words }
    }
}

/// Data of one directed traversal `i → j`.
#[derive(Clone, Debug)]
pub struct Traversal {
    /// Length in px.
    pub dist: f64,
    /// Heading `ψ_ij` in radians.
    pub heading: f64,
    /// View at `i` facing `j`.
    pub depart: Mask,
    /// View at `j` facing along `i → j`.
    pub arrive: Mask,
}

/// What a traversal covers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sensing {
    /// 000's camera views at departure and arrival.
    Camera(Camera),
    /// The free pixels swept by a footprint this many pixels wide.
    Footprint {
        /// Footprint width in px.
        width_px: f64,
    },
}

/// All traversals of a graph, indexed like the adjacency lists: `edges[i][k]` is `i → adj[i][k]`.
pub struct Traversals {
    /// Per waypoint, per neighbour.
    pub edges: Vec<Vec<Traversal>>,
    /// Words in a full raster bitset.
    pub words: usize,
}

impl Traversals {
    /// The union of every traversal's views: what the whole graph can see.
    pub fn all_views(&self) -> Union {
        let mut all = Union::new(self.words);
        for t in self.edges.iter().flatten() {
            all.add(&t.depart);
            all.add(&t.arrive);
        }
        all
    }

    /// Computes every traversal's data, or, once `give_up` says so (asked before each
    /// waypoint's edges), stops and returns how many waypoints' edges were done.
    pub fn compute(
        map: &WorkMap,
        graph: &Graph,
        sensing: &Sensing,
        give_up: &(dyn Fn() -> bool + Sync),
    ) -> Result<Self, usize> {
        use crate::coverage::raster::{RasterGrid, for_each_swept_cell};
        use crate::geom::Point;
        use rayon::prelude::*;
        use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
        let occ = |c: i64, r: i64| map.is_occluded(c, r);
        let raster = RasterGrid { cols: map.width, rows: map.height, resolution: 1.0, origin_x: 0.0, origin_y: 0.0 };
        let view = |p: (f64, f64), psi: f64| match sensing {
            Sensing::Camera(camera) => {
                let mut idx = Vec::new();
                camera.view(map.width, map.height, occ, p, psi, |i| idx.push(i));
                Mask::from_indices(&mut idx)
            }
            Sensing::Footprint { .. } => Mask::default(),
        };
        let swept = |a: (f64, f64), b: (f64, f64)| match sensing {
            Sensing::Footprint { width_px } => {
                let mut idx = Vec::new();
                for_each_swept_cell(&raster, Point::new(a.0, a.1), Point::new(b.0, b.1), *width_px, |i| {
                    if !map.occluded[i] {
                        idx.push(i);
                    }
                });
                Mask::from_indices(&mut idx)
            }
            Sensing::Camera(_) => Mask::default(),
        };
        let (late, done) = (AtomicBool::new(false), AtomicUsize::new(0));
        let edges: Vec<Vec<Traversal>> = (0..graph.points.len())
            .into_par_iter()
            .map(|i| {
                if late.load(Ordering::Relaxed) || give_up() {
                    late.store(true, Ordering::Relaxed);
                    return Vec::new();
                }
                let traversals: Vec<Traversal> = graph.adj[i]
                    .iter()
                    .map(|&j| {
                        let (a, b) = (graph.points[i], graph.points[j as usize]);
                        let heading = (b.1 - a.1).atan2(b.0 - a.0);
                        Traversal {
                            dist: (b.0 - a.0).hypot(b.1 - a.1),
                            heading,
                            depart: match sensing {
                                Sensing::Camera(_) => view(a, heading),
                                Sensing::Footprint { .. } => swept(a, b),
                            },
                            arrive: view(b, heading),
                        }
                    })
                    .collect();
                done.fetch_add(1, Ordering::Relaxed);
                traversals
            })
            .collect();
        if late.into_inner() {
            return Err(done.into_inner());
        }
        Ok(Self { edges, words: (map.width * map.height).div_ceil(64) })
    }

    /// The traversal `i → j` (must be an edge).
    pub fn get(&self, graph: &Graph, i: usize, j: usize) -> &Traversal {
        let k = graph.adj[i].binary_search(&(j as u32)).expect("consecutive waypoints are joined by an edge");
        &self.edges[i][k]
    }

    /// Bytes held by the masks.
    pub fn mask_bytes(&self) -> usize {
        self.edges.iter().flatten().map(|t| 8 * (t.depart.words.len() + t.arrive.words.len())).sum()
    }
}

/// A full-raster bitset used to accumulate views, cleared over the touched range only.
#[derive(Clone, Debug)]
pub struct Union {
    words: Vec<u64>,
    lo: usize,
    hi: usize,
}

impl Union {
    /// An empty union over `words` words.
    pub fn new(words: usize) -> Self {
        Self { words: vec![0; words], lo: usize::MAX, hi: 0 }
    }
    /// Clears the touched range.
    pub fn clear(&mut self) {
        if self.lo <= self.hi {
            self.words[self.lo..=self.hi].iter_mut().for_each(|w| *w = 0);
        }
        self.lo = usize::MAX;
        self.hi = 0;
    }
    /// ORs a mask in.
    pub fn add(&mut self, m: &Mask) {
        if m.words.is_empty() {
            return;
        }
        let f = m.first as usize;
        for (w, &x) in self.words[f..f + m.words.len()].iter_mut().zip(&m.words) {
            *w |= x;
        }
        self.lo = self.lo.min(f);
        self.hi = self.hi.max(f + m.words.len() - 1);
    }
    /// `(|U|, |U ∩ band|)`.
    pub fn counts(&self, band: &[u64]) -> (u64, u64) {
        if self.lo > self.hi {
            return (0, 0);
        }
        let mut all = 0u64;
        let mut walls = 0u64;
        for (w, b) in self.words[self.lo..=self.hi].iter().zip(&band[self.lo..=self.hi]) {
            all += u64::from(w.count_ones());
            walls += u64::from((w & b).count_ones());
        }
        (all, walls)
    }
    /// Whether pixel `i` is in the union.
    pub fn contains(&self, i: usize) -> bool {
        self.words[i / 64] >> (i % 64) & 1 == 1
    }
}
