//! Evaluator throughput: a 100-segment random path on thesis-1 (issue: evaluations per second
//! and swept cells per second).

use covga::coverage::{CoverageGrid, Footprint, SweepScratch};
use covga::geom::Point;
use covga::map::presets::preset;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use std::hint::black_box;

fn evaluate(c: &mut Criterion) {
    let map = preset("thesis-1").expect("preset");
    let grid = CoverageGrid::new(&map);
    let mut scratch = SweepScratch::new(&grid);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let path: Vec<Point> =
        (0..=100).map(|_| Point::new(rng.random_range(1.0..10.0), rng.random_range(1.0..10.0))).collect();
    let robot = Footprint::default();
    let swept = robot.measure(&grid, &mut scratch, &path);
    let cells = swept.cells_swept + swept.obstacle_cells;
    let mut group = c.benchmark_group("evaluate");
    group.throughput(Throughput::Elements(1));
    group.bench_function("random_100_segments/evaluations", |b| {
        b.iter(|| black_box(robot.measure(&grid, &mut scratch, black_box(&path))))
    });
    let layers = covga::coverage::bits::BitLayers::new(&grid);
    let mut planes = covga::coverage::planes::VisitPlanes::default();
    group.bench_function("random_100_segments/bit_rows", |b| {
        b.iter(|| black_box(layers.sweep(&mut planes, black_box(&path), 0.6)))
    });
    let rows: usize = path
        .windows(2)
        .map(|w| {
            let mut n = 0;
            covga::coverage::rows::for_each_swept_row(&grid_raster(&grid), w[0], w[1], 0.6, |_, _, _| n += 1);
            n
        })
        .sum();
    eprintln!("random path: {cells} cells, {rows} row runs");
    group.bench_function("random_100_segments/row_scan_only", |b| {
        b.iter(|| {
            let mut n = 0usize;
            for w in black_box(&path).windows(2) {
                covga::coverage::rows::for_each_swept_row(&grid_raster(&grid), w[0], w[1], 0.6, |r, lo, hi| {
                    n += r + lo + hi
                });
            }
            black_box(n)
        })
    });
    group.throughput(Throughput::Elements(cells));
    group.bench_function("random_100_segments/swept_cells", |b| {
        b.iter(|| black_box(robot.measure(&grid, &mut scratch, black_box(&path))))
    });
    let start = Point::new(1.3, 1.3);
    let lanes = covga::patterns::plan(
        &map,
        covga::patterns::Pattern::Boustrophedon { angle_deg: 0.0 },
        0.6,
        start,
        start,
        false,
    )
    .expect("pattern")
    .points;
    let tilted = covga::patterns::plan(
        &map,
        covga::patterns::Pattern::Boustrophedon { angle_deg: 30.0 },
        0.6,
        start,
        start,
        false,
    )
    .expect("pattern")
    .points;
    for (name, p) in [("boustrophedon_0deg", &lanes), ("boustrophedon_30deg", &tilted)] {
        let m = robot.measure(&grid, &mut scratch, p);
        group.throughput(Throughput::Elements(m.cells_swept + m.obstacle_cells));
        group.bench_function(format!("{name}/swept_cells"), |b| {
            b.iter(|| black_box(robot.measure(&grid, &mut scratch, black_box(p))))
        });
    }
    group.finish();
}

fn grid_raster(g: &CoverageGrid) -> covga::coverage::raster::RasterGrid {
    *g.raster()
}

criterion_group!(benches, evaluate);
criterion_main!(benches);
