use crate::{MapConfig, MapSize, ReliefConfig, Terrain, TileKind};

fn config(relief: ReliefConfig) -> MapConfig {
    let mut c = MapConfig { size: MapSize::Bounded { x: 40, z: 30 }, relief, ..MapConfig::default() };
    c.terrain.inner_rings = 3;
    c
}

/// Relief lifts mountain centers (the plateau becomes a peak) and changes nothing when off.
#[test]
fn relief_raises_mountain_centers_and_is_off_by_default() {
    let flat = Terrain::new(config(ReliefConfig::default())).unwrap();
    let peaked = Terrain::new(config(ReliefConfig::MOUNTAINS)).unwrap();
    let (a, b) = (flat.generate_map().unwrap(), peaked.generate_map().unwrap());
    let mut raised = 0;
    let mut mountains = 0;
    for tile in flat.tiles() {
        if flat.tile_kind(tile) != TileKind::Mountain {
            continue;
        }
        mountains += 1;
        let center = flat.lattice().tile_center(tile);
        let (h0, h1) = (flat.vertex(center).height, peaked.vertex(center).height);
        assert!(h1 >= h0);
        if h1 > h0 + 0.02 {
            raised += 1;
        }
    }
    assert!(mountains > 10, "{mountains} mountains");
    assert!(raised * 2 > mountains, "{raised} of {mountains} mountain centers raised");
    assert_ne!(a.buffers.positions, b.buffers.positions);
    let off = Terrain::new(MapConfig { size: MapSize::Bounded { x: 40, z: 30 }, ..MapConfig::default() }).unwrap();
    let mut map0 = MapConfig { size: MapSize::Bounded { x: 40, z: 30 }, ..MapConfig::default() };
    map0.relief = ReliefConfig::default();
    assert_eq!(off.generate_map().unwrap(), Terrain::new(map0).unwrap().generate_map().unwrap());
}
