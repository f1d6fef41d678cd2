//! What the thesis GA's coverage objective measures (`thesis.objective`): 003's swept footprint
//! (eq. 3.6, the default) or, for the ablation's search-versus-objective comparison, 000's
//! camera coverage (eq. 2) along the driven path, as the waypoint planner optimises it.
//!
//! With the camera, `cov_final` becomes `C = α_cov·C_open + (1 − α_cov)·C_walls` (000 eq. 2,
//! `α_cov` from `waypoint.alpha_cov`) over the common scorer's camera raster, the camera posed
//! as the scorer poses it (every metre along each move and at its ends, looking along it);
//! `t_final` (eq. 3.10), the projection (eqs. 3.14–3.15) and the obstacle penalty (eq. 3.16)
//! stay 003's. A move's views are kept per segment ([`SegmentViews`]), so a plan costs an OR
//! of the views of its moves plus the views of the moves no earlier plan had.

use crate::coverage::camera::blended_coverage;
use crate::coverage::fitness::{Projection, ThesisScore, f_obstacle};
use crate::coverage::score::CameraSpec;
use crate::coverage::views::{CameraLayer, SegmentViews};
use crate::geom::Point;
use crate::map::GridMap;
use serde::{Deserialize, Serialize};

/// `thesis.objective`: what `cov_final` measures.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Objective {
    /// The robot's swept footprint (003 eq. 3.6).
    #[default]
    Footprint,
    /// 000's camera coverage of walls and open space (eq. 2) along the driven path.
    Camera,
}

impl Objective {
    /// Whether this is 003's footprint objective (the default, left out of written files).
    pub fn is_footprint(&self) -> bool {
        matches!(self, Objective::Footprint)
    }
}

/// The camera objective of a scenario: the scorer's camera layer and `α_cov`.
pub struct CameraObjective {
    layer: CameraLayer,
    alpha_cov: f64,
}

impl std::fmt::Debug for CameraObjective {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CameraObjective").field("alpha_cov", &self.alpha_cov).finish_non_exhaustive()
    }
}

impl CameraObjective {
    /// The camera objective on `map` with the camera `spec`, weight `alpha_cov` (in [0, 1]) and
    /// the stations the scorer's reachable pixels are connected to.
    pub fn new(map: &GridMap, spec: &CameraSpec, alpha_cov: f64, stations: &[Point]) -> Self {
        Self { layer: CameraLayer::new(map, spec, stations), alpha_cov }
    }

    /// `C` of 000 eq. 2 over all free pixels of the path `driven` (the path the robot drives:
    /// the viewpoints, or the routes between them).
    pub fn coverage(&self, driven: &[Point], views: &mut SegmentViews) -> f64 {
        let [walls, open, _, _] = self.layer.coverage(&[driven], views);
        blended_coverage(self.alpha_cov, open, walls)
    }
}

/// `score` with `cov_final` replaced by `coverage` (in [0, 1]): `t_final` kept, both
/// projections (003 eqs. 3.14–3.15) and the penalty of `obj_pix` obstacle cells (eq. 3.16)
/// computed again.
pub fn with_coverage(score: ThesisScore, coverage: f64, obj_pix: u64, projection: Projection) -> ThesisScore {
    let t = score.t_final;
    let (f1, f2) = (Projection::F1.apply(t, coverage), Projection::F2.apply(t, coverage));
    ThesisScore { cov_final: coverage, t_final: t, f1, f2, fitness: f_obstacle(projection.apply(t, coverage), obj_pix) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::Footprint;
    use crate::map::presets::preset;
    use crate::thesis::genome::random_genome;
    use crate::thesis::individual::{Base, EvalScratch, EvaluationMode, Individual, evaluate};
    use crate::thesis::scenario::ThesisScenario;

    fn spec() -> CameraSpec {
        CameraSpec { scale: 0.15, d_min: 0.2, d_max: 7.0, fov_deg: 69.4, sections: 15, band_m: 0.45 }
    }

    /// With the camera objective, `cov_final` is eq. 2 of the scorer's pose-by-pose camera
    /// coverage of the viewpoints' path, `t_final` is the footprint's, and the fitness is the
    /// projection of the two with the obstacle penalty; with `α_cov` = 1 it is the open
    /// coverage alone.
    #[test]
    fn camera_cov_final_is_eq_2_of_the_scorer_s_views() {
        let map = preset("office").unwrap();
        let s = Point::new(2.0, 2.0);
        let robot = Footprint::default();
        let mut rng = crate::ga::rng::stream(7, crate::ga::rng::Purpose::Main, &[]);
        for alpha in [0.1, 1.0] {
            let plain = ThesisScenario::new(map.clone(), robot, s, s, Projection::F2);
            let camera = CameraObjective::new(&map, &spec(), alpha, &[s]);
            let layer = CameraLayer::new(&map, &spec(), &[s]);
            let with = ThesisScenario::new(map.clone(), robot, s, s, Projection::F2).with_camera(Some(camera));
            for _ in 0..5 {
                let mut ind = Individual::default();
                random_genome(&mut rng, 20, 4.0, &mut ind.genome);
                let mut foot = Individual::with_genome(ind.genome.clone());
                evaluate(&mut ind, &with, Base::None, EvaluationMode::Incremental, &mut EvalScratch::default());
                evaluate(&mut foot, &plain, Base::None, EvaluationMode::Incremental, &mut EvalScratch::default());
                let [walls, open, _, _] = layer.coverage_by_pose(std::slice::from_ref(&ind.points));
                let c = alpha * open + (1.0 - alpha) * walls;
                assert_eq!(ind.score.cov_final, c);
                assert_eq!(ind.score.t_final, foot.score.t_final);
                assert_eq!(ind.score.f2, ind.score.t_final * c);
                assert_eq!(ind.score.fitness, f_obstacle(ind.score.f2, ind.sweep.obj_pix));
                assert_ne!(ind.score.cov_final, foot.score.cov_final);
            }
        }
    }
}
