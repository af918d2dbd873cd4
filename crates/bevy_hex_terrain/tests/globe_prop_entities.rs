//! Props on a globe in a headless `App`: every chunk's prop children are the core's props of
//! its mesh (what, on which tile, where, upright along the globe's up, how big), then the game
//! setup's resource and wonder markers of its mesh, spawned at most
//! a budget a frame; an edit makes its chunks' props again from the edited globe; turning props
//! off and on despawns and spawns them; under fog of war the props of unexplored tiles are
//! hidden, and shown when their tile is explored.

mod common;

use std::collections::HashMap;

use bevy::asset::AssetPlugin;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{GlobeChange, GlobeChunk, GlobeProp, GlobeStroke, GlobeTerrain, PropKind};
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{GlobeStreamer, HexGlobeProp};
use common::{keep, run_until, seen};

const BUDGET: usize = 40;

fn app() -> App {
    let mut config =
        MapConfig { size: MapSize::Globe { frequency: 8 }, chunk_size: (2, 2), seed: 5, ..MapConfig::default() };
    config.terrain.inner_rings = 1;
    config.climate.enabled = true;
    config.setup = Some(SetupConfig { players: 2, ..SetupConfig::default() });
    let mut app = App::new();
    let assets = AssetPlugin { watch_for_changes_override: Some(false), ..default() };
    app.add_plugins((
        MinimalPlugins,
        assets,
        TransformPlugin,
        HexGlobePlugin::from_config(config),
        HexGlobeEditorPlugin,
    ))
    .insert_resource(HexPropSettings { max_spawns_per_frame: BUDGET, max_per_chunk: 60, ..default() });
    keep::<HexMapEdited<GlobeChange>>(&mut app);
    app
}

fn globe(app: &App) -> GlobeTerrain {
    (**app.world().resource::<HexGlobe>().globe().unwrap()).clone()
}

/// Each chunk's props as spawned, in spawn order: what, where, which way up and how big.
fn spawned(app: &mut App) -> HashMap<GlobeChunk, Vec<(HexGlobeProp, Transform)>> {
    let mut chunks = app.world_mut().query::<(&HexGlobeChunk, Option<&Children>)>();
    let mut props = app.world_mut().query::<(&HexGlobeProp, &Transform)>();
    let world = app.world();
    chunks
        .iter(world)
        .map(|(chunk, children)| {
            let list = children.into_iter().flatten().filter_map(|&c| props.get(world, c).ok()).map(|(p, t)| (*p, *t));
            (chunk.chunk, list.collect())
        })
        .collect()
}

fn prop_count(app: &mut App) -> usize {
    app.world_mut().query::<&HexGlobeProp>().iter(app.world()).count()
}

/// Whether every prop of `globe`'s chunks, by the core, is spawned as the chunk's children.
fn matches_core(app: &mut App, globe: &GlobeTerrain) -> Result<(), String> {
    let settings = *app.world().resource::<HexPropSettings>();
    let size = globe.config().layout.hex_size;
    let spawned = spawned(app);
    for (chunk, props) in &spawned {
        let mesh = globe.generate(*chunk);
        let mut want: Vec<GlobeProp> = globe.props(&mesh, settings.max_per_chunk, settings.density);
        want.extend(globe.marker_props(&mesh));
        if props.len() != want.len() {
            return Err(format!("{chunk:?}: {} props spawned, {} placed", props.len(), want.len()));
        }
        for ((prop, t), w) in props.iter().zip(&want) {
            if (prop.kind, prop.variant, prop.tile) != (w.kind, w.variant, w.tile) {
                return Err(format!("{chunk:?}: {prop:?} for {w:?}"));
            }
            let up = t.rotation * Vec3::Y;
            let ok = t.translation == Vec3::from_array(w.position)
                && (up - Vec3::from_array(w.up)).length() < 1e-5
                && (t.scale - Vec3::splat(w.scale * size)).length() < 1e-6;
            if !ok {
                return Err(format!("{chunk:?}: {:?} of {:?} placed at {t:?}", w.kind, w.tile));
            }
        }
    }
    Ok(())
}

fn settled(app: &mut App) -> bool {
    app.world().resource::<GlobeStreamer>().is_settled() && {
        let g = globe(app);
        matches_core(app, &g).is_ok()
    }
}

#[test]
fn globe_props_are_the_cores_spawned_a_budget_a_frame_and_follow_edits_and_fog() {
    let mut app = app();
    // A budget a frame while they come.
    let mut last = 0;
    run_until(&mut app, "the props", |app| {
        let now = prop_count(app);
        assert!(now <= last + BUDGET, "{} props spawned in a frame", now - last);
        last = now;
        settled(app)
    });
    let generated = globe(&app);
    matches_core(&mut app, &generated).unwrap();
    let total = prop_count(&mut app);
    let spawned_now = spawned(&mut app);
    let kinds: Vec<PropKind> = spawned_now.values().flatten().map(|(p, _)| p.kind).collect();
    assert!(total > 200 && kinds.contains(&PropKind::Rock) && kinds.contains(&PropKind::Pine), "{total} props");
    // The setup's resources (and wonders) stand among them, one on each tile the setup put one.
    let setup = generated.setup().unwrap();
    let markers = kinds.iter().filter(|&&k| matches!(k, PropKind::Resource | PropKind::Wonder)).count();
    assert_eq!(markers, setup.resources().len() + setup.wonders().len(), "the setup's markers");
    let marker = |p: &HexGlobeProp| matches!(p.kind, PropKind::Resource | PropKind::Wonder);

    // An edit on a wooded tile: its chunks' props made again from the edited globe.
    let (forest, _) = spawned_now.values().flatten().find(|(p, _)| p.kind != PropKind::Rock && !marker(p)).unwrap();
    let tile = forest.tile;
    app.world_mut().write_message(HexMapEdit::Stroke(GlobeStroke {
        tool: Tool::SetKind(TileKind::Sea),
        brush: Brush::Range(1),
        tile,
    }));
    run_until(&mut app, "the edit", |app| !seen::<HexMapEdited<GlobeChange>>(app).is_empty() && settled(app));
    let edited = globe(&app);
    matches_core(&mut app, &edited).unwrap();
    let on_land = |(p, _): &&(HexGlobeProp, Transform)| !marker(p);
    assert!(
        spawned(&mut app).values().flatten().filter(on_land).all(|(p, _)| p.tile != tile),
        "trees on a tile sunk into the sea"
    );

    // Off and on again.
    app.world_mut().resource_mut::<HexPropSettings>().enabled = false;
    app.update();
    app.update();
    assert_eq!(prop_count(&mut app), 0);
    app.world_mut().resource_mut::<HexPropSettings>().enabled = true;
    run_until(&mut app, "the props again", settled);

    // Fog of war: every tile unexplored hides every prop; the tiles explored show theirs.
    #[cfg(feature = "render")]
    {
        app.insert_resource(HexTileStateStyle { fog_of_war: true, ..default() });
        app.update();
        let mut q = app.world_mut().query::<(&HexGlobeProp, &Visibility)>();
        assert!(q.iter(app.world()).all(|(_, v)| *v == Visibility::Hidden), "props under unexplored fog shown");
        let open: Vec<_> = edited.grid().tiles().filter(|t| t.0 % 3 == 0).collect();
        for &t in &open {
            app.world_mut().resource_mut::<GlobeTileStates>().set_visibility(t, FogState::Explored).unwrap();
        }
        app.update();
        let mut counts = [0; 2];
        for (prop, visibility) in q.iter(app.world()) {
            let shown = open.contains(&prop.tile);
            let want = if shown { Visibility::Inherited } else { Visibility::Hidden };
            assert_eq!(*visibility, want, "{prop:?}");
            counts[usize::from(shown)] += 1;
        }
        assert!(counts.iter().all(|&c| c > 20), "{counts:?}");
    }
}
