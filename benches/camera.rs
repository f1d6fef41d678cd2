//! The camera model's speed target on `experiments/maps/basement.yaml` (skipped with a message
//! where the map is not beside the checkout): the camera coverage of a 100 m stretch of the
//! boustrophedon plan, pose by pose as the scorer did before the masks (`by_pose`), with every
//! segment new (`masks_cold`), with every segment's views kept from an earlier plan
//! (`masks_warm`, what an optimiser pays for a plan it has seen the segments of), and with
//! the warm cache and one segment in the middle moved (`masks_one_new`, a mutation).
//!
//! `RAYON_NUM_THREADS=1 cargo bench --bench camera`

use covga::coverage::views::{CameraLayer, SegmentViews};
use covga::experiment::file::ExperimentFile;
use covga::geom::Point;
use covga::patterns::{self, Pattern};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::Path;

/// The first `metres` of `path` (cut inside the segment that reaches it).
fn first_metres(path: &[Point], metres: f64) -> Vec<Point> {
    let mut out = vec![path[0]];
    let mut left = metres;
    for w in path.windows(2) {
        let len = (w[1] - w[0]).norm();
        if len >= left {
            out.push(w[0] + (w[1] - w[0]) * (left / len));
            return out;
        }
        left -= len;
        out.push(w[1]);
    }
    out
}

fn bench(c: &mut Criterion) {
    let map = Path::new("experiments/maps/basement.yaml");
    if !map.exists() {
        eprintln!("camera bench: {} is missing (run from the repository root); nothing to measure", map.display());
        return;
    }
    let mut file = ExperimentFile::default();
    file.map.source = map.display().to_string();
    file.stations.start = [0.0, 0.0];
    let exp = file.validate("bench", Path::new("."), "bench").expect("valid");
    let s = &exp.scenario;
    let plan = patterns::plan(&s.map, Pattern::Boustrophedon { angle_deg: 0.0 }, s.robot.width, s.start, s.end, true)
        .expect("a boustrophedon on basement");
    let path = first_metres(&plan.points, 100.0);
    let layer = CameraLayer::new(&s.map, &s.camera, &[s.start]);
    let paths = vec![path.clone()];
    let mut moved = path.clone();
    let mid = moved.len() / 2;
    moved[mid] += nalgebra::Vector2::new(0.05, 0.05);
    let moved = vec![moved];
    assert_eq!(layer.coverage(&paths, &mut SegmentViews::default()), layer.coverage_by_pose(&paths));
    let mut group = c.benchmark_group("camera_100m_basement");
    group.sample_size(20);
    group.bench_function("by_pose", |b| b.iter(|| layer.coverage_by_pose(black_box(&paths))));
    group.bench_function("masks_cold", |b| b.iter(|| layer.coverage(black_box(&paths), &mut SegmentViews::default())));
    let mut warm = SegmentViews::default();
    layer.coverage(&paths, &mut warm);
    group.bench_function("masks_warm", |b| b.iter(|| layer.coverage(black_box(&paths), &mut warm)));
    group.bench_function("masks_one_new", |b| {
        b.iter(|| {
            let mut views = warm.clone();
            layer.coverage(black_box(&moved), &mut views)
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
