//! What the two architectures and the run loop ask of a population member. One GA then
//! evolves either one robot's genome ([`Individual`], 003 as written) or a fleet's genomes,
//! one per robot ([`crate::fleet::central::Crew`]), with the same operators, selections and
//! parameter control.

use super::crossover::{ChildBuffers, Parent, crossover_into};
use super::diversity::{DiversityScratch, diversity, max_distance};
use super::genome::{Action, random_genome};
use super::individual::{Base, EvalScratch, EvaluationMode, Individual, InitParams, correct_and_evaluate};
use super::mutation::{Mutation, mutate, mutate_action};
use super::params::ThesisParams;
use super::scenario::ThesisScenario;
use crate::coverage::fitness::ThesisScore;
use crate::ga::rng::Rng;
use crate::geom::Point;
use rand::Rng as _;

/// What a job does to a member before it is corrected and evaluated.
#[derive(Clone, Copy, Debug)]
pub enum Op {
    /// Architecture (a): `randInit` with `P_mI`, else the action mutation with `P_mA`.
    Mutate {
        /// `P_mI`.
        p_mi: f64,
        /// `P_mA`.
        p_ma: f64,
    },
    /// Architecture (b) children: the action mutation with `P_mA`.
    MutateAction {
        /// `P_mA`.
        p_ma: f64,
    },
    /// A fresh random genome (`randInit`).
    Reinit,
    /// The genome as it is (a seed plan): corrected and evaluated, not varied.
    Evaluate,
}

/// What a member's genome was made from, for incremental evaluation.
#[derive(Clone, Copy, Debug)]
pub enum Origin<'a, T> {
    /// A fresh genome.
    New,
    /// A copy of an evaluated member (its own path is the base).
    Copy,
    /// A crossover child of this receiving parent.
    Child(&'a T),
}

/// How changed genomes are re-drawn when dead and evaluated.
#[derive(Clone, Copy, Debug)]
pub struct Variation {
    /// How a dead genome is re-initialised (thesis-ga §6).
    pub init: InitParams,
    /// Incremental or full evaluation.
    pub mode: EvaluationMode,
}

/// The cells the common scorer counts as reachable in a world, as bit rows in the layout of
/// its visit maps, for the reachable coverage of the history's best plan.
#[derive(Clone, Debug, Default)]
pub struct ReachMask {
    /// One bit per reachable cell ([`crate::coverage::bits::BitLayers::mask_of`]).
    pub words: Vec<u64>,
    /// Reachable cells (the denominator).
    pub cells: u64,
}

impl ReachMask {
    /// The reachable cells of a robot of `width` starting at `stations` on `world`'s map.
    pub fn new(world: &ThesisScenario, width: f64, stations: &[Point]) -> Self {
        let reach = crate::map::reach::Reach::new(&crate::map::clearance::Clearance::new(&world.map, width), stations);
        Self { words: world.layers.mask_of(reach.coverable()), cells: reach.coverable_count() as u64 }
    }

    /// `reached` cells as a share of the reachable ones.
    pub fn coverage(&self, reached: u64) -> f64 {
        reached as f64 / self.cells.max(1) as f64
    }
}

/// A member of the thesis GA's population.
pub trait Member: Clone + Default + Send + Sync {
    /// What an evaluation reads (a [`ThesisScenario`], or one per robot).
    type World: Sync;
    /// `f_obstacle` (maximised).
    fn fitness(&self) -> f64;
    /// The objectives behind the fitness.
    fn score(&self) -> ThesisScore;
    /// Genes in all (`G_len`; summed over a fleet's robots).
    fn genome_len(&self) -> usize;
    /// `obj_pix`: sweeps of obstacle cells (summed over a fleet's robots); 0 for a plan that
    /// stays in free space.
    fn obstacle_cells(&self) -> u64;
    /// The modified dual-point crossover of `a` and `b` (003 §3.3.2), written into `kids`:
    /// recycled members, resized to the number of children (`C_child`), each made an
    /// unevaluated member holding one child's genes. Their buffers are reused; the evaluation
    /// that follows overwrites the rest. Returns false when no child could be made (the
    /// children are then copies; `kids` hold nothing of use).
    fn cross(
        a: &Self,
        b: &Self,
        params: &ThesisParams,
        world: &Self::World,
        rng: &mut Rng,
        kids: &mut Vec<Self>,
    ) -> bool;
    /// Applies `op`, then corrects and evaluates what changed (R17), against `origin` where
    /// that saves work. Returns the single-robot path evaluations spent.
    fn vary_and_evaluate(
        &mut self,
        op: Op,
        origin: Origin<'_, Self>,
        world: &Self::World,
        how: &Variation,
        scratch: &mut EvalScratch,
        rng: &mut Rng,
    ) -> u64;
    /// Evaluates the member anew (after the world changed). Returns the evaluations spent.
    fn reevaluate(&mut self, world: &Self::World, mode: EvaluationMode, scratch: &mut EvalScratch) -> u64;
    /// `Div` of a population (003 eq. 3.18).
    fn diversity(pop: &[Self], scratch: &mut DiversityScratch) -> f64;
    /// `Div_max` of a population (thesis-ga §12.2).
    fn max_distance(pop: &[Self]) -> u64;
    /// The cells the common scorer counts as reachable for a plan in `world`.
    fn reach_mask(world: &Self::World) -> ReachMask;
    /// Distinct cells of `mask` the member's plan sweeps.
    fn reached(&self, mask: &ReachMask) -> u64;
    /// Per robot of a fleet's member, what the history records of it (none for one robot).
    fn robot_records(&self, _world: &Self::World) -> Vec<crate::ga::observer::RobotRecord> {
        Vec::new()
    }
}

/// A world that can mark a region as already covered (the retrain, 003 §3.5.3).
pub trait Premark {
    /// Marks the free cells whose centre lies in `[x0, x1) × [y0, y1)` as covered.
    fn premark_rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64);
}

impl Premark for ThesisScenario {
    fn premark_rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64) {
        ThesisScenario::premark_rect(self, x0, y0, x1, y1);
    }
}

/// Applies `op` to one genome (thesis-ga §8, R15–R16) and says what changed.
pub fn vary(genome: &mut Vec<Action>, op: Op, init: &InitParams, rng: &mut Rng) -> Mutation {
    match op {
        Op::Mutate { p_mi, p_ma } => mutate(genome, p_mi, p_ma, init, rng),
        Op::MutateAction { p_ma } => {
            if rng.random_bool(p_ma.clamp(0.0, 1.0)) {
                mutate_action(genome, rng);
                Mutation::Action
            } else {
                Mutation::None
            }
        }
        Op::Reinit => {
            random_genome(rng, init.actions, init.dist_max, genome);
            Mutation::Reinit
        }
        Op::Evaluate => Mutation::None,
    }
}

impl Member for Individual {
    type World = ThesisScenario;
    fn reach_mask(world: &ThesisScenario) -> ReachMask {
        ReachMask::new(world, world.robot.width, &[world.frame.start])
    }
    fn reached(&self, mask: &ReachMask) -> u64 {
        self.visits.visited_in(&mask.words)
    }
    fn fitness(&self) -> f64 {
        self.score.fitness
    }
    fn score(&self) -> ThesisScore {
        self.score
    }
    fn genome_len(&self) -> usize {
        self.genome.len()
    }
    fn obstacle_cells(&self) -> u64 {
        self.sweep.obj_pix
    }
    fn cross(
        a: &Self,
        b: &Self,
        p: &ThesisParams,
        world: &ThesisScenario,
        rng: &mut Rng,
        kids: &mut Vec<Self>,
    ) -> bool {
        fn parent(x: &Individual) -> Parent<'_> {
            Parent { genome: &x.genome, points: &x.points, stable: x.stable_genes }
        }
        kids.resize_with(p.c_child.children(), Default::default);
        let (c_len, short, mode, max_len) = (p.c_len, p.short_genomes, p.c_child, p.max_genome_len);
        let crossed = crossover_into(parent(a), parent(b), c_len, short, mode, max_len, &world.frame, rng, kids);
        for kid in kids.iter_mut() {
            kid.stable_genes = 0;
        }
        crossed
    }

    fn vary_and_evaluate(
        &mut self,
        op: Op,
        origin: Origin<'_, Self>,
        world: &ThesisScenario,
        how: &Variation,
        scratch: &mut EvalScratch,
        rng: &mut Rng,
    ) -> u64 {
        let change = vary(&mut self.genome, op, &how.init, rng);
        let base = match (change, origin) {
            (Mutation::Reinit, _) | (_, Origin::New) => Base::None,
            (Mutation::None, Origin::Copy) => return 0,
            (_, Origin::Copy) => Base::Own,
            (_, Origin::Child(parent)) => Base::Parent(parent),
        };
        correct_and_evaluate(self, world, base, how.mode, scratch, &how.init, rng)
    }

    fn reevaluate(&mut self, world: &ThesisScenario, mode: EvaluationMode, scratch: &mut EvalScratch) -> u64 {
        super::individual::evaluate(self, world, Base::None, mode, scratch);
        1
    }

    fn diversity(pop: &[Self], scratch: &mut DiversityScratch) -> f64 {
        diversity(pop, scratch)
    }
    fn max_distance(pop: &[Self]) -> u64 {
        max_distance(pop)
    }
}

/// A member's genome is where a crossover child is written; its viewpoints are the scratch
/// (the evaluation that follows overwrites them).
impl ChildBuffers for Individual {
    fn buffers(&mut self) -> (&mut Vec<Action>, &mut Vec<Point>) {
        let fields = &mut **self;
        (&mut fields.genome, &mut fields.points)
    }
}
