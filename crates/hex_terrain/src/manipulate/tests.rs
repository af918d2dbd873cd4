use super::*;

fn thresholds(tol: f32) -> Thresholds {
    Thresholds { sea: 0.3, mountain: 0.7, tolerance: tol }
}

#[test]
fn interpolation_maps_each_band_into_its_range() {
    let t = thresholds(0.03);
    let mut prev = -1.0;
    for i in 0..=1000 {
        let h = i as f32 / 1000.0;
        let v = t.interpolate(h);
        assert!(v >= prev, "not monotone at {h}");
        prev = v;
        let (lo, hi) = t.range(t.classify(h));
        assert!(v >= lo - 1e-6 && v <= hi + 1e-6, "{h} -> {v} outside {lo}..{hi}");
    }
    assert_eq!(t.interpolate(0.0), 0.0);
    assert_eq!(t.interpolate(1.0), 1.0);
    assert_eq!(thresholds(0.0).interpolate(0.42), 0.42);
}

#[test]
fn inner_vertices_end_in_range_with_clamp_but_not_always_with_thesis() {
    let t = thresholds(0.03);
    let config = ManipulationConfig::default();
    let thesis = ManipulationConfig { pull: PullMode::Thesis, ..ManipulationConfig::default() };
    let mut thesis_outside = 0;
    for kind in TileKind::ALL {
        let (lo, hi) = t.range(kind);
        for i in 0..=100 {
            let raw = i as f32 / 100.0;
            let m = manipulate(&t, &config, raw, 1, 2, Some((kind, kind)));
            assert!(m.height >= lo && m.height <= hi);
            let m = manipulate(&t, &thesis, raw, 1, 2, Some((kind, kind)));
            thesis_outside += usize::from(m.height < lo || m.height > hi);
        }
    }
    assert!(thesis_outside > 0, "Algorithm 3 as written leaves far vertices outside");
}

#[test]
fn borders_go_to_the_threshold_between_types() {
    let t = thresholds(0.03);
    let c = ManipulationConfig::default();
    use TileKind::*;
    assert_eq!(manipulate(&t, &c, 0.9, 2, 2, span(&[Sea, Land])).height, 0.3);
    assert_eq!(manipulate(&t, &c, 0.1, 2, 2, span(&[Mountain, Land])).height, 0.7);
    assert_eq!(manipulate(&t, &c, 0.1, 2, 2, span(&[Mountain, Sea, Land])).height, 0.5);
    // same type: edge correction pulls into the range
    let m = manipulate(&t, &c, 0.9, 2, 2, span(&[Land, Land]));
    assert_eq!(m.height, 0.67);
    assert!(m.moved);
    // off: untouched apart from interpolation
    let off = ManipulationConfig { edge_correction: false, ..c.clone() };
    assert_eq!(manipulate(&t, &off, 0.9, 2, 2, span(&[Land, Land])).height, t.interpolate(0.9));
    // outside the map: nothing to unify with
    assert_eq!(manipulate(&t, &c, 0.9, 2, 2, None).height, t.interpolate(0.9));
}
