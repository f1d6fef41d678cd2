use super::*;
use crate::coverage::score::camera_poses;
use crate::map::presets::preset;
use proptest::prelude::*;

fn camera() -> CameraSpec {
    CameraSpec { scale: 0.15, d_min: 0.2, d_max: 7.0, fov_deg: 69.4, sections: 15, band_m: 0.45 }
}

/// The camera is posed at both ends of a segment and every [`CAMERA_STEP_M`] between, looking
/// along it: a 4 m lane gives the union of five views, no more and no fewer.
#[test]
fn the_camera_is_posed_every_metre_along_a_segment_and_at_its_ends() {
    let map = preset("thesis-1").unwrap();
    let layer = CameraLayer::new(&map, &camera(), &[Point::new(1.0, 1.0)]);
    let wm = &layer.map;
    let views = |xs: &[f64]| {
        let mut seen = vec![false; wm.occluded.len()];
        for &x in xs {
            let pos = wm.to_px(x, 1.0);
            layer.camera.view(wm.width, wm.height, |c, r| wm.is_occluded(c, r), pos, 0.0, |i| seen[i] = true);
        }
        let open = seen.iter().filter(|s| **s).count() as f64 / layer.counts[1] as f64;
        let walls = (0..seen.len()).filter(|&i| seen[i] && layer.in_band(i)).count() as f64 / layer.counts[0] as f64;
        (walls, open)
    };
    let lane = vec![Point::new(1.0, 1.0), Point::new(5.0, 1.0)];
    assert_eq!(camera_poses(std::slice::from_ref(&lane)), 5);
    let masked = layer.coverage(std::slice::from_ref(&lane), &mut SegmentViews::default());
    assert_eq!(layer.coverage_by_pose(std::slice::from_ref(&lane)), masked);
    let [walls, open, _, _] = masked;
    assert_eq!((walls, open), views(&[1.0, 2.0, 3.0, 4.0, 5.0]));
    assert!(open > views(&[1.0, 5.0]).1, "the poses between the ends see more");
    // A repeated vertex adds no pose (it has no heading) and a vertex on a pose adds none.
    let repeated = vec![lane[0], lane[0], Point::new(3.0, 1.0), lane[1]];
    let mut views_cache = SegmentViews::default();
    assert_eq!(layer.coverage(&[repeated], &mut views_cache), layer.coverage(&[lane], &mut views_cache));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// The masks give exactly the pose-by-pose union on maps with walls, for plans of one to
    /// three paths, with one cache kept across plans (segments found again, some repeated
    /// within a plan) and a cache small enough to start afresh in the middle of a plan.
    #[test]
    fn segment_masks_give_the_union_pose_by_pose(
        map in 0usize..2,
        plans in proptest::collection::vec(
            proptest::collection::vec(proptest::collection::vec((0.0..1.0f64, 0.0..1.0f64), 1..7), 1..4),
            1..4,
        ),
        small in proptest::bool::ANY,
    ) {
        let map = preset(["thesis-2", "office"][map]).unwrap();
        let layer = CameraLayer::new(&map, &camera(), &[map.origin() + nalgebra::Vector2::new(1.3, 1.3)]);
        let mut views = if small { SegmentViews::with_max_words(300) } else { SegmentViews::default() };
        let at = |(u, v): (f64, f64)| map.origin() + nalgebra::Vector2::new(u * map.width_m(), v * map.height_m());
        let mut viewed = 0;
        for plan in &plans {
            let paths: Vec<Vec<Point>> = plan.iter().map(|p| p.iter().copied().map(at).collect()).collect();
            prop_assert_eq!(layer.coverage(&paths, &mut views), layer.coverage_by_pose(&paths));
            prop_assert!(views.viewed() >= viewed);
            viewed = views.viewed();
        }
        // Scoring the last plan again views nothing new (with the large cache).
        let last: Vec<Vec<Point>> = plans[plans.len() - 1].iter().map(|p| p.iter().copied().map(at).collect()).collect();
        let before = views.viewed();
        let again = layer.coverage(&last, &mut views);
        prop_assert_eq!(again, layer.coverage_by_pose(&last));
        if !small {
            prop_assert_eq!(views.viewed(), before);
        }
    }
}

/// One cache used with two layers of the same raster (cameras of different range) and then
/// with another map's: each coverage is its own layer's, never the masks of the layer before.
#[test]
fn a_cache_used_with_another_layer_starts_afresh() {
    let map = preset("thesis-2").unwrap();
    let short = CameraSpec { d_max: 2.0, ..camera() };
    let s = map.origin() + nalgebra::Vector2::new(1.3, 1.3);
    let path = vec![vec![s, s + nalgebra::Vector2::new(6.0, 0.0), s + nalgebra::Vector2::new(6.0, 6.0)]];
    let (far, near) = (CameraLayer::new(&map, &camera(), &[s]), CameraLayer::new(&map, &short, &[s]));
    let office = preset("office").unwrap();
    let other = CameraLayer::new(&office, &camera(), &[office.origin() + nalgebra::Vector2::new(2.0, 2.0)]);
    let mut views = SegmentViews::default();
    for layer in [&far, &near, &far, &other, &near] {
        assert_eq!(layer.coverage(&path, &mut views), layer.coverage_by_pose(&path));
    }
    assert_ne!(far.coverage_by_pose(&path), near.coverage_by_pose(&path));
}
