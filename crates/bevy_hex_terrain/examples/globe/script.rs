//! The scripted turn (`HEXTERRAIN_SCRIPT=1`): once the players are founded and the globe is on
//! screen, checks that each city stands on its player's start of the game setup, each player's
//! territory (the tiles within two of its city, against the tile
//! states), red's fog (in sight: what its units see, by the core's sight rule; explored: the
//! land it started knowing), follows red's scout across the pentagon to the neighbor beyond and
//! checks red's fog there again, checks the tile picked under the pointer (at the middle of the
//! window under Xvfb) against a ray cast from the camera, then prints `SCRIPT OK`, saves a
//! screenshot (`HEXTERRAIN_SCREENSHOT`) and exits. A failed check prints `SCRIPT FAILED` and
//! exits with an error.

use std::collections::HashSet;

use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy_hex_terrain::hex_terrain::{GlobeTerrain, GlobeTile};
use bevy_hex_terrain::prelude::*;
use bevy_hex_terrain::{GlobeStreamer, HexGlobe, HoveredGlobeTile, OnGlobeTile};

use super::{City, Fogs, Scout, Unit};

/// Where the script is.
#[derive(Resource, Default)]
pub struct Script {
    step: u32,
    frame: u32,
    /// The tiles red's scout has stood on since the first checks.
    visited: Vec<GlobeTile>,
}

fn fail(why: String, exit: &mut MessageWriter<AppExit>) {
    println!("SCRIPT FAILED: {why}");
    exit.write(AppExit::error());
}

/// What red's units see now, by the core's sight rule.
fn in_sight(globe: &GlobeTerrain, units: &Query<(&Unit, &OnGlobeTile)>) -> HashSet<GlobeTile> {
    units.iter().filter(|(u, _)| u.player == 0).flat_map(|(u, at)| globe.field_of_view(at.tile, u.sight)).collect()
}

/// Every tile red sees shown visible, and no other.
fn check_sight(
    globe: &GlobeTerrain,
    states: &GlobeTileStates,
    units: &Query<(&Unit, &OnGlobeTile)>,
) -> Result<usize, String> {
    let seen = in_sight(globe, units);
    for tile in globe.grid().tiles() {
        let visible = states.visibility(tile) == FogState::Visible;
        if visible != seen.contains(&tile) {
            return Err(format!(
                "{tile:?} shown {:?}, in red's sight: {}",
                states.visibility(tile),
                seen.contains(&tile)
            ));
        }
    }
    Ok(seen.len())
}

#[allow(clippy::too_many_arguments, reason = "a script reads the whole game")]
pub fn script(
    mut commands: Commands,
    mut s: ResMut<Script>,
    globe: Res<HexGlobe>,
    streamer: Res<GlobeStreamer>,
    fogs: Option<Res<Fogs>>,
    states: Res<GlobeTileStates>,
    units: Query<(&Unit, &OnGlobeTile)>,
    cities: Query<(&Unit, &OnGlobeTile), With<City>>,
    scouts: Query<(&Unit, &OnGlobeTile, &Scout)>,
    hovered: Res<HoveredGlobeTile>,
    cameras: Query<&GlobalTransform, With<GlobeCamera>>,
    mut exit: MessageWriter<AppExit>,
) {
    let (Some(globe), Some(_)) = (globe.globe(), fogs) else { return };
    s.frame += 1;
    let Some((_, red_scout, scout)) = scouts.iter().find(|(u, ..)| u.player == 0) else { return };
    match s.step {
        // The globe on screen for ten frames.
        0 if streamer.is_settled() => {
            s.frame = 0;
            s.step = 1;
        }
        1 if s.frame >= 10 => {
            let starts = globe.setup().map(|setup| setup.starts().to_vec()).unwrap_or_default();
            for (unit, city) in &cities {
                if starts.get(unit.player as usize) != Some(&city.tile) {
                    return fail(
                        format!("player {}'s city stands on {:?}, not its start of {starts:?}", unit.player, city.tile),
                        &mut exit,
                    );
                }
                let owned: HashSet<GlobeTile> =
                    globe.grid().tiles().filter(|&t| states.owner(t) == Some(unit.player)).collect();
                let expected: HashSet<GlobeTile> =
                    globe.grid().within(city.tile, 2).into_iter().map(|(t, _)| t).collect();
                if owned != expected {
                    return fail(
                        format!(
                            "player {} owns {} tiles, not the {} within two of its city",
                            unit.player,
                            owned.len(),
                            expected.len()
                        ),
                        &mut exit,
                    );
                }
            }
            let seen = match check_sight(globe, &states, &units) {
                Ok(seen) => seen,
                Err(why) => return fail(why, &mut exit),
            };
            let (_, home) = cities.iter().find(|(u, _)| u.player == 0).expect("red's city");
            let known = globe.field_of_view(home.tile, 10);
            if let Some(t) = known.iter().find(|&&t| states.visibility(t) == FogState::Unexplored) {
                return fail(format!("{t:?}, which red knew from the start, is unexplored"), &mut exit);
            }
            println!(
                "SCRIPT: cities on the setup's starts {starts:?}, their territories the tiles within two; red sees \
                 {seen} tiles and knows {}",
                known.len()
            );
            s.visited = vec![red_scout.tile];
            s.step = 2;
        }
        // Red's scout walks on: across the pentagon to the neighbor beyond.
        2 => {
            if s.visited.last() != Some(&red_scout.tile) {
                s.visited.push(red_scout.tile);
            }
            let [_, pentagon, beyond] = scout.path;
            let crossed =
                s.visited.iter().position(|&t| t == pentagon).is_some_and(|p| s.visited[p..].contains(&beyond))
                    || s.visited.windows(2).any(|w| w == [pentagon, scout.path[0]]);
            if !crossed {
                if s.frame > 2000 {
                    fail(format!("red's scout did not cross the pentagon: {:?}", s.visited), &mut exit);
                }
                return;
            }
            if !globe.grid().is_pentagon(pentagon) {
                return fail(format!("{pentagon:?} is not a pentagon"), &mut exit);
            }
            if let Err(why) = check_sight(globe, &states, &units) {
                return fail(format!("after the walk: {why}"), &mut exit);
            }
            println!("SCRIPT: red's scout walked {:?}, across the pentagon; its fog followed", s.visited);
            s.step = 3;
        }
        3 => {
            // The tile under the pointer, at the middle of the window: the ray along the view.
            let Ok(camera) = cameras.single() else { return };
            let (origin, forward) = (camera.translation().as_dvec3(), camera.forward().as_dvec3());
            let center = globe.raycast(origin.to_array(), forward.to_array(), f64::MAX).map(|hit| hit.tile);
            let picked = hovered.tile();
            let near = |a: GlobeTile, b: GlobeTile| {
                a == b || globe.grid().neighbors(a).is_some_and(|n| n.as_slice().contains(&b))
            };
            match (picked, center) {
                (Some(p), Some(c)) if near(p, c) => {}
                // No pointer over the window (a display without one): nothing to check.
                (None, _) => println!("SCRIPT: no pointer over the window"),
                _ => {
                    return fail(
                        format!("picked {picked:?} under the pointer, the view's center is {center:?}"),
                        &mut exit,
                    );
                }
            }
            println!(
                "SCRIPT OK: territories, red's fog before and after its scout crossed a pentagon, the picked tile {picked:?}"
            );
            s.step = 4;
            match std::env::var_os("HEXTERRAIN_SCREENSHOT") {
                Some(path) => {
                    commands.spawn(Screenshot::primary_window()).observe(
                        move |shot: On<ScreenshotCaptured>, mut exit: MessageWriter<AppExit>| {
                            if let Ok(img) = shot.image.clone().try_into_dynamic() {
                                let _ = img.to_rgb8().save(&path);
                            }
                            exit.write(AppExit::Success);
                        },
                    );
                }
                None => {
                    exit.write(AppExit::Success);
                }
            }
        }
        _ => {}
    }
}
