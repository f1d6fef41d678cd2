//! Batch evaluation of action genomes given from outside the GA (a Python optimiser's
//! population, say) with exactly the thesis GA's fitness: each genome is decoded with the
//! out-of-bounds correction of 003 eqs. 3.7–3.8, its connector aimed at E, and scored by
//! 003 eqs. 3.4–3.16 on the scenario, as [`super::individual::evaluate`] scores the GA's own.

use super::genome::{Action, MIN_GENOME_LEN};
use super::individual::{Base, EvalScratch, EvaluationMode, Individual, evaluate};
use super::scenario::ThesisScenario;
use rayon::prelude::*;

/// The columns of a batch result, in order.
pub const COLUMNS: [&str; 4] = ["cov_final", "t_final", "f", "obstacle_cells"];

/// The most actions one genome may have (the GA's own `thesis.max_genome_len` bound).
pub const MAX_ACTIONS: usize = 1_000_000;

/// One genome's result: `cov_final`, `t_final`, `f_obstacle` of the scenario's projection, and
/// `obj_pix` (obstacle cell sweeps; 0 for a plan that stays in free space).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BatchScore {
    /// `cov_final` (003 eq. 3.6).
    pub cov_final: f64,
    /// `t_final` (003 eq. 3.10).
    pub t_final: f64,
    /// `f_obstacle` (003 eq. 3.16) under the scenario's projection.
    pub fitness: f64,
    /// `obj_pix`: sweeps of obstacle cells.
    pub obstacle_cells: u64,
}

impl BatchScore {
    /// The values in the order of [`COLUMNS`].
    pub fn row(&self) -> [f64; 4] {
        [self.cov_final, self.t_final, self.fitness, self.obstacle_cells as f64]
    }
}

/// A genome given as its live moves `(alpha_deg, dist_m)`, from S on.
#[derive(Debug, thiserror::Error, PartialEq)]
#[error("genome {genome}, action {action}: {message}")]
pub struct GenomeError {
    /// Index of the genome in the batch.
    pub genome: usize,
    /// Index of the action in the genome.
    pub action: usize,
    /// What is wrong and what is allowed.
    pub message: String,
}

/// The full genome of live moves `moves` (S's move first): the moves, then the connector
/// (recomputed by decoding) and E, so `G_len = moves.len() + 2` (thesis-ga §2.1). Headings are
/// taken modulo 360°; distances must be finite and ≥ 0.
pub fn genome_of(index: usize, moves: &[(f64, f64)]) -> Result<Vec<Action>, GenomeError> {
    let fail = |action: usize, message: String| GenomeError { genome: index, action, message };
    if moves.is_empty() || moves.len() > MAX_ACTIONS {
        return Err(fail(
            0,
            format!("has {} actions: expected 1 to {MAX_ACTIONS} (S's move first; E is added)", moves.len()),
        ));
    }
    let mut genome = Vec::with_capacity(moves.len() + MIN_GENOME_LEN - 1);
    for (k, &(alpha, dist)) in moves.iter().enumerate() {
        if !alpha.is_finite() {
            return Err(fail(k, format!("angle = {alpha} is not a finite number of degrees")));
        }
        if !(dist.is_finite() && dist >= 0.0) {
            return Err(fail(k, format!("distance = {dist} is out of range: expected finite metres >= 0")));
        }
        genome.push(Action::new(alpha.rem_euclid(360.0), dist));
    }
    genome.push(Action::new(0.0, 0.0));
    genome.push(Action::new(0.0, 0.0));
    Ok(genome)
}

/// The path the robot drives for the genome of live moves `moves` (see [`genome_of`]): its
/// viewpoints decoded as the GA decodes its own (the out-of-bounds correction of 003
/// eqs. 3.7–3.8, the connector aimed at E), joined by straight or routed moves as the
/// scenario's `thesis.moves` says: the plan the GA reports for such a genome.
pub fn decode(scenario: &ThesisScenario, moves: &[(f64, f64)]) -> Result<Vec<crate::geom::Point>, GenomeError> {
    let mut ind = Individual::with_genome(genome_of(0, moves)?);
    evaluate(&mut ind, scenario, Base::None, EvaluationMode::Full, &mut EvalScratch::default());
    Ok(scenario.driven(&ind.points))
}

/// Scores every genome (live moves, see [`genome_of`]) in parallel on the current rayon pool.
/// The result of each genome does not depend on the others or on the threads.
pub fn evaluate_batch(scenario: &ThesisScenario, genomes: &[Vec<(f64, f64)>]) -> Result<Vec<BatchScore>, GenomeError> {
    let genomes: Vec<Vec<Action>> =
        genomes.iter().enumerate().map(|(i, g)| genome_of(i, g)).collect::<Result<_, _>>()?;
    Ok(evaluate_genomes(scenario, genomes))
}

/// [`evaluate_batch`] of genomes already built by [`genome_of`].
pub fn evaluate_genomes(scenario: &ThesisScenario, genomes: Vec<Vec<Action>>) -> Vec<BatchScore> {
    evaluate_genomes_until(scenario, genomes, &std::sync::atomic::AtomicBool::new(false))
        .expect("nothing sets the flag")
}

/// [`evaluate_genomes`] that gives up (`None`) once `stop` is set from another thread (a
/// caller's Ctrl-C): each genome not yet evaluated is skipped, so the batch ends within about
/// one evaluation per thread.
pub fn evaluate_genomes_until(
    scenario: &ThesisScenario,
    genomes: Vec<Vec<Action>>,
    stop: &std::sync::atomic::AtomicBool,
) -> Option<Vec<BatchScore>> {
    use std::sync::atomic::Ordering;
    let scores: Vec<Option<BatchScore>> = genomes
        .into_par_iter()
        .map_init(
            || (EvalScratch::default(), Individual::default()),
            |(scratch, ind), genome| {
                if stop.load(Ordering::Relaxed) {
                    return None;
                }
                ind.genome = genome;
                evaluate(ind, scenario, Base::None, EvaluationMode::Full, scratch);
                Some(BatchScore {
                    cov_final: ind.score.cov_final,
                    t_final: ind.score.t_final,
                    fitness: ind.score.fitness,
                    obstacle_cells: ind.sweep.obj_pix,
                })
            },
        )
        .collect();
    if stop.load(Ordering::Relaxed) {
        return None;
    }
    scores.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::Footprint;
    use crate::coverage::fitness::Projection;
    use crate::geom::Point;
    use crate::map::presets::preset;
    use crate::thesis::genome::random_genome;
    use crate::thesis::individual::EvalScratch;
    use rand::SeedableRng;

    fn scenario() -> ThesisScenario {
        let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 };
        let s = Point::new(1.3, 1.3);
        ThesisScenario::new(preset("thesis-1").unwrap(), robot, s, s, Projection::F2)
    }

    #[test]
    fn batch_equals_the_gas_own_incremental_evaluation() {
        let sc = scenario();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let mut moves = Vec::new();
        let mut expected = Vec::new();
        for _ in 0..20 {
            let mut genome = Vec::new();
            random_genome(&mut rng, 30, 3.0, &mut genome);
            let mut ind = Individual::with_genome(genome.clone());
            evaluate(&mut ind, &sc, Base::None, EvaluationMode::Incremental, &mut EvalScratch::default());
            expected.push((ind.score, ind.sweep.obj_pix));
            moves.push(genome[..genome.len() - 2].iter().map(|a| (a.alpha_deg(), a.dist_m())).collect());
        }
        let got = evaluate_batch(&sc, &moves).unwrap();
        for (g, (score, obj)) in got.iter().zip(&expected) {
            assert_eq!(g.fitness.to_bits(), score.fitness.to_bits());
            assert_eq!(g.cov_final.to_bits(), score.cov_final.to_bits());
            assert_eq!(g.t_final.to_bits(), score.t_final.to_bits());
            assert_eq!(g.obstacle_cells, *obj);
        }
        assert!(expected.iter().any(|(_, obj)| *obj > 0), "some random genome touches a wall");
    }

    #[test]
    fn a_decoded_genome_runs_from_s_through_its_corrected_viewpoints_to_e() {
        let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 };
        let (start, end) = (Point::new(1.3, 1.3), Point::new(9.0, 9.0));
        let sc = ThesisScenario::new(preset("thesis-1").unwrap(), robot, start, end, Projection::F2);
        // East 2 m, then north 20 m (past the map's top edge: clamped inside the map).
        let path = decode(&sc, &[(0.0, 2.0), (90.0, 20.0)]).unwrap();
        assert_eq!(path.first(), Some(&Point::new(1.3, 1.3)));
        assert_eq!(path.last(), Some(&end));
        assert!((path[1] - Point::new(3.3, 1.3)).norm() < 1e-9, "{path:?}");
        // The move would end at y = 21.3; it is clamped to the map's top edge (11 m).
        assert!((path[2] - Point::new(3.3, 11.0)).norm() < 1e-9, "{path:?}");
        // The GA's own decode of the same genome, as its best_path.csv would hold it.
        let mut ind = Individual::with_genome(genome_of(0, &[(0.0, 2.0), (90.0, 20.0)]).unwrap());
        evaluate(&mut ind, &sc, Base::None, EvaluationMode::Incremental, &mut EvalScratch::default());
        assert_eq!(path, sc.driven(&ind.points));
        assert!(decode(&sc, &[]).is_err());
    }

    #[test]
    fn headings_wrap_and_bad_moves_name_their_place() {
        let sc = scenario();
        let a = evaluate_batch(&sc, &[vec![(90.0, 2.0), (0.0, 1.0)]]).unwrap();
        let b = evaluate_batch(&sc, &[vec![(-270.0, 2.0), (720.0, 1.0)]]).unwrap();
        assert_eq!(a, b);
        type Moves = Vec<Vec<(f64, f64)>>;
        let cases: [(Moves, &str); 4] = [
            (vec![vec![(0.0, 1.0)], vec![]], "genome 1, action 0: has 0 actions"),
            (vec![vec![(f64::NAN, 1.0)]], "genome 0, action 0: angle = NaN"),
            (vec![vec![(0.0, 1.0), (0.0, -1.0)]], "genome 0, action 1: distance = -1"),
            (vec![vec![(0.0, f64::INFINITY)]], "genome 0, action 0: distance = inf"),
        ];
        for (genomes, message) in cases {
            let e = evaluate_batch(&sc, &genomes).unwrap_err().to_string();
            assert!(e.starts_with(message), "{e}");
        }
    }

    #[test]
    fn a_straight_move_into_the_wall_sweeps_obstacle_cells() {
        let sc = scenario();
        let r = evaluate_batch(&sc, &[vec![(0.0, 1.0)], vec![(180.0, 5.0)]]).unwrap();
        assert_eq!(r[0].obstacle_cells, 0);
        assert!(r[1].obstacle_cells > 0 && r[1].fitness < r[0].fitness);
        assert_eq!(r[0].row()[3], 0.0);
    }
}
