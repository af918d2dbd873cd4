use crate::{MapConfig, MapSize, ReliefConfig, Terrain, TileKind};

fn config(relief: ReliefConfig) -> MapConfig {
    let mut c = MapConfig { size: MapSize::Bounded { x: 40, z: 30 }, relief, ..MapConfig::default() };
    c.terrain.inner_rings = 3;
    c
}

/// Relief lifts mountain centers (the plateau becomes a peak) and changes nothing without hex
/// unity.
#[test]
fn relief_raises_mountain_centers_and_needs_hex_unity() {
    let flat = Terrain::new(config(ReliefConfig::default())).unwrap();
    let peaked = Terrain::new(config(ReliefConfig::MOUNTAINS)).unwrap();
    let (a, b) = (flat.generate_map().unwrap(), peaked.generate_map().unwrap());
    let mut raised = 0;
    let mut mountains = 0;
    for tile in flat.tiles() {
        if flat.tile_kind(tile).unwrap() != TileKind::Mountain {
            continue;
        }
        mountains += 1;
        let center = flat.lattice().tile_center(tile);
        let (h0, h1) = (flat.vertex(center).unwrap().height, peaked.vertex(center).unwrap().height);
        assert!(h1 >= h0);
        if h1 > h0 + 0.02 {
            raised += 1;
        }
    }
    assert!(mountains > 10, "{mountains} mountains");
    assert!(raised * 2 > mountains, "{raised} of {mountains} mountain centers raised");
    assert_ne!(a.buffers.positions, b.buffers.positions);
    // Relief shapes tiles inside the ranges hex unity gives them: without hex unity it is off.
    let mut raw_flat = config(ReliefConfig::default());
    raw_flat.manipulation.hex_unity = false;
    let mut raw_peaked = config(ReliefConfig::MOUNTAINS);
    raw_peaked.manipulation.hex_unity = false;
    let (c, d) = (Terrain::new(raw_flat).unwrap(), Terrain::new(raw_peaked).unwrap());
    assert_eq!(c.generate_map().unwrap(), d.generate_map().unwrap());
}
