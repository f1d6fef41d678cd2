use super::*;

fn cam() -> Camera {
    Camera { d_min: 1.0, d_max: 20.0, fov: 60f64.to_radians(), sections: 7, shape: ViewShape::Sections }
}

#[test]
fn eq_1_cuts_each_section_at_its_obstacle() {
    assert_eq!(d_view(20.0, 1.0, f64::INFINITY), 20.0);
    assert_eq!(d_view(20.0, 1.0, 5.0), 5.0);
    assert_eq!(d_view(20.0, 1.0, 0.5), 1.0);
    assert_eq!(cam().section(0.0), Some(3));
    assert_eq!(cam().section(-30f64.to_radians()), Some(0));
    assert_eq!(cam().section(30f64.to_radians()), Some(6));
    assert_eq!(cam().section(31f64.to_radians()), None);
}

#[test]
fn a_camera_facing_a_wall_sees_nothing_behind_it() {
    // 40 x 40 free raster with a wall at column 20; camera at (10.5, 20.5) facing +x.
    let (w, h) = (40usize, 40usize);
    let occ = |c: i64, r: i64| c < 0 || r < 0 || c >= w as i64 || r >= h as i64 || c == 20;
    let mut seen = Vec::new();
    cam().view(w, h, occ, (10.5, 20.5), 0.0, |i| seen.push(i));
    assert!(!seen.is_empty());
    assert!(seen.iter().all(|&i| i % w < 20), "nothing at or behind the wall");
    assert!(seen.iter().any(|&i| i % w == 19), "up to the wall");
    // Facing away from the wall it sees the open side only, up to d_max.
    let mut back = Vec::new();
    cam().view(w, h, occ, (10.5, 20.5), std::f64::consts::PI, |i| back.push(i));
    assert!(back.iter().all(|&i| i % w <= 10));
    // Nothing closer than d_min.
    assert!(seen.iter().all(|&i| ((i % w) as f64 + 0.5 - 10.5).hypot((i / w) as f64 + 0.5 - 20.5) >= 1.0));
}

#[test]
fn the_fan_spans_from_the_first_ray_to_the_last_ray() {
    // Open 60 x 60 raster, camera at (20.5, 20.5) facing +x, 60 deg in 7 sections: the rays
    // stand at -30, -21.4, ..., +21.4 deg, so bearing +24 deg (pixel (29, 24), range 9.85) is
    // outside the fan although inside the field of view; bearing -24 deg is inside both.
    let (w, h) = (60usize, 60usize);
    let occ = |c: i64, r: i64| c < 0 || r < 0 || c >= w as i64 || r >= h as i64;
    let fan = Camera { shape: ViewShape::Fan, ..cam() };
    let seen = |camera: &Camera| {
        let mut v = Vec::new();
        camera.view(w, h, occ, (20.5, 20.5), 0.0, |i| v.push(i));
        v
    };
    let (by_sections, by_fan) = (seen(&cam()), seen(&fan));
    assert!(by_sections.contains(&(24 * w + 29)) && !by_fan.contains(&(24 * w + 29)));
    assert!(by_sections.contains(&(16 * w + 29)) && by_fan.contains(&(16 * w + 29)));
    // Nothing nearer than d_min = 1 px or farther than d_max = 20 px.
    for i in &by_fan {
        let d = ((i % w) as f64 - 20.0).hypot((i / w) as f64 - 20.0);
        assert!((0.99..=20.01).contains(&d), "pixel {i} at {d}");
    }
}

#[test]
fn fan_polygon_vertices_by_hand() {
    // Two sections over 90 deg at the origin facing +x: rays at -45 and 0 deg with depths
    // 10 and 4, then the d_min = 1 points of the last ray (0 deg) and the first (-45 deg).
    let c = Camera { d_min: 1.0, d_max: 10.0, fov: 90f64.to_radians(), sections: 2, shape: ViewShape::Fan };
    let poly = c.fan_polygon((0.0, 0.0), 0.0, &[10.0, 4.0]);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let expected = [(10.0 * h, -10.0 * h), (4.0, 0.0), (1.0, 0.0), (h, -h)];
    assert_eq!(poly.len(), expected.len());
    for (p, e) in poly.iter().zip(expected) {
        assert!((p.0 - e.0).abs() < 1e-12 && (p.1 - e.1).abs() < 1e-12, "{p:?} vs {e:?}");
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(4000))]

    /// Each section's nearest occluder is the same with and without the pre-filter, which cuts
    /// each ring to the wedge of the sections still open: random walls from sparse to dense,
    /// poses (on pixel centres and corners too), headings, fields of view (mostly under the
    /// half turn where the cut applies) and sections (wide ones close unevenly).
    #[test]
    fn the_prefilter_changes_no_section_depth(
        seed in 0u64..1_000_000, x in 0.0..48.0f64, y in 0.0..48.0f64,
        corner in proptest::prelude::any::<bool>(), psi in -7.0..7.0f64, fov_deg in 1.0..220.0f64,
        sections in 1usize..12, density in 0.005..0.3f64, d_max in 1.0..40.0f64,
    ) {
        use rand::{Rng, SeedableRng};
        let (w, h) = (48usize, 48usize);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let walls: Vec<bool> = (0..w * h).map(|_| rng.random_bool(density)).collect();
        let occ = |c: i64, r: i64| c < 0 || r < 0 || c >= w as i64 || r >= h as i64 || walls[r as usize * w + c as usize];
        let pos = if corner { (x.floor(), y.floor()) } else { (x.floor() + 0.5, y.floor() + 0.5) };
        let camera = Camera { d_min: 0.5, d_max, fov: fov_deg.to_radians(), sections, shape: ViewShape::Sections };
        let depths = |prefilter: bool| {
            frame::Frame::new(&camera, (w, h), (pos, psi), prefilter, true).nearest_occluders(&camera, &occ)
        };
        proptest::prop_assert_eq!(depths(true), depths(false));
    }
}

proptest::proptest! {
    /// Passing over out-of-range and out-of-view pixels changes no viewed pixel: random
    /// walls, poses (on pixel centres and corners too), headings, fields of view up to a
    /// whole turn, both shapes.
    #[test]
    fn the_prefilter_changes_no_view(
        seed in 0u64..1_000_000,
        x in 0.0..40.0f64, y in 0.0..40.0f64, corner in proptest::prelude::any::<bool>(),
        psi in -7.0..7.0f64, fov_deg in 1.0..360.0f64, sections in 1usize..20,
        d_min in 0.0..6.0f64, d_max in 1.0..25.0f64, fan in proptest::prelude::any::<bool>(),
    ) {
        use rand::{Rng, SeedableRng};
        let (w, h) = (40usize, 40usize);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let walls: Vec<bool> = (0..w * h).map(|_| rng.random_bool(0.08)).collect();
        let occ = |c: i64, r: i64| c < 0 || r < 0 || c >= w as i64 || r >= h as i64 || walls[r as usize * w + c as usize];
        let pos = if corner { (x.floor(), y.floor()) } else { (x.floor() + 0.5, y.floor() + 0.5) };
        let shape = if fan { ViewShape::Fan } else { ViewShape::Sections };
        let camera = Camera { d_min, d_max, fov: fov_deg.to_radians(), sections, shape };
        let seen = |prefilter: bool| {
            let mut v = Vec::new();
            camera.view_filtered(w, h, occ, pos, psi, prefilter, true, |_| false, |i| v.push(i));
            v
        };
        proptest::prop_assert_eq!(seen(true), seen(false));
    }

    /// A `d_max` far beyond the raster, capped to it, changes no viewed pixel: random walls,
    /// poses anywhere on the raster, headings, fields of view, sections and depth ranges.
    #[test]
    fn capping_d_max_at_the_raster_changes_no_view(
        seed in 0u64..1_000_000, x in 0.0..12.0f64, y in 0.0..12.0f64,
        psi in -7.0..7.0f64, fov_deg in 1.0..360.0f64, sections in 1usize..40,
        d_min in 0.0..20.0f64, d_max in 1.0..120.0f64,
    ) {
        use rand::{Rng, SeedableRng};
        let (w, h) = (12usize, 9usize);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let walls: Vec<bool> = (0..w * h).map(|_| rng.random_bool(0.1)).collect();
        let occ = |c: i64, r: i64| c < 0 || r < 0 || c >= w as i64 || r >= h as i64 || walls[r as usize * w + c as usize];
        let camera = Camera { d_min, d_max: d_max.max(d_min + 0.1), fov: fov_deg.to_radians(), sections, shape: ViewShape::Sections };
        let pos = (x, y.min(h as f64));
        let seen = |capped: bool| {
            let mut v = Vec::new();
            camera.view_filtered(w, h, occ, pos, psi, true, capped, |_| false, |i| v.push(i));
            v
        };
        proptest::prop_assert_eq!(seen(true), seen(false));
    }

    /// Marking views into a union, passing over the pixels already in it, gives the union
    /// of the full views: random walls, up to eight poses, headings and depth ranges.
    #[test]
    fn the_union_of_views_skips_nothing_it_needs(
        seed in 0u64..1_000_000, poses in proptest::collection::vec((0.0..30.0f64, 0.0..30.0f64, -7.0..7.0f64), 1..8),
        fov_deg in 1.0..360.0f64, sections in 1usize..20, d_min in 0.0..4.0f64, d_max in 1.0..20.0f64,
    ) {
        use rand::{Rng, SeedableRng};
        let (w, h) = (30usize, 30usize);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let walls: Vec<bool> = (0..w * h).map(|_| rng.random_bool(0.08)).collect();
        let occ = |c: i64, r: i64| c < 0 || r < 0 || c >= w as i64 || r >= h as i64 || walls[r as usize * w + c as usize];
        let camera = Camera { d_min, d_max: d_max.max(d_min + 0.1), fov: fov_deg.to_radians(), sections, shape: ViewShape::Sections };
        let (mut full, mut union) = (vec![false; w * h], vec![false; w * h]);
        for &(x, y, psi) in &poses {
            camera.view(w, h, occ, (x, y), psi, |i| full[i] = true);
            camera.view_into(w, h, occ, (x, y), psi, &mut union);
        }
        proptest::prop_assert_eq!(full, union);
    }
}

/// Section edges and range bounds through pixel centres (headings along the axes and
/// diagonals, a pose on a pixel centre, ranges of whole pixels): the pre-filter's margins
/// pass over no pixel on an edge, so the views are the same with and without it.
#[test]
fn edges_through_pixel_centres_change_no_view() {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
    let (w, h) = (31usize, 31usize);
    let walls: Vec<bool> = (0..w * h).map(|i| i % 7 == 3 && i / w > 20).collect();
    let occ = |c: i64, r: i64| c < 0 || r < 0 || c >= w as i64 || r >= h as i64 || walls[r as usize * w + c as usize];
    for psi in [0.0, FRAC_PI_4, FRAC_PI_2, -FRAC_PI_2, PI, 3.0 * FRAC_PI_4] {
        for (fov, sections) in [(FRAC_PI_2, 2), (FRAC_PI_2, 4), (PI / 3.0, 3), (FRAC_PI_2 + 1e-12, 2)] {
            for (d_min, d_max) in [(0.0, 10.0), (2.0, 8.0), (1.0, 5.0)] {
                let camera = Camera { d_min, d_max, fov, sections, shape: ViewShape::Sections };
                let seen = |prefilter: bool| {
                    let mut v = Vec::new();
                    camera.view_filtered(w, h, occ, (15.5, 15.5), psi, prefilter, true, |_| false, |i| v.push(i));
                    v
                };
                let fast = seen(true);
                assert!(!fast.is_empty());
                assert_eq!(fast, seen(false), "psi {psi} fov {fov} m {sections} range {d_min}..{d_max}");
            }
        }
    }
}
