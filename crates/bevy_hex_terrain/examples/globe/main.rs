//! A hex globe: the Continents globe (a Standard-size Goldberg globe, 4,412 tiles, 12 of them
//! pentagons, with Civilization's Continents map type and a climate by latitude) streamed to the
//! camera's horizon, lit by a sun over the camera's shoulder. Drag with the left button or use
//! the arrow keys (WASD) to turn it, the wheel to zoom from the whole planet to a few tiles; near
//! the ground the view tilts toward the horizon. The line at the top names the tile under the
//! mouse (picked on the globe's surface; its biome, latitude and longitude, and whether it is a
//! pentagon), or, with no mouse over the globe, the tile at the center of the view.
//! Two players, red and blue, each found a city on the map's game setup's start (the map file's
//! `setup`: the best start of each region of equal fertility, `GlobeTerrain::setup`), clearing
//! its tile of trees (an edit, `Tool::SetProps`), owning the tiles within two of it (`GlobeTileStates`: their borders and tint), and send a scout walking
//! back and forth across the pentagon on land nearest the city (of the twelve, those whose
//! neighbors are all land) between two of its neighbors (`OnGlobeTile`, `GlobeTileWalk`). The
//! camera starts over red's city. The globe is drawn in red's fog of war
//! (`GlobeFog`): what its city and scout see now, what red has explored (it starts knowing the
//! land within ten tiles of its city) greyed, the rest dark (`HEXTERRAIN_FOG=off` draws every
//! tile as generated). `HEXTERRAIN_GLOBE_ALTITUDE` sets the camera's
//! first altitude and `HEXTERRAIN_GLOBE_AT=LON,LAT` its first place in degrees instead of red's
//! city (the screenshots use them: `36,-26.6` looks down on red's scout's pentagon). The minimap (bottom right) is the whole
//! globe drawn equirectangular, the camera's view outlined; a click or a drag there flies the
//! camera over that spot. R raises the tiles round the one under the mouse (Shift+R lowers
//! them), Ctrl+Z undoes, Ctrl+Y redoes (`HexGlobeEditorPlugin`: only the chunks an edit changed
//! are built again). The sea is drawn as water (`HexWaterSettings`: depth colors over the sea
//! floor, foam along the shore, waves catching the sun); N turns its look off and on, X the
//! terrain textures (`HEXTERRAIN_TEXTURES=on` starts with them). `HEXTERRAIN_SCRIPT=1` plays a scripted turn that checks the game
//! (`script.rs`; `tests/strategy.rs` runs it).

mod script;

use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{GlobeFog, GlobeStroke, GlobeTerrain, GlobeTile, PropDensity};
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{GlobeTileWalk, GlobeWalkEnded, HexGlobe, HexGlobeMinimapPlugin, HoveredGlobeTile, OnGlobeTile};

/// The text naming the tile under the mouse.
#[derive(Component)]
struct TileLabel;

/// A scout walking back and forth between two neighbors of a pentagon, across it.
#[derive(Component)]
struct Scout {
    path: [GlobeTile; 3],
}

/// A player's city.
#[derive(Component)]
struct City;

/// A player's unit: the player and how far it sees.
#[derive(Component)]
struct Unit {
    player: u32,
    sight: u32,
}

/// Both players' fog of war, kept by the game; the screen shows red's (player 0).
#[derive(Resource)]
struct Fogs(GlobeFog);

/// Whether the camera flies over red's city once it is founded (no `HEXTERRAIN_GLOBE_AT`).
#[derive(Resource)]
struct FlyToCity(bool);

/// The players' colors: red, blue.
const PLAYERS: [Color; 2] = [Color::srgb(0.85, 0.15, 0.1), Color::srgb(0.15, 0.35, 0.9)];

fn main() -> AppExit {
    let scripted = std::env::var_os("HEXTERRAIN_SCRIPT").is_some();
    let altitude = std::env::var("HEXTERRAIN_GLOBE_ALTITUDE").ok().and_then(|a| a.parse().ok()).unwrap_or(60.0);
    // Where the camera starts: over red's city once it is founded, unless told otherwise.
    let at: Option<(f32, f32)> = std::env::var("HEXTERRAIN_GLOBE_AT").ok().and_then(|at| {
        at.split_once(',').and_then(|(lon, lat)| Some((lon.trim().parse().ok()?, lat.trim().parse().ok()?)))
    });
    let (lon, lat) = at.unwrap_or_default();
    let mut app = App::new();
    app.insert_resource(ClearColor(Color::srgb(0.02, 0.02, 0.05)))
        .add_plugins((
            DefaultPlugins,
            HexGlobePlugin::from_asset("maps/globe/continents.map.ron"),
            // The equirectangular minimap with the camera's view outlined; a click there flies
            // the camera over that spot.
            HexGlobeMinimapPlugin,
            // The world builder: keys raise and lower the tiles under the mouse (`edit`).
            HexGlobeEditorPlugin,
        ))
        .insert_resource(HexMinimapSettings { size: UVec2::new(320, 160), ..default() })
        // Fog of war drawn (HEXTERRAIN_FOG=off: every tile as generated); the owners' colors are
        // the players'.
        .insert_resource(HexTileStateStyle {
            fog_of_war: std::env::var("HEXTERRAIN_FOG").as_deref() != Ok("off"),
            owner_colors: PLAYERS.to_vec(),
            ..default()
        })
        .add_systems(Startup, move |mut commands: Commands| {
            // The orbit camera, which keeps the globe streamed to its horizon, with the sun over
            // its shoulder (from the top left of the view, wherever it flies).
            commands.spawn((
                Camera3d::default(),
                GlobeCamera { altitude, ..GlobeCamera::above(lon.to_radians(), lat.to_radians()) },
                HexTerrainAgent::default(),
                children![(
                    DirectionalLight { illuminance: 9_000.0, ..default() },
                    Transform::from_rotation(Quat::from_euler(EulerRot::YXZ, -0.6, -0.5, 0.0)),
                )],
            ));
            commands.insert_resource(GlobalAmbientLight { brightness: 250.0, ..default() });
            commands.spawn((
                Text::default(),
                TextFont::from_font_size(16.0),
                Node { position_type: PositionType::Absolute, top: px(10.0), left: px(10.0), ..default() },
                TileLabel,
            ));
        })
        .insert_resource(FlyToCity(at.is_none()))
        .insert_resource(HexTerrainMaterialSettings {
            textures: std::env::var("HEXTERRAIN_TEXTURES").is_ok_and(|v| v == "on"),
            ..default()
        })
        .add_systems(
            Update,
            (name_the_tile, edit, switch_look, (found_the_players, see).chain().after(HexTerrainSystems::Map)),
        )
        .add_observer(turn_back);
    if scripted {
        // The scripted turn checks the game, saves its screenshot and exits.
        app.init_resource::<script::Script>().add_systems(Update, script::script.after(see));
    } else {
        // With HEXTERRAIN_SCREENSHOT=out.png set, the screenshot plugin saves a picture and exits.
        app.add_plugins(HexScreenshotPlugin::default());
    }
    app.run()
}

/// Once the globe is in: for each player (red, blue) a city on its start of the game setup,
/// owning the tiles within two, and a scout on a neighbor of the land pentagon nearest the city,
/// walking across it to the neighbor across; red knows the land within ten tiles of its city.
fn found_the_players(
    mut commands: Commands,
    globe: Res<HexGlobe>,
    (fly, mut cameras): (Res<FlyToCity>, Query<&mut GlobeCamera>),
    mut states: ResMut<GlobeTileStates>,
    (mut meshes, mut materials): (ResMut<Assets<Mesh>>, ResMut<Assets<StandardMaterial>>),
    mut edits: MessageWriter<HexMapEdit<GlobeStroke>>,
    mut founded: Local<bool>,
) {
    let Some(globe) = globe.globe().filter(|_| !*founded) else { return };
    *founded = true;
    let Some(starts) = globe.setup().map(|s| s.starts().to_vec()).filter(|s| s.len() >= PLAYERS.len()) else {
        warn!("the globe's map file has no game setup for {} players: no players founded", PLAYERS.len());
        return;
    };
    let grid = globe.grid();
    let land = |t: GlobeTile| globe.tile_kind(t) == Some(TileKind::Land);
    let center = |t: GlobeTile| bevy::math::DVec3::from_array(grid.center(t).expect("a tile of the globe"));
    let pentagons: Vec<GlobeTile> = grid
        .tiles()
        .filter(|&t| {
            grid.is_pentagon(t) && land(t) && grid.neighbors(t).is_some_and(|n| n.as_slice().iter().all(|&n| land(n)))
        })
        .collect();
    let (scout, city) = (meshes.add(Capsule3d::new(0.18, 0.45)), meshes.add(Cylinder::new(0.45, 0.5)));
    let mut fog = GlobeFog::new(globe, 2).expect("two players");
    for (player, color) in PLAYERS.into_iter().enumerate() {
        let home = starts[player];
        let player = player as u32;
        for (tile, _) in grid.within(home, 2) {
            states.set_owner(tile, Some(player)).expect("a player of the palette, a tile of the globe");
        }
        // A city clears its tile of trees (an edit of the map, as the world builder's brush).
        let clear = Tool::SetProps(PropDensity::None);
        edits.write(HexMapEdit::Stroke(GlobeStroke { tool: clear, brush: Brush::Range(0), tile: home }));
        let material = materials.add(color);
        commands.spawn((
            OnGlobeTile::new(home),
            Unit { player, sight: 3 },
            City,
            Mesh3d(city.clone()),
            MeshMaterial3d(material.clone()),
        ));
        if let Some(&pentagon) = pentagons
            .iter()
            .max_by(|&&a, &&b| center(home).dot(center(a)).total_cmp(&center(home).dot(center(b))).then(b.cmp(&a)))
        {
            let around = grid.neighbors(pentagon).expect("a tile of the globe");
            let around = around.as_slice();
            let path = [around[0], pentagon, around[2]];
            commands.spawn((
                OnGlobeTile { lift: 0.4, ..OnGlobeTile::new(path[0]) },
                GlobeTileWalk::new(path, 1.0),
                Scout { path },
                Unit { player, sight: 2 },
                Mesh3d(scout.clone()),
                MeshMaterial3d(material),
            ));
        }
        if player == 0 {
            // What red knows before the first turn: explored, not in sight.
            explore(&mut fog, globe, home, 10);
            if fly.0
                && let (Ok(mut camera), Some(info)) = (cameras.single_mut(), globe.tile_info(home))
            {
                let (lon, lat) = (info.longitude as f32, info.latitude as f32);
                camera.orientation = GlobeCamera::above(lon.to_radians(), lat.to_radians()).orientation;
            }
        }
    }
    commands.insert_resource(Fogs(fog));
}

/// Red has explored the land within `radius` of `home` (and the sea it saw from there).
fn explore(fog: &mut GlobeFog, globe: &GlobeTerrain, home: GlobeTile, radius: u32) {
    fog.update(globe, 0, [(home, radius)]).expect("a fog of this globe");
    fog.update(globe, 0, []).expect("a fog of this globe");
}

/// When a unit reaches a tile: each player's fog sees what its units see now, and the screen
/// shows red's.
fn see(
    globe: Res<HexGlobe>,
    fogs: Option<ResMut<Fogs>>,
    units: Query<(&Unit, &OnGlobeTile)>,
    moved: Query<(), (With<Unit>, Changed<OnGlobeTile>)>,
    mut states: ResMut<GlobeTileStates>,
) {
    let (Some(globe), Some(mut fogs)) = (globe.globe(), fogs) else { return };
    if moved.is_empty() && !fogs.is_added() {
        return;
    }
    for player in 0..2 {
        let sighted = units.iter().filter(|(u, _)| u.player == player).map(|(u, at)| (at.tile, u.sight));
        fogs.0.update(globe, player, sighted).expect("a fog of this globe");
    }
    states.show_fog(&fogs.0, 0).expect("the fog of this globe");
}

/// A scout at the end of its walk turns back.
fn turn_back(ended: On<GlobeWalkEnded>, mut commands: Commands, scouts: Query<&Scout>) {
    let Ok(scout) = scouts.get(ended.entity) else { return };
    let mut path = scout.path;
    if ended.tile == path[2] {
        path.reverse();
    }
    commands.entity(ended.entity).insert(GlobeTileWalk::new(path, 1.0));
}

/// R raises the tile under the mouse and its neighbors (Shift+R lowers them); Ctrl+Z undoes,
/// Ctrl+Y redoes.
fn edit(
    keys: Res<ButtonInput<KeyCode>>,
    hovered: Res<HoveredGlobeTile>,
    mut edits: MessageWriter<HexMapEdit<GlobeStroke>>,
) {
    let ctrl = keys.any_pressed([KeyCode::ControlLeft, KeyCode::ControlRight]);
    let shift = keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
    if ctrl && keys.just_pressed(KeyCode::KeyZ) {
        edits.write(HexMapEdit::Undo);
    } else if ctrl && keys.just_pressed(KeyCode::KeyY) {
        edits.write(HexMapEdit::Redo);
    } else if keys.just_pressed(KeyCode::KeyR)
        && let Some(tile) = hovered.tile()
    {
        let tool = if shift { Tool::Lower(0.1) } else { Tool::Raise(0.1) };
        edits.write(HexMapEdit::Stroke(GlobeStroke { tool, brush: Brush::Range(1), tile }));
    }
}

/// N turns the water's look off and on, X the terrain textures.
fn switch_look(
    keys: Res<ButtonInput<KeyCode>>,
    mut water: ResMut<HexWaterSettings>,
    mut material: ResMut<HexTerrainMaterialSettings>,
) {
    if keys.just_pressed(KeyCode::KeyN) {
        water.enabled = !water.enabled;
    }
    if keys.just_pressed(KeyCode::KeyX) {
        material.textures = !material.textures;
    }
}

/// Names the tile under the mouse, else the one at the center of the view.
fn name_the_tile(
    hovered: Res<HoveredGlobeTile>,
    globe: Res<HexGlobe>,
    cameras: Query<&GlobalTransform, With<GlobeCamera>>,
    mut labels: Query<&mut Text, With<TileLabel>>,
    mut named: Local<Option<(Option<GlobeTile>, bool, u64)>>,
) {
    let generation = globe.generation();
    let (Some(globe), Ok(camera), Ok(mut label)) = (globe.globe(), cameras.single(), labels.single_mut()) else {
        return;
    };
    let center = || {
        let (origin, forward) = (camera.translation().as_dvec3(), camera.forward().as_dvec3());
        globe.raycast(origin.to_array(), forward.to_array(), f64::MAX).map(|hit| hit.tile)
    };
    let (tile, where_) = match hovered.tile() {
        Some(tile) => (Some(tile), "under the mouse"),
        None => (center(), "at the center of the view"),
    };
    // The label is rewritten only when its tile, its wording or the globe changes (a tile's info
    // samples its center).
    let now = (tile, hovered.tile().is_some(), generation);
    if *named == Some(now) {
        return;
    }
    *named = Some(now);
    let text = tile.and_then(|t| globe.tile_info(t)).map_or_else(String::new, |info| {
        format!(
            "Tile {} {where_}: {}, latitude {:.1}, longitude {:.1}{}",
            info.tile.0,
            globe.ruleset().terrain(info.terrain.terrain).name,
            info.latitude,
            info.longitude,
            if info.pentagon { ", a pentagon (five neighbors)" } else { "" }
        )
    });
    label.0 = text;
}
