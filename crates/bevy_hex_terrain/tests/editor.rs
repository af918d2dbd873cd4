//! The world builder in a headless `App`: an edit rebuilds exactly the chunks it reports (the
//! others keep their mesh handles), undo gives back the generated meshes byte for byte, tile
//! states stay, a refused stroke keeps the terrain, saving writes a map file that loads to the
//! same edits, and a hot reload of that file applies once.

mod common;

use std::collections::HashSet;

use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{Brush, Stroke, Tool};
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{EditAction, HexMapSaved, HexMapUnchanged};
use common::*;

/// The positions of every chunk's mesh, by chunk.
fn mesh_positions(app: &mut App) -> Vec<(ChunkCoord, Vec<[f32; 3]>)> {
    let handles = meshed_chunks(app);
    let meshes = app.world().resource::<Assets<Mesh>>();
    let mut out: Vec<_> = handles
        .into_iter()
        .map(|(c, h)| {
            let mesh = meshes.get(&h).expect("a chunk's mesh");
            let Some(VertexAttributeValues::Float32x3(p)) = mesh.attribute(Mesh::ATTRIBUTE_POSITION) else {
                panic!("a chunk mesh without positions")
            };
            (c, p.clone())
        })
        .collect();
    out.sort_by_key(|(c, _)| (c.z, c.x));
    out
}

fn edit(app: &mut App, request: HexMapEdit) {
    app.world_mut().write_message(request);
}

/// Updates until `n` edits are reported and every chunk shows the map's current generation.
fn settle_edits(app: &mut App, n: usize) {
    run_until(app, "the edit's chunks", |app| seen::<HexMapEdited>(app).len() >= n && ready(app));
}

fn watered() -> MapConfig {
    let mut config = MapConfig { seed: 3, size: MapSize::Bounded { x: 24, z: 16 }, chunk_size: (8, 8), ..default() };
    config.climate.enabled = true;
    config.rivers.enabled = true;
    config
}

/// Every `ChunkSpawned` triggered on a chunk entity (a global observer sees each).
#[derive(Resource, Default)]
struct Observed(Vec<ChunkSpawned>);

#[test]
fn an_edit_rebuilds_exactly_its_chunks_and_undo_gives_back_the_meshes() {
    let mut app = app(watered(), 2);
    app.init_resource::<Observed>().add_observer(|e: On<ChunkSpawned>, mut seen: ResMut<Observed>| {
        seen.0.push(*e.event());
    });
    keep::<ChunkSpawned>(&mut app);
    keep::<HexMapEdited>(&mut app);
    keep::<HexMapError>(&mut app);
    run_until(&mut app, "the map", ready);
    let generated = mesh_positions(&mut app);
    let before = meshed_chunks(&mut app);
    let tile = app.world().resource::<HexMap>().terrain().tile_from_offset([11, 8]);
    app.world_mut().resource_mut::<TileStates>().set_owner(tile, Some(2)).unwrap();
    let map_id = app.world().resource::<HexMap>().map_id();
    let low = app.world().resource::<HexMap>().tile_info(tile).unwrap().elevation;

    edit(&mut app, HexMapEdit::Stroke(Stroke { tool: Tool::Raise(0.25), brush: Brush::Range(1), tile }));
    settle_edits(&mut app, 1);
    let edited = seen::<HexMapEdited>(&app)[0].clone();
    assert_eq!(edited.action, EditAction::Stroke);
    assert!(edited.change.tiles.contains(&tile));
    let after = meshed_chunks(&mut app);
    let rebuilt: HashSet<ChunkCoord> = after.iter().filter(|(c, h)| before[c] != **h).map(|(c, _)| *c).collect();
    let reported: HashSet<ChunkCoord> = edited.change.chunks.iter().copied().collect();
    assert!(!reported.is_empty());
    assert_eq!(rebuilt, reported, "the chunks rebuilt are the chunks the edit reported");
    let map = app.world().resource::<HexMap>();
    assert_eq!((map.map_id(), map.generation()), (map_id, edited.generation));
    assert!(map.tile_info(tile).unwrap().elevation > low, "the raised tile is higher");
    // Each chunk's mesh came as a message and as an event on the chunk entity, the first time
    // with `first`; the edit's chunks came again, not first.
    let observed = app.world().resource::<Observed>().0.clone();
    assert_eq!(observed, seen::<ChunkSpawned>(&app), "the events on the chunks are the messages");
    let firsts: Vec<Entity> = observed.iter().filter(|e| e.first).map(|e| e.entity).collect();
    assert_eq!(firsts.len(), firsts.iter().collect::<HashSet<_>>().len(), "one first mesh a chunk");
    let again: HashSet<ChunkCoord> = observed.iter().filter(|e| !e.first).map(|e| e.coord).collect();
    assert_eq!(again, reported, "the rebuilt chunks come again, not first");
    assert_eq!(app.world().resource::<TileStates>().owner(tile), Some(2), "tile states stay through an edit");
    assert_eq!(app.world().resource::<HexEditor>().undo_len(), 1);

    edit(&mut app, HexMapEdit::Undo);
    settle_edits(&mut app, 2);
    assert_eq!(seen::<HexMapEdited>(&app)[1].action, EditAction::Undo);
    assert!(mesh_positions(&mut app) == generated, "undo gives back the generated meshes");
    assert_eq!(app.world().resource::<HexEditor>().redo_len(), 1);

    // An operation that changes nothing is answered too: a stroke setting what the tile has, an
    // undo with nothing left to take back.
    keep::<HexMapUnchanged>(&mut app);
    let g = app.world().resource::<HexMap>().generation();
    edit(&mut app, HexMapEdit::Stroke(Stroke { tool: Tool::Erase, brush: Brush::Range(0), tile }));
    edit(&mut app, HexMapEdit::Undo);
    run_until(&mut app, "two answers", |app| seen::<HexMapUnchanged>(app).len() >= 2);
    let unchanged: Vec<EditAction> = seen::<HexMapUnchanged>(&app).iter().map(|u| u.action).collect();
    assert_eq!(unchanged, [EditAction::Stroke, EditAction::Undo]);
    assert_eq!(app.world().resource::<HexMap>().generation(), g);
    assert_eq!(seen::<HexMapEdited>(&app).len(), 2);

    // A stroke the editor refuses: reported by the map's name, the terrain as it was.
    let g = app.world().resource::<HexMap>().generation();
    edit(&mut app, HexMapEdit::Stroke(Stroke { tool: Tool::Raise(f32::NAN), brush: Brush::Range(0), tile }));
    run_until(&mut app, "the refusal", |app| !seen::<HexMapError>(app).is_empty());
    let error = seen::<HexMapError>(&app)[0].to_string();
    assert!(error.contains("edit not applied") && error.contains("NaN"), "{error}");
    assert_eq!(app.world().resource::<HexMap>().generation(), g);
}

fn asset_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("hex-terrain-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_saved_edit_file_loads_to_the_same_edits_and_its_reload_applies_once() {
    let dir = asset_dir("editor");
    let file = dir.join("edit.map.ron");
    std::fs::write(&file, "(seed: 9, size: Bounded(x: 16, z: 8), chunk_size: (8, 8))").unwrap();
    let mut app = app_with("edit.map.ron".into(), HexStreamingSettings::default(), Some(&dir));
    keep::<HexMapEdited>(&mut app);
    keep::<HexMapSaved>(&mut app);
    keep::<HexMapError>(&mut app);
    run_until(&mut app, "the map", |app| app.world().resource::<HexMap>().config().seed == 9 && ready(app));
    let tile = app.world().resource::<HexMap>().terrain().tile_from_offset([4, 4]);
    let mountain = Tool::SetKind(TileKind::Mountain);
    edit(&mut app, HexMapEdit::Stroke(Stroke { tool: mountain, brush: Brush::Range(1), tile }));
    edit(&mut app, HexMapEdit::Save(file.clone()));
    run_until(&mut app, "the save", |app| !seen::<HexMapSaved>(app).is_empty() && ready(app));
    let saved = seen::<HexMapSaved>(&app)[0].clone();
    assert_eq!((saved.path.as_path(), saved.edits), (file.as_path(), 7));
    let text = std::fs::read_to_string(&file).unwrap();
    let config = MapConfig::from_ron(&text).unwrap();
    assert_eq!(&config, app.world().resource::<HexMap>().config(), "the file holds the edited map");
    assert_eq!(app.world().resource::<HexMap>().tile_kind(tile), Some(TileKind::Mountain));

    // The saved file is the map shown: reloading it regenerates nothing.
    let g = app.world().resource::<HexMap>().generation();
    app.world().resource::<AssetServer>().reload("edit.map.ron");
    for _ in 0..60 {
        app.update();
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    assert_eq!(app.world().resource::<HexMap>().generation(), g, "reloading the saved file changed the map");

    // Edited by hand (one tile less): applied once, and the editor starts from it.
    let mut by_hand = config.clone();
    by_hand.edits.pop();
    std::fs::write(&file, by_hand.to_ron()).unwrap();
    app.world().resource::<AssetServer>().reload("edit.map.ron");
    run_until(&mut app, "the reload", |app| app.world().resource::<HexMap>().config().edits.len() == 6 && ready(app));
    for _ in 0..60 {
        app.update();
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    assert_eq!(app.world().resource::<HexMap>().generation(), g + 1, "one reload, one new generation");
    edit(&mut app, HexMapEdit::Undo);
    for _ in 0..20 {
        app.update();
    }
    assert_eq!(seen::<HexMapEdited>(&app).len(), 1, "nothing to undo in a map reloaded from its file");
    assert!(seen::<HexMapError>(&app).is_empty(), "{:?}", seen::<HexMapError>(&app));
    let _ = std::fs::remove_dir_all(&dir);
}
