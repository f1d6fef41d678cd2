//! The centralised fleet GA (beyond 003, which plans for one robot): a member of the population
//! is a [`Crew`], one action genome per robot, each decoded with its own stations and swept
//! with its own width; the member's fitness is 003's eqs. 3.9–3.16 over all robots' visits on
//! one map ([`crew_score`]). The thesis GA runs unchanged on crews ([`crate::thesis::run::Ga`]):
//! selection acts on whole crews; crossover pairs a robot's genome with the same robot's genome
//! in the other parent; mutation and the corrections act on each robot's genome in turn.
//!
//! Evaluations are counted per robot path evaluated, so a crew whose three genomes all changed
//! costs three, and an evaluation budget buys the same number of path sweeps as in the
//! negotiation or a single-robot run.

use super::{Fleet, fleet_t_final, fleet_t_optimal};
use crate::coverage::fitness::{Projection, ThesisScore, area_m2, cov_actual, cov_final, f_obstacle, f1, f2, t_actual};
use crate::coverage::planes::VisitPlanes;
use crate::ga::observer::RobotRecord;
use crate::ga::rng::Rng;
use crate::geom::Point;
use crate::map::GridMap;
use crate::thesis::diversity::{DiversityScratch, kept_pair_distance_sum, max_distance_by};
use crate::thesis::individual::{EvalScratch, EvaluationMode, Individual};
use crate::thesis::member::{Member, Op, Origin, Premark, ReachMask, Variation};
use crate::thesis::params::ThesisParams;
use crate::thesis::scenario::ThesisScenario;

/// What a crew's evaluation reads: one scenario per robot (its footprint and stations on the
/// shared map) and the fleet's combined sweep rate.
#[derive(Clone, Debug)]
pub struct FleetWorld {
    /// One scenario per robot, in the fleet's order.
    pub robots: Vec<ThesisScenario>,
    /// `Σ R_width,i · R_speed,i` in m²/s.
    pub sweep_rate: f64,
}

impl FleetWorld {
    /// The world of `fleet` on `map` under `projection`.
    pub fn new(map: &GridMap, fleet: &Fleet, projection: Projection) -> Self {
        let robots = fleet
            .robots()
            .iter()
            .map(|r| ThesisScenario::new(map.clone(), r.footprint, r.start, r.end, projection))
            .collect();
        Self { robots, sweep_rate: fleet.sweep_rate() }
    }
}

impl Premark for FleetWorld {
    fn premark_rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64) {
        for s in &mut self.robots {
            s.premark_rect(x0, y0, x1, y1);
        }
    }
}

/// One plan of the fleet: an evaluated genome per robot, and the fleet's score.
#[derive(Clone, Debug, Default)]
pub struct Crew {
    /// Each robot's genome, path and visit map, scored as if it were alone.
    pub robots: Vec<Individual>,
    /// 003's objectives of the whole plan ([`crew_score`]).
    pub score: ThesisScore,
    /// Distinct free cells some robot sweeps.
    pub union_cells: u64,
}

impl Crew {
    /// The robots' paths, in the fleet's order.
    pub fn paths(&self) -> Vec<Vec<Point>> {
        self.robots.iter().map(|r| r.points.clone()).collect()
    }
}

/// Distinct cells visited by any of `maps` (the union of their visits, word by word).
pub fn union_cells(maps: &[Individual]) -> u64 {
    let Some(first) = maps.first() else { return 0 };
    let words = first.visits.plane_words();
    let planes: usize = maps.iter().map(|m| m.visits.planes()).max().unwrap_or(0);
    let mut cells = 0u64;
    for idx in 0..words {
        let mut any = 0u64;
        for m in maps {
            any |= visited(&m.visits, idx, planes);
        }
        cells += u64::from(any.count_ones());
    }
    cells
}

/// The cells of word `idx` visited at least once: a count is non-zero when one of its bits is.
fn visited(v: &VisitPlanes, idx: usize, planes: usize) -> u64 {
    (0..planes).fold(0, |acc, p| acc | v.word(p, idx))
}

/// A robot's time as the fitness reads it: 003 eq. 3.12 over the area it sweeps, plus its
/// rotation time.
fn robot_time_s(ind: &Individual, scenario: &ThesisScenario) -> f64 {
    let res = scenario.map.resolution();
    t_actual(area_m2(ind.sweep.cov_pix, res), scenario.robot.speed, scenario.robot.width) + ind.t_rot_s
}

/// 003's objectives of a fleet plan: eq. 3.9 with `cross_pix` the sweeps of cells some robot
/// had already swept (all sweeps minus the union), eq. 3.10 over the union, `t_optimal` with
/// the fleet's sweep rate ([`fleet_t_optimal`]) and eq. 3.13 with the slowest robot's
/// eq. 3.12 time plus rotation time ([`fleet_t_final`]); the projection and eq. 3.16 with all
/// robots' obstacle sweeps. For one robot this is [`crate::coverage::fitness::score_counts`].
pub fn crew_score(robots: &[Individual], union: u64, world: &FleetWorld) -> ThesisScore {
    let first = &world.robots[0];
    let res = first.map.resolution();
    let (mut cov_pix, mut obj_pix, mut makespan) = (0u64, 0u64, 0.0f64);
    for (ind, s) in robots.iter().zip(&world.robots) {
        cov_pix += ind.sweep.cov_pix;
        obj_pix += ind.sweep.obj_pix;
        makespan = makespan.max(robot_time_s(ind, s));
    }
    let actual = cov_actual(area_m2(cov_pix, res), area_m2(cov_pix - union, res));
    let cov = cov_final(actual, area_m2(first.grid.area_cells() as u64, res));
    let t = fleet_t_final(fleet_t_optimal(actual, world.sweep_rate), &[makespan]);
    let (f1v, f2v) = (f1(t, cov), f2(t, cov));
    let f = match first.projection {
        Projection::F1 => f1v,
        Projection::F2 => f2v,
    };
    ThesisScore { cov_final: cov, t_final: t, f1: f1v, f2: f2v, fitness: f_obstacle(f, obj_pix) }
}

impl Member for Crew {
    type World = FleetWorld;

    fn fitness(&self) -> f64 {
        self.score.fitness
    }
    fn score(&self) -> ThesisScore {
        self.score
    }
    fn genome_len(&self) -> usize {
        self.robots.iter().map(|r| r.len()).sum()
    }
    fn obstacle_cells(&self) -> u64 {
        self.robots.iter().map(|r| r.sweep.obj_pix).sum()
    }
    /// The narrowest robot's reachable cells from every robot's start, as the common scorer
    /// counts them for a fleet's plan.
    fn reach_mask(world: &FleetWorld) -> ReachMask {
        let Some(first) = world.robots.first() else { return ReachMask::default() };
        let width = world.robots.iter().map(|r| r.robot.width).fold(f64::INFINITY, f64::min);
        let stations: Vec<Point> = world.robots.iter().map(|r| r.frame.start).collect();
        ReachMask::new(first, width, &stations)
    }
    /// Cells of `mask` some robot sweeps.
    fn reached(&self, mask: &ReachMask) -> u64 {
        (0..mask.words.len())
            .map(|idx| {
                let any = self
                    .robots
                    .iter()
                    .filter(|r| idx < r.visits.plane_words())
                    .fold(0, |a, r| a | r.visits.visited_word(idx));
                u64::from((any & mask.words[idx]).count_ones())
            })
            .sum()
    }
    fn robot_records(&self, world: &FleetWorld) -> Vec<RobotRecord> {
        self.robots
            .iter()
            .zip(&world.robots)
            .map(|(ind, s)| RobotRecord {
                genome_len: ind.len() as u32,
                swept_cells: ind.sweep.unique(),
                t_actual_s: robot_time_s(ind, s),
            })
            .collect()
    }
    /// Robot by robot, the robot's genomes of the two parents cross; a robot whose crossover
    /// draws no blocks passes to each child as the receiving parent's copy.
    fn cross(a: &Self, b: &Self, p: &ThesisParams, world: &FleetWorld, rng: &mut Rng, kids: &mut Vec<Self>) -> bool {
        let robots = world.robots.len();
        kids.resize_with(p.c_child.children(), Default::default);
        for kid in kids.iter_mut() {
            kid.robots.resize_with(robots, Default::default);
        }
        let mut robot_kids: Vec<Individual> = Vec::with_capacity(kids.len());
        let mut crossed_any = false;
        for k in 0..robots {
            robot_kids.clear();
            robot_kids.extend(kids.iter_mut().map(|kid| std::mem::take(&mut kid.robots[k])));
            let crossed = Individual::cross(&a.robots[k], &b.robots[k], p, &world.robots[k], rng, &mut robot_kids);
            crossed_any |= crossed;
            for (c, (kid, mut robot)) in kids.iter_mut().zip(robot_kids.drain(..)).enumerate() {
                if !crossed {
                    let receiver = if c % 2 == 0 { a } else { b };
                    robot.genome.clone_from(&receiver.robots[k].genome);
                    robot.stable_genes = 0;
                }
                kid.robots[k] = robot;
            }
        }
        crossed_any
    }

    fn vary_and_evaluate(
        &mut self,
        op: Op,
        origin: Origin<'_, Self>,
        world: &FleetWorld,
        how: &Variation,
        scratch: &mut EvalScratch,
        rng: &mut Rng,
    ) -> u64 {
        self.robots.resize_with(world.robots.len(), Default::default);
        let mut evaluations = 0;
        for (k, (robot, scenario)) in self.robots.iter_mut().zip(&world.robots).enumerate() {
            let origin = match origin {
                Origin::New => Origin::New,
                Origin::Copy => Origin::Copy,
                Origin::Child(parent) => Origin::Child(&parent.robots[k]),
            };
            evaluations += robot.vary_and_evaluate(op, origin, scenario, how, scratch, rng);
        }
        if evaluations > 0 {
            self.rescore(world);
        }
        evaluations
    }

    fn reevaluate(&mut self, world: &FleetWorld, mode: EvaluationMode, scratch: &mut EvalScratch) -> u64 {
        let mut evaluations = 0;
        for (robot, scenario) in self.robots.iter_mut().zip(&world.robots) {
            evaluations += robot.reevaluate(scenario, mode, scratch);
        }
        self.rescore(world);
        evaluations
    }

    /// The sum over robots of each robot's `Div` (eq. 3.18 with the distance of two crews the
    /// sum of their robots' eq. 3.17 distances, so the mean over pairs splits by robot).
    fn diversity(pop: &[Self], scratch: &mut DiversityScratch) -> f64 {
        let n = pop.len();
        if n < 2 {
            return 0.0;
        }
        let robots = pop[0].robots.len();
        let sum: u64 = (0..robots).map(|k| kept_pair_distance_sum(n, |i| &pop[i].robots[k].visits, scratch, k)).sum();
        2.0 * sum as f64 / (n as f64 * (n as f64 - 1.0))
    }

    fn max_distance(pop: &[Self]) -> u64 {
        let robots = pop.first().map_or(0, |c| c.robots.len());
        max_distance_by(pop.len(), robots, |i, k| &pop[i].robots[k].visits)
    }
}

impl Crew {
    fn rescore(&mut self, world: &FleetWorld) {
        self.union_cells = union_cells(&self.robots);
        self.score = crew_score(&self.robots, self.union_cells, world);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fleet::config::FleetFile;
    use crate::fleet::metrics::FleetScorer;
    use crate::map::presets::preset;
    use crate::planner::Budget;
    use crate::thesis::run::{Ga, ThesisGa, ThesisOutcome};

    fn params(pop: usize, selection: &str) -> ThesisParams {
        let selection = crate::thesis::config::SelectionName::parse(selection).unwrap();
        let section = crate::thesis::config::ThesisSection { pop_min: pop, selection, ..Default::default() };
        crate::thesis::config::validate_params(&section, "test").unwrap()
    }

    fn budget(iterations: u32) -> Budget {
        Budget::iterations(iterations)
    }

    const HETERO: &str = "[[robots]]\nname = \"small\"\nwidth = 0.4\nspeed = 0.2\nstart = [1.3, 1.3]\n\
        [[robots]]\nname = \"medium\"\nwidth = 0.6\nspeed = 0.3\nstart = [9.7, 1.3]\n\
        [[robots]]\nname = \"large\"\nwidth = 0.9\nspeed = 0.5\nstart = [5.5, 9.5]\n";

    fn central(map: &GridMap, fleet: &Fleet, p: ThesisParams, seed: u64, iterations: u32) -> ThesisOutcome<Crew> {
        let mut ga = Ga::<Crew> {
            scenario: FleetWorld::new(map, fleet, Projection::F2),
            params: p,
            seed,
            seeds: (Vec::new(), 0),
        };
        ga.run(&budget(iterations), None, &mut []).unwrap()
    }

    #[test]
    fn a_fleet_of_one_is_the_single_robot_run_for_both_architectures() {
        let map = preset("thesis-2").unwrap();
        let text = "[[robots]]\nname = \"solo\"\nwidth = 0.6\nspeed = 0.2\nrot_speed = 0.5\nstart = [1.3, 1.3]\n";
        let fleet = FleetFile::parse(text, "f.toml", &map).unwrap();
        for selection in ["elite", "rrws"] {
            let p = params(20, selection);
            let crew = central(&map, &fleet, p, 5, 120);
            let r = &fleet.robots()[0];
            let scenario = ThesisScenario::new(map.clone(), r.footprint, r.start, r.end, Projection::F2);
            let alone = ThesisGa { scenario, params: p, seed: 5, seeds: (Vec::new(), 0) }
                .run(&budget(120), None, &mut [])
                .unwrap();
            assert_eq!(crew.best.robots[0].genome, alone.best.genome, "{selection}");
            assert_eq!(crew.best.score.fitness.to_bits(), alone.best.score.fitness.to_bits(), "{selection}");
            assert_eq!(crew.evaluations, alone.evaluations, "{selection}");
            let bits = |o: &[crate::ga::observer::GenerationStats]| -> Vec<u64> {
                o.iter().map(|g| g.best_fitness.to_bits() ^ g.diversity.unwrap_or(0.0).to_bits()).collect()
            };
            assert_eq!(bits(&crew.history), bits(&alone.history), "{selection}: every generation");
        }
    }

    #[test]
    fn crew_scores_agree_with_the_common_fleet_scorer() {
        let map = preset("thesis-1").unwrap();
        let fleet = FleetFile::parse(HETERO, "f.toml", &map).unwrap();
        let out = central(&map, &fleet, params(20, "elite"), 3, 30);
        let world = FleetWorld::new(&map, &fleet, Projection::F2);
        let scorer = FleetScorer::new(&map, &fleet);
        let mut checked = 0;
        let pop = Ga::<Crew> { scenario: world, params: params(20, "elite"), seed: 9, seeds: (Vec::new(), 0) }
            .init(false)
            .population;
        for crew in pop.iter().chain(std::iter::once(&out.best)) {
            let s = scorer.score(&crew.paths()).unwrap();
            assert_eq!(crew.union_cells, s.union_cells);
            assert_eq!(crew.score.cov_final.to_bits(), s.cov_final.to_bits());
            assert_eq!(crew.score.t_final.to_bits(), s.t_final.to_bits());
            checked += 1;
        }
        assert_eq!(checked, 21);
    }

    #[test]
    fn central_runs_are_deterministic_with_one_and_two_threads() {
        let map = preset("thesis-1").unwrap();
        let fleet = FleetFile::parse(HETERO, "f.toml", &map).unwrap();
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| central(&map, &fleet, params(24, "tournament"), 8, 60))
        };
        let (one, two) = (run(1), run(2));
        assert_eq!(one.best.paths(), two.best.paths());
        assert_eq!(one.evaluations, two.evaluations);
        let fit = |o: &ThesisOutcome<Crew>| o.history.iter().map(|g| g.best_fitness.to_bits()).collect::<Vec<_>>();
        assert_eq!(fit(&one), fit(&two));
    }

    #[test]
    fn a_crew_crosses_robot_by_robot_into_recycled_kids() {
        // Robot 0's genomes are too short to cross (three genes), robot 1's cross. Each child
        // holds its receiver's robot 0 and the matching child of robot 1's own crossover, drawn
        // from the same stream, whatever the recycled kids held before.
        use crate::thesis::crossover::{Parent, crossover};
        let map = preset("thesis-1").unwrap();
        let fleet = FleetFile::parse(HETERO, "f.toml", &map).unwrap();
        let world = FleetWorld::new(&map, &fleet, Projection::F2);
        let p = params(20, "elite");
        let mut rng = crate::ga::rng::stream(4, crate::ga::rng::Purpose::Main, &[]);
        let robot = |r: usize, len: usize, rng: &mut Rng| {
            let mut ind = Individual::default();
            crate::thesis::genome::random_genome(rng, len - 2, 5.0, &mut ind.genome);
            crate::thesis::individual::evaluate(
                &mut ind,
                &world.robots[r],
                crate::thesis::individual::Base::None,
                EvaluationMode::Full,
                &mut EvalScratch::default(),
            );
            ind
        };
        let crew = |rng: &mut Rng| Crew {
            robots: vec![robot(0, 3, rng), robot(1, 20, rng), robot(2, 3, rng)],
            ..Default::default()
        };
        let (a, b) = (crew(&mut rng), crew(&mut rng));
        let mut kids = vec![crew(&mut rng), Crew::default()];
        let mut replay = rng.clone();
        assert!(Crew::cross(&a, &b, &p, &world, &mut rng, &mut kids));
        fn parent(x: &Individual) -> Parent<'_> {
            Parent { genome: &x.genome, points: &x.points, stable: x.stable_genes }
        }
        let (r1a, r1b) = (parent(&a.robots[1]), parent(&b.robots[1]));
        let expected = crossover(
            r1a,
            r1b,
            p.c_len,
            p.short_genomes,
            p.c_child,
            p.max_genome_len,
            &world.robots[1].frame,
            &mut replay,
        )
        .expect("robot 1 crosses");
        assert_eq!(kids.len(), p.c_child.children());
        for (c, kid) in kids.iter().enumerate() {
            let receiver = if c % 2 == 0 { &a } else { &b };
            assert_eq!(kid.robots.len(), 3);
            assert_eq!(kid.robots[0].genome, receiver.robots[0].genome, "child {c}, robot 0");
            assert_eq!(kid.robots[1].genome, expected[c], "child {c}, robot 1");
            assert_eq!(kid.robots[2].genome, receiver.robots[2].genome, "child {c}, robot 2");
            assert!(kid.robots.iter().all(|r| r.stable_genes == 0));
        }
        assert_eq!(rng.get_word_pos(), replay.get_word_pos(), "robots 0 and 2 draw nothing");
        // No robot can cross: no child.
        let short = |rng: &mut Rng| Crew { robots: (0..3).map(|r| robot(r, 3, rng)).collect(), ..Default::default() };
        let (c, d) = (short(&mut rng), short(&mut rng));
        assert!(!Crew::cross(&c, &d, &p, &world, &mut rng, &mut kids));
    }

    #[test]
    fn union_of_visit_maps_by_hand() {
        let map = preset("thesis-1").unwrap();
        let grid = crate::coverage::CoverageGrid::new(&map);
        let layers = crate::coverage::bits::BitLayers::new(&grid);
        // Two 0.4 m bands of 20 cells' length on the same row (2 rows × 20 = 40 cells each),
        // the second shifted by 10 cells: union 60 cells.
        let mut a = Individual::default();
        let mut b = Individual::default();
        a.visits.reset(layers.plane_words());
        b.visits.reset(layers.plane_words());
        layers.sweep(&mut a.visits, &[Point::new(2.0, 3.0), Point::new(6.0, 3.0)], 0.4);
        layers.sweep(&mut b.visits, &[Point::new(4.0, 3.0), Point::new(8.0, 3.0)], 0.4);
        assert_eq!(union_cells(&[a.clone()]), 40);
        assert_eq!(union_cells(&[a, b]), 60);
        assert_eq!(union_cells(&[]), 0);
    }

    #[test]
    fn a_heterogeneous_fleet_beats_its_best_robot_alone_on_makespan() {
        let map = preset("thesis-1").unwrap();
        let fleet = FleetFile::parse(HETERO, "f.toml", &map).unwrap();
        let p = params(30, "elite");
        let team = central(&map, &fleet, p, 2, 300);
        let scorer = FleetScorer::new(&map, &fleet);
        let t = scorer.score(&team.best.paths()).unwrap();
        // Each robot alone, same settings and iterations, planning the whole map.
        for r in fleet.robots() {
            let scenario = ThesisScenario::new(map.clone(), r.footprint, r.start, r.end, Projection::F2);
            let alone = ThesisGa { scenario, params: p, seed: 2, seeds: (Vec::new(), 0) }
                .run(&budget(300), None, &mut [])
                .unwrap();
            let m =
                alone.best.path_metrics(&ThesisScenario::new(map.clone(), r.footprint, r.start, r.end, Projection::F2));
            let time = m.length_m / r.footprint.speed;
            let cov = alone.best.score.cov_final;
            assert!(t.union_free >= cov - 0.05, "{}: team union {} vs alone {cov}", r.name, t.union_free);
            assert!(t.makespan_s < time, "{}: team makespan {} vs alone {time}", r.name, t.makespan_s);
        }
    }
}
