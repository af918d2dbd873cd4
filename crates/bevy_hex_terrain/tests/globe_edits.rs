//! The world builder on a globe, in a headless `App`: a stroke on a pentagon rebuilds exactly the
//! chunks it reports (the others keep their mesh handles) and the edited globe is the one the
//! core's editor makes of the same stroke; a unit on the tile stands on the raised surface;
//! tile states stay; undo gives back the generated meshes; a refused stroke keeps the globe and
//! says why; saving writes a map file that compiles to the edited globe.

mod common;

use std::collections::{HashMap, HashSet};

use bevy::asset::AssetPlugin;
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{GlobeChange, GlobeChunk, GlobeEditor, GlobeStroke, GlobeTerrain, GlobeTile};
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{EditAction, GlobeStreamer, HexMapSaved, OnGlobeTile};
use common::{keep, run_until, seen};

type GlobeEdit = HexMapEdit<GlobeStroke>;
type GlobeEdited = HexMapEdited<GlobeChange>;

fn config() -> MapConfig {
    let mut config =
        MapConfig { size: MapSize::Globe { frequency: 8 }, chunk_size: (2, 2), seed: 11, ..MapConfig::default() };
    config.terrain.inner_rings = 1;
    config.climate.enabled = true;
    config
}

fn app() -> App {
    let mut app = App::new();
    let assets = AssetPlugin { watch_for_changes_override: Some(false), ..default() };
    app.add_plugins((
        MinimalPlugins,
        assets,
        TransformPlugin,
        HexGlobePlugin::from_config(config()),
        HexGlobeEditorPlugin,
    ));
    keep::<GlobeEdited>(&mut app);
    keep::<HexMapUnchanged>(&mut app);
    keep::<HexMapSaved>(&mut app);
    keep::<HexMapError>(&mut app);
    app
}

fn settled(app: &mut App) -> bool {
    app.world().resource::<GlobeStreamer>().is_settled()
}

/// Every chunk's mesh handle, by chunk.
fn handles(app: &mut App) -> HashMap<GlobeChunk, Handle<Mesh>> {
    let mut q = app.world_mut().query::<(&HexGlobeChunk, &Mesh3d)>();
    q.iter(app.world()).map(|(c, m)| (c.chunk, m.0.clone())).collect()
}

/// Every chunk's mesh positions (the plugin's mesh: a border point once per tile holding it),
/// as the set of their bits, by chunk.
fn positions(app: &mut App) -> HashMap<GlobeChunk, HashSet<[u32; 3]>> {
    let handles = handles(app);
    let meshes = app.world().resource::<Assets<Mesh>>();
    handles
        .into_iter()
        .map(|(chunk, h)| {
            let Some(VertexAttributeValues::Float32x3(p)) = meshes.get(&h).unwrap().attribute(Mesh::ATTRIBUTE_POSITION)
            else {
                panic!("a chunk without positions")
            };
            (chunk, p.iter().map(|v| v.map(f32::to_bits)).collect())
        })
        .collect()
}

/// The positions of the core's mesh of each chunk of a globe, as bits.
fn core_positions(globe: &GlobeTerrain) -> HashMap<GlobeChunk, HashSet<[u32; 3]>> {
    globe
        .chunks()
        .into_iter()
        .map(|chunk| (chunk, globe.generate(chunk).buffers.positions.iter().map(|v| v.map(f32::to_bits)).collect()))
        .collect()
}

fn shown(app: &App) -> GlobeTerrain {
    (**app.world().resource::<HexGlobe>().globe().unwrap()).clone()
}

fn write(app: &mut App, edit: GlobeEdit) {
    app.world_mut().write_message(edit);
}

/// Updates until `n` edits are reported and every chunk shows the globe as it is.
fn settle_edits(app: &mut App, n: usize) {
    run_until(app, "the edit's chunks", |app| seen::<GlobeEdited>(app).len() >= n && settled(app));
}

#[test]
fn a_stroke_on_a_pentagon_rebuilds_its_chunks_and_undo_gives_the_globe_back() {
    let mut app = app();
    run_until(&mut app, "the globe", settled);
    let generated = shown(&app);
    let generated_meshes = positions(&mut app);
    assert_eq!(generated_meshes, core_positions(&generated), "the streamed meshes are the core's");
    let pentagon = generated.grid().tiles().find(|&t| generated.grid().is_pentagon(t)).unwrap();
    let unit = app.world_mut().spawn((OnGlobeTile { tile: pentagon, lift: 0.0 }, Transform::default())).id();
    app.world_mut().resource_mut::<GlobeTileStates>().set_owner(pentagon, Some(1)).unwrap();
    app.update();
    let stood = app.world().get::<Transform>(unit).unwrap().translation.length();
    let before = handles(&mut app);

    // The same stroke by the core's editor: the change and the globe expected.
    let stroke = GlobeStroke { tool: Tool::Raise(0.3), brush: Brush::Range(1), tile: pentagon };
    let mut core = GlobeEditor::from_globe(generated.clone());
    let expected = core.apply(stroke).unwrap();
    write(&mut app, HexMapEdit::Stroke(stroke));
    settle_edits(&mut app, 1);
    let edited = seen::<GlobeEdited>(&app)[0].clone();
    assert_eq!(edited.action, EditAction::Stroke);
    assert_eq!(edited.change, expected);
    assert_eq!(edited.generation, app.world().resource::<HexGlobe>().generation());
    let now = shown(&app);
    assert_eq!(now.config(), core.globe().config(), "the globe shown is the core editor's");
    let after = handles(&mut app);
    let rebuilt: HashSet<GlobeChunk> = after.iter().filter(|(c, h)| before[c] != **h).map(|(c, _)| *c).collect();
    let reported: HashSet<GlobeChunk> = expected.chunks.iter().copied().collect();
    assert!(!reported.is_empty());
    assert_eq!(rebuilt, reported, "the chunks rebuilt are the chunks the edit changed");
    assert_eq!(positions(&mut app), core_positions(&now), "every mesh shows the edited globe");
    // The unit stands on the raised surface; the tile states stayed.
    let info = now.tile_info(pentagon).unwrap();
    let stands = app.world().get::<Transform>(unit).unwrap().translation.length();
    assert!((stands - (now.radius() as f32 + info.elevation)).abs() < 1e-3, "{stands} off the surface");
    assert!(stands > stood + 1e-3, "the unit rose with its tile: {stood} to {stands}");
    assert_eq!(app.world().resource::<GlobeTileStates>().owner(pentagon), Some(1));
    let editor = app.world().resource::<HexGlobeEditor>();
    assert_eq!((editor.undo_len(), editor.redo_len(), editor.edited_tiles()), (1, 0, 6), "a pentagon and 5 neighbors");

    // Undo: the generated meshes back.
    write(&mut app, HexMapEdit::Undo);
    settle_edits(&mut app, 2);
    assert_eq!(seen::<GlobeEdited>(&app)[1].action, EditAction::Undo);
    assert!(positions(&mut app) == generated_meshes, "undo gives back the generated meshes");
    assert!(shown(&app).config().edits.is_empty());
    let back = app.world().get::<Transform>(unit).unwrap().translation.length();
    assert!((back - stood).abs() < 1e-4, "the unit back on the generated surface");

    // Refused strokes keep the globe and say why; undos with nothing to undo change nothing.
    let generation = app.world().resource::<HexGlobe>().generation();
    let tiles = generated.grid().tile_count();
    write(&mut app, HexMapEdit::Stroke(GlobeStroke { tile: GlobeTile(tiles), ..stroke }));
    write(&mut app, HexMapEdit::Stroke(GlobeStroke { tool: Tool::AddRiver, ..stroke }));
    write(&mut app, HexMapEdit::Undo);
    write(&mut app, HexMapEdit::Undo);
    run_until(&mut app, "the refusals", |app| {
        seen::<HexMapUnchanged>(app).len() >= 2 && !app.world().resource::<HexGlobeEditor>().is_busy()
    });
    let errors: Vec<String> = seen::<HexMapError>(&app).iter().map(ToString::to_string).collect();
    assert_eq!(errors.len(), 2, "{errors:?}");
    assert!(
        errors[0].contains(&format!("tile {tiles}")) && errors[0].contains(&format!("0..{tiles}")),
        "{}",
        errors[0]
    );
    assert!(errors[1].contains("AddRiver"), "{}", errors[1]);
    assert_eq!(seen::<HexMapUnchanged>(&app), vec![HexMapUnchanged { action: EditAction::Undo }; 2]);
    assert_eq!(app.world().resource::<HexGlobe>().generation(), generation, "nothing refused changed the globe");
    assert_eq!(seen::<GlobeEdited>(&app).len(), 2);

    // Redo, then save: the file compiles to the edited globe.
    let dir = std::env::temp_dir().join(format!("hex-globe-editor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("edited.map.ron");
    write(&mut app, HexMapEdit::Redo);
    write(&mut app, HexMapEdit::Save(path.clone()));
    run_until(&mut app, "the save", |app| !seen::<HexMapSaved>(app).is_empty());
    assert_eq!(seen::<HexMapSaved>(&app)[0], HexMapSaved { path: path.clone(), edits: 6 });
    let saved = MapConfig::from_ron(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let reloaded = GlobeTerrain::new(saved).unwrap();
    assert_eq!(reloaded.config(), core.globe().config());
    for t in reloaded.grid().tiles() {
        assert_eq!(reloaded.tile_height(t).map(f32::to_bits), core.globe().tile_height(t).map(f32::to_bits), "{t:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
