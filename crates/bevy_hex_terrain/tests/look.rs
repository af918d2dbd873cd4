//! Water and props in a headless app: each chunk's props are the core's placement (capped,
//! deterministic), they and the water surfaces are children of their chunk and leave with it, a
//! long walk keeps their number bounded, and the settings switch them off and on at run time.

mod common;

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{ChunkContent, HexPropSettings, HexTerrainPlugins};
use common::*;
use hex_terrain::Terrain;

/// A 40x30 Map0 with forests on its middle land band and rocks on its mountains.
fn wooded() -> MapConfig {
    let mut c = MapConfig { size: MapSize::Bounded { x: 40, z: 30 }, chunk_size: (8, 8), ..MapConfig::default() };
    c.noise.scale = 40.0;
    c
}

/// Every chunk full (levels of detail off): these tests compare props with the core's full
/// placement; `detail.rs` tests the props of coarse chunks.
fn app_with_props(config: MapConfig, radius: u32, props: HexPropSettings) -> App {
    let settings = HexStreamingSettings { coarse_distance: None, ..settings(radius) };
    let mut app = app_with(config.into(), settings, None);
    app.insert_resource(props);
    app
}

/// Every prop entity: its chunk, kind, variant, tile and transform.
fn props(app: &mut App) -> Vec<(ChunkCoord, HexProp, Transform)> {
    let mut out: Vec<_> = app
        .world_mut()
        .query::<(&HexProp, &Transform, &ChildOf)>()
        .iter(app.world())
        .map(|(p, t, parent)| (parent.parent(), *p, *t))
        .collect::<Vec<_>>()
        .into_iter()
        .map(|(chunk, p, t)| (app.world().get::<HexChunk>(chunk).expect("a prop's parent is a chunk").coord, p, t))
        .collect();
    out.sort_by(|a, b| {
        (a.0, a.1.tile.x, a.1.tile.y, a.2.translation.x.to_bits(), a.2.translation.z.to_bits()).cmp(&(
            b.0,
            b.1.tile.x,
            b.1.tile.y,
            b.2.translation.x.to_bits(),
            b.2.translation.z.to_bits(),
        ))
    });
    out
}

fn count<T: Component>(app: &mut App) -> usize {
    app.world_mut().query_filtered::<(), With<T>>().iter(app.world()).count()
}

#[test]
fn props_are_the_cores_capped_placement_and_the_same_every_time() {
    let cap = 12;
    let props_settings = HexPropSettings { max_per_chunk: cap, ..default() };
    let mut app = app_with_props(wooded(), 8, props_settings);
    spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "terrain ready", ready);
    run_until(&mut app, "props settled", props_settled);
    let placed = props(&mut app);
    assert!(placed.len() > 20, "the wooded map grows props: {}", placed.len());
    let terrain = Terrain::new(wooded()).unwrap();
    let size = terrain.config().layout.hex_size;
    for chunk in terrain.chunks() {
        let mine: Vec<_> = placed.iter().filter(|(c, ..)| *c == chunk).collect();
        assert!(mine.len() <= cap, "chunk {chunk:?} has {} props over the cap of {cap}", mine.len());
        let expected = terrain.props(&terrain.generate_chunk(chunk).unwrap(), cap, 1.0);
        assert_eq!(mine.len(), expected.len(), "chunk {chunk:?}");
        for p in &expected {
            let at = Vec3::from_array(p.position);
            assert!(
                mine.iter().any(|(_, prop, t)| prop.tile == p.tile
                    && prop.kind == p.kind
                    && t.translation.distance(at) < 1e-5
                    && (t.scale.x - p.scale * size).abs() < 1e-5),
                "chunk {chunk:?}: the core's prop {p:?} is not spawned"
            );
        }
    }
    // The same map in another app: the same props.
    let mut again = app_with_props(wooded(), 8, props_settings);
    spawn_agent(&mut again, Vec3::ZERO);
    run_until(&mut again, "terrain ready", ready);
    run_until(&mut again, "props settled", props_settled);
    assert_eq!(placed, props(&mut again));
    // Water surfaces are children of chunks with sea below them.
    let waters = count::<HexWater>(&mut app);
    assert!(waters > 0 && waters <= terrain.chunks().len(), "{waters} water surfaces");
}

#[test]
fn walking_keeps_props_and_water_with_their_chunks() {
    let mut config = unbounded((6, 6));
    config.noise.scale = 40.0;
    let cap = 40;
    let mut app = app_with_props(config, 1, HexPropSettings { max_per_chunk: cap, ..default() });
    let agent = spawn_agent(&mut app, Vec3::ZERO);
    let mut max_entities = 0;
    let mut settled = Vec::new();
    for step in 0..240 {
        let at = Vec3::new(step as f32 * 4.5, 0.0, 0.0);
        app.world_mut().entity_mut(agent).insert(Transform::from_translation(at));
        for _ in 0..3 {
            app.update();
        }
        max_entities = max_entities.max(app.world().entities().count_spawned() as usize);
        if step % 60 == 59 {
            run_until(&mut app, "terrain ready", ready);
            app.update();
            settled.push(app.world().entities().count_spawned() as usize);
        }
    }
    run_until(&mut app, "terrain ready at the end", ready);
    run_until(&mut app, "props settled at the end", props_settled);
    let live = app.world().resource::<ChunkStreamer>().live_chunks();
    // radius + prefetch + hysteresis = 3: at most 49 chunks, each with a water surface and at
    // most `cap` props, and at most `MAX_RETIRED_CHUNKS` dropped ones whose children are going.
    assert!(live <= 49);
    let bound = (49 + bevy_hex_terrain::MAX_RETIRED_CHUNKS) * (2 + cap) + 16;
    assert!(max_entities <= bound, "entities peaked at {max_entities}");
    let (lo, hi) = (settled.iter().min().unwrap(), settled.iter().max().unwrap());
    assert!(*hi <= bound && *lo > 0, "settled entity counts {settled:?}");
    // Every prop and water surface belongs to a live chunk, and every live chunk shows all of
    // its content: despawned chunks took theirs with them.
    let expected: usize = app.world_mut().query::<&ChunkContent>().iter(app.world()).map(|c| c.props.len()).sum();
    assert_eq!(props(&mut app).len(), expected);
    let wet = app.world_mut().query::<&ChunkContent>().iter(app.world()).filter(|c| c.water.is_some()).count();
    assert_eq!(count::<HexWater>(&mut app), wet);
    // Meshes: a terrain and at most a water mesh a chunk (props share a few meshes, headless none).
    let meshes = app.world().resource::<Assets<Mesh>>().len();
    assert!(meshes <= 2 * 49, "{meshes} meshes alive: despawned chunks must free theirs");
}

/// Props come and go a budget a frame: walking over a wooded world, no frame spawns more prop
/// entities than `HexPropSettings::max_spawns_per_frame`, nor despawns more of a dropped chunk's
/// children than `HexStreamingSettings::max_despawns_per_frame` (a chunk with at most a few
/// children goes at once); a dropped chunk is no chunk any more from the frame it is dropped,
/// and once settled every loaded chunk shows all its props and no dropped chunk's are left.
#[test]
fn props_come_and_go_a_budget_a_frame() {
    let mut config = unbounded((8, 8));
    config.noise.scale = 40.0;
    let budget = 40;
    let streaming = HexStreamingSettings { max_despawns_per_frame: budget, ..settings(1) };
    let mut app = app_with(config.into(), streaming, None);
    app.insert_resource(HexPropSettings { max_spawns_per_frame: budget, max_per_chunk: 120, ..default() });
    let agent = spawn_agent(&mut app, Vec3::ZERO);
    let mut live: std::collections::HashSet<Entity> = std::collections::HashSet::new();
    let (mut most_spawned, mut most_gone, mut retired_seen) = (0, 0, 0);
    // A chunk (8 flat columns, 12 units) every 48 frames: a dropped column's children drain
    // before the next, so no dropped chunk has to go whole.
    for step in 0..480 {
        let at = Vec3::new(step as f32 * 0.25, 0.0, 0.0);
        app.world_mut().entity_mut(agent).insert(Transform::from_translation(at));
        app.update();
        let world = app.world_mut();
        let now: std::collections::HashSet<Entity> =
            world.query_filtered::<Entity, With<HexProp>>().iter(world).collect();
        // Chunks dropped whole this frame (a few children each) take theirs outside the budget.
        let dropped = world.resource::<Messages<ChunkDespawned>>().iter_current_update_messages().count();
        let spawned = now.difference(&live).count();
        let gone = live.difference(&now).count();
        assert!(spawned <= budget, "frame {step}: {spawned} props spawned, over the budget of {budget}");
        assert!(gone <= budget + 8 * dropped, "frame {step}: {gone} props despawned ({dropped} chunks dropped)");
        most_spawned = most_spawned.max(spawned);
        most_gone = most_gone.max(gone);
        let retiring = world.resource::<ChunkStreamer>().retiring_chunks();
        assert!(retiring < bevy_hex_terrain::MAX_RETIRED_CHUNKS, "frame {step}: {retiring} chunks retiring");
        retired_seen = retired_seen.max(retiring);
        // The chunk entities are exactly the streamer's: a dropped chunk is no chunk any more.
        let chunks = world.query::<&HexChunk>().iter(world).count();
        assert_eq!(chunks, world.resource::<ChunkStreamer>().live_chunks(), "frame {step}");
        live = now;
    }
    assert!(most_spawned == budget && most_gone >= budget, "the walk hits both budgets: {most_spawned}, {most_gone}");
    assert!(retired_seen > 0, "dropped chunks retire");
    run_until(&mut app, "terrain ready", ready);
    run_until(&mut app, "props settled", props_settled);
    let expected: usize = app.world_mut().query::<&ChunkContent>().iter(app.world()).map(|c| c.props.len()).sum();
    assert_eq!(props(&mut app).len(), expected, "every loaded chunk shows all its props, no dropped chunk's remain");
}

/// The props' table gets room for every prop the kept chunks can hold before the first prop is
/// spawned, so it never grows while a walk fills the world and goes on (Bevy would double it,
/// copying every prop in one frame): every prop lands in that one table, headless and, with the
/// prop assets, drawn (spawned with their mesh, material and box).
#[test]
fn the_props_table_has_room_before_the_first_prop_and_never_grows() {
    for drawn in [false, true] {
        let mut config = unbounded((8, 8));
        config.noise.scale = 40.0;
        let settings = HexStreamingSettings { coarse_distance: None, ..settings(1) };
        let mut app = app_with(config.into(), settings, None);
        app.insert_resource(HexPropSettings { max_per_chunk: 120, ..default() });
        #[cfg(feature = "render")]
        if drawn {
            use bevy_hex_terrain::PropAssets;
            use hex_terrain::{PROP_VARIANTS, PropKind};
            let kinds = PropKind::ALL.len();
            let handles = vec![vec![Handle::<Mesh>::default(); usize::from(PROP_VARIANTS)]; kinds];
            let aabbs = vec![vec![bevy::camera::primitives::Aabb::default(); usize::from(PROP_VARIANTS)]; kinds];
            app.insert_resource(PropAssets {
                meshes: handles.clone(),
                far_meshes: handles,
                material: Handle::default(),
                aabbs,
            });
        }
        #[cfg(not(feature = "render"))]
        if drawn {
            continue;
        }
        let agent = spawn_agent(&mut app, Vec3::ZERO);
        let (mut room, mut most) = (None, 0);
        for step in 0..400 {
            let at = Vec3::new(step as f32 * 0.4, 0.0, step as f32 * 0.1);
            app.world_mut().entity_mut(agent).insert(Transform::from_translation(at));
            app.update();
            let world = app.world_mut();
            let mut tables: Vec<_> = world
                .query_filtered::<Entity, With<HexProp>>()
                .iter(world)
                .map(|e| world.entity(e).location().table_id)
                .collect();
            tables.dedup();
            let live = world.query::<&HexProp>().iter(world).count();
            most = most.max(live);
            let Some(&table) = tables.first() else { continue };
            assert_eq!(tables.len(), 1, "step {step} (drawn: {drawn}): props in {} tables", tables.len());
            let capacity = world.storages().tables.get(table).unwrap().capacity();
            assert!(capacity >= live, "step {step}");
            let first = *room.get_or_insert(capacity);
            assert_eq!(capacity, first, "step {step} (drawn: {drawn}): the table grew from {first} to {capacity}");
            if drawn {
                let unboxed = world
                    .query_filtered::<(), (With<HexProp>, Without<bevy::camera::primitives::Aabb>)>()
                    .iter(world)
                    .count();
                assert_eq!(unboxed, 0, "step {step}: props spawned without their box");
            }
        }
        // Past several doublings of a table grown from the first frame's batch.
        assert!(most > 8 * 64, "drawn: {drawn}: at most {most} props live");
    }
}

/// Chunk tasks build what the water and props plugins ask for, from their settings when the
/// task starts: without the plugins, no water surface and no props are built at all; a new
/// density applies to the chunks built after it.
#[test]
fn tasks_build_what_the_plugins_and_their_settings_ask_for() {
    let contents = |app: &mut App| -> Vec<(usize, bool)> {
        let mut all: Vec<_> = app
            .world_mut()
            .query::<(&HexChunk, &ChunkContent)>()
            .iter(app.world())
            .map(|(chunk, c)| ((chunk.coord.x, chunk.coord.z), (c.props.len(), c.water.is_some())))
            .collect();
        all.sort_unstable_by_key(|(coord, _)| *coord);
        all.into_iter().map(|(_, c)| c).collect()
    };
    let plugins = HexTerrainPlugins::new(wooded());
    #[cfg(feature = "render")]
    let group = plugins.build().disable::<HexTerrainMaterialPlugin>();
    #[cfg(not(feature = "render"))]
    let group = plugins.build();
    let mut bare = App::new();
    bare.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin)).insert_resource(settings(8));
    bare.add_plugins(group.disable::<HexWaterPlugin>().disable::<HexPropsPlugin>());
    spawn_agent(&mut bare, Vec3::ZERO);
    run_until(&mut bare, "terrain ready without water and props", ready);
    let bare = contents(&mut bare);
    assert!(!bare.is_empty());
    assert!(bare.iter().all(|&(props, water)| props == 0 && !water), "{bare:?}");

    let mut app = app_with_props(wooded(), 8, HexPropSettings::default());
    spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "terrain ready", ready);
    let full = contents(&mut app);
    assert_eq!(full.len(), bare.len());
    assert!(full.iter().any(|&(_, water)| water) && full.iter().any(|&(props, _)| props > 0));
    // Half the density, then a new map generation (a reload of the same map) rebuilds every
    // chunk with it: fewer props, the same water.
    app.world_mut().resource_mut::<HexPropSettings>().density = 0.5;
    let generation = app.world().resource::<HexMap>().generation();
    app.world_mut().write_message(LoadHexMap(wooded().into()));
    run_until(&mut app, "terrain ready again", |app| {
        app.world().resource::<HexMap>().generation() > generation && ready(app)
    });
    let thinned = contents(&mut app);
    assert_eq!(thinned.len(), full.len());
    let (before, after): (usize, usize) = (full.iter().map(|c| c.0).sum(), thinned.iter().map(|c| c.0).sum());
    assert!(after < before && after > 0, "{after} props at half the density, {before} at the full one");
    assert!(thinned.iter().zip(&full).all(|(a, b)| a.1 == b.1));
}

#[test]
fn props_and_water_switch_off_and_on_at_run_time() {
    let mut app = app_with_props(wooded(), 8, HexPropSettings::default());
    spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "terrain ready", ready);
    run_until(&mut app, "props settled", props_settled);
    let (props_on, water_on) = (count::<HexProp>(&mut app), count::<HexWater>(&mut app));
    assert!(props_on > 0 && water_on > 0);
    app.world_mut().resource_mut::<HexPropSettings>().enabled = false;
    app.world_mut().resource_mut::<HexWaterSettings>().enabled = false;
    app.update();
    app.update();
    assert_eq!((count::<HexProp>(&mut app), count::<HexWater>(&mut app)), (0, 0));
    app.world_mut().resource_mut::<HexPropSettings>().enabled = true;
    app.world_mut().resource_mut::<HexWaterSettings>().enabled = true;
    app.update();
    run_until(&mut app, "props settled", props_settled);
    assert_eq!((count::<HexProp>(&mut app), count::<HexWater>(&mut app)), (props_on, water_on));
}

#[test]
fn a_map_switch_replaces_the_props_with_the_new_maps() {
    let props_settings = HexPropSettings { max_per_chunk: 30, ..default() };
    let mut app = app_with_props(wooded(), 8, props_settings);
    spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "terrain ready", ready);
    run_until(&mut app, "props settled", props_settled);
    let before = props(&mut app);
    let other = MapConfig { seed: 4242, ..wooded() };
    app.world_mut().write_message(LoadHexMap(other.clone().into()));
    let generation = app.world().resource::<HexMap>().generation();
    run_until(&mut app, "the new map ready", |app| {
        app.world().resource::<HexMap>().generation() > generation && ready(app)
    });
    run_until(&mut app, "props settled", props_settled);
    let after = props(&mut app);
    assert_ne!(before, after, "another seed grows other props");
    let terrain = Terrain::new(other).unwrap();
    let expected: usize = terrain
        .chunks()
        .into_iter()
        .map(|c| terrain.props(&terrain.generate_chunk(c).unwrap(), props_settings.max_per_chunk, 1.0).len())
        .sum();
    assert_eq!(after.len(), expected, "the props are the new map's, none of the old map's is left");
}

/// Under fog of war, props on unexplored tiles are hidden and show once their tile is explored;
/// a frame looks only at the props of the tiles whose fog changed in it (a hover's highlight
/// touches none, a fog change a tile's props, not the map's), and switching the fog off shows
/// them all.
#[cfg(feature = "render")]
#[test]
fn props_hide_under_fog_and_a_write_looks_only_at_its_tiles_props() {
    let mut app = app_with_props(wooded(), 1, HexPropSettings::default());
    app.insert_resource(HexTileStateStyle { fog_of_war: true, ..default() });
    spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "the chunks around the agent", |app| {
        let streamer = app.world().resource::<ChunkStreamer>();
        streamer.wanted().next().is_some() && streamer.wanted().all(|(c, _)| streamer.is_chunk_loaded(c))
    });
    run_until(&mut app, "props settled", props_settled);
    app.update();
    let shown = |app: &mut App| -> Vec<(Hex, bool)> {
        app.world_mut()
            .query::<(&HexProp, &Visibility)>()
            .iter(app.world())
            .map(|(p, v)| (p.tile, *v != Visibility::Hidden))
            .collect()
    };
    let all = shown(&mut app);
    assert!(all.len() > 20, "{} props", all.len());
    assert!(all.iter().all(|(_, s)| !s), "nothing explored: every prop hidden");
    // The tile with the most props is explored: its props show, the others stay hidden.
    let mut per_tile: std::collections::HashMap<Hex, usize> = std::collections::HashMap::new();
    for (t, _) in &all {
        *per_tile.entry(*t).or_default() += 1;
    }
    let (&tile, &n) = per_tile.iter().max_by_key(|(t, n)| (**n, t.x, t.y)).unwrap();
    app.world_mut().resource_mut::<TileStates>().set_visibility(tile, FogState::Explored).unwrap();
    app.update();
    for (t, s) in shown(&mut app) {
        assert_eq!(s, t == tile, "prop on {t:?}");
    }
    // A highlight on that tile leaves its fog as it was: no prop is looked at.
    let checks = |app: &App| app.world().resource::<bevy_hex_terrain::HexPropStats>().fog_checks;
    let before = checks(&app);
    app.world_mut().resource_mut::<TileStates>().set_highlight(tile, Highlight::Hovered, true).unwrap();
    app.update();
    assert_eq!(checks(&app), before, "a hover looks at no prop");
    // A fog change on it: its props only, not the map's.
    app.world_mut().resource_mut::<TileStates>().set_visibility(tile, FogState::Visible).unwrap();
    app.update();
    app.world_mut().resource_mut::<TileStates>().set_visibility(tile, FogState::Unexplored).unwrap();
    let before = checks(&app);
    app.update();
    assert_eq!(checks(&app) - before, n as u64, "the tile's {n} props, not the map's {}", all.len());
    for (t, s) in shown(&mut app) {
        assert!(!s, "prop on {t:?} hidden again");
    }
    // A frame without writes looks at none.
    let before = app.world().resource::<bevy_hex_terrain::HexPropStats>().fog_checks;
    app.update();
    assert_eq!(app.world().resource::<bevy_hex_terrain::HexPropStats>().fog_checks, before);
    // Fog off: every prop shows.
    app.world_mut().resource_mut::<HexTileStateStyle>().fog_of_war = false;
    app.update();
    assert!(shown(&mut app).iter().all(|(_, s)| *s));
}

/// A map with a game setup: every loaded chunk's resources and wonders are props on exactly the
/// setup's tiles (a gem of the resource's class, an obelisk), `HexMap` answers the setup's
/// queries, and under fog of war a resource on an unexplored tile is hidden like a tree.
#[cfg(feature = "render")]
#[test]
fn the_setups_resources_and_wonders_stand_on_their_tiles_and_hide_under_fog() {
    let mut config = wooded();
    config.setup = Some(SetupConfig { players: 2, min_distance: 8, ..default() });
    let mut app = app_with_props(config.clone(), 8, HexPropSettings::default());
    app.insert_resource(HexTileStateStyle { fog_of_war: true, ..default() });
    spawn_agent(&mut app, Vec3::ZERO);
    run_until(&mut app, "every chunk", |app| {
        let streamer = app.world().resource::<ChunkStreamer>();
        streamer.wanted().next().is_some() && streamer.wanted().all(|(c, _)| streamer.is_chunk_loaded(c))
    });
    run_until(&mut app, "props settled", props_settled);
    app.update();
    let terrain = Terrain::new(config).unwrap();
    let setup = terrain.setup().unwrap();
    assert!(!setup.resources().is_empty());
    let map = app.world().resource::<HexMap>();
    assert_eq!(map.setup(), Some(setup));
    for r in setup.resources() {
        assert_eq!(map.resource(r.tile), Some(r));
    }
    for (p, &s) in setup.starts().iter().enumerate() {
        assert_eq!(map.start(s), Some(p as u32));
    }
    let markers: Vec<(HexProp, bool)> = app
        .world_mut()
        .query::<(&HexProp, &Visibility)>()
        .iter(app.world())
        .filter(|(p, _)| matches!(p.kind, hex_terrain::PropKind::Resource | hex_terrain::PropKind::Wonder))
        .map(|(p, v)| (*p, *v == Visibility::Hidden))
        .collect();
    let mut got: Vec<(i32, i32, u8)> = markers.iter().map(|(p, _)| (p.tile.x, p.tile.y, p.variant)).collect();
    got.sort_unstable();
    let mut want: Vec<(i32, i32, u8)> = setup
        .resources()
        .iter()
        .map(|r| (r.tile.x, r.tile.y, r.class as u8))
        .chain(setup.wonders().iter().map(|w| (w.tile.x, w.tile.y, 0)))
        .collect();
    want.sort_unstable();
    assert_eq!(got, want, "the spawned markers are the setup's resources and wonders");
    assert!(markers.iter().all(|(_, hidden)| *hidden), "nothing explored: every marker hidden");
    let tile = setup.resources()[0].tile;
    app.world_mut().resource_mut::<TileStates>().set_visibility(tile, FogState::Explored).unwrap();
    app.update();
    let shown = app
        .world_mut()
        .query::<(&HexProp, &Visibility)>()
        .iter(app.world())
        .any(|(p, v)| p.kind == hex_terrain::PropKind::Resource && p.tile == tile && *v != Visibility::Hidden);
    assert!(shown, "the resource on the explored tile shows");
}
