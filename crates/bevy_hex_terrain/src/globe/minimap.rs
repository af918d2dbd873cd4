//! The globe's minimap (the `minimap` feature): the core's equirectangular
//! [`GlobeMinimap`] of the shown globe in a Bevy UI node, built on the async compute pool when
//! the look or the globe's size changes (an edit or a hot reload is recolored in place), with
//! the [`GlobeCamera`]'s view outlined (where the rays along the border of its view meet the
//! globe, joined by great-circle arcs); pressing or dragging on it turns the cameras to look down
//! on that spot and sends a [`GlobeMinimapNavigate`].

use std::sync::Arc;

use bevy::picking::events::{Drag, Pointer, Press};
use bevy::prelude::*;
use bevy::tasks::futures::check_ready;
use bevy::tasks::{AsyncComputeTaskPool, Task};
use hex_terrain::minimap::{GlobeMinimap, TileLook};
use hex_terrain::{GlobeTerrain, GlobeTile};

use super::{GlobeCamera, GlobeTileStates, HexGlobe, globe_horizon};
use crate::minimap::{HexMinimapSettings, layout, match_terrain, new_image, redraw_outline};
use crate::tiles::{FogState, HexTileStateStyle};

/// The globe's minimap picture and what it was built for (the core's picture and the building
/// task are not reflected).
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct GlobeMinimapPicture {
    #[reflect(ignore)]
    picture: Option<Arc<GlobeMinimap>>,
    /// The painted picture without the outline (RGBA8 sRGB).
    painted: Vec<u8>,
    /// The outline's pixels drawn over it.
    outline: Vec<u32>,
    image: Handle<Image>,
    #[reflect(ignore)]
    task: Option<Task<Option<GlobeMinimap>>>,
    /// The globe generation and the style the shown (or building) picture is for.
    #[reflect(ignore)]
    made_for: Option<(u64, u32, MinimapStyleKey)>,
    /// Where on the node the pointer last pressed (`-0.5..0.5`), for drags.
    pressed_at: Option<Vec2>,
    /// Pixels whose color a tile state change changed, since the start.
    repainted: u64,
    /// Full paints of the picture since the start (a built picture, a change of style, the
    /// tile states reset).
    full_paints: u64,
    /// Globes of the picture's size taken in place (edits, hot reloads).
    recolors: u64,
}

/// What of the style a picture is built with (a change rebuilds it): the kinds' colors, the
/// background and the owners' colors.
type MinimapStyleKey = ([[u8; 3]; 3], [u8; 4], Vec<[u8; 3]>);

impl GlobeMinimapPicture {
    /// The picture shown, with its pixels' tiles; `None` until the first is built.
    #[must_use]
    pub fn minimap(&self) -> Option<&GlobeMinimap> {
        self.picture.as_deref()
    }

    /// The image the node shows.
    #[must_use]
    pub fn image(&self) -> &Handle<Image> {
        &self.image
    }

    /// The pixels (row-major) of the camera's view outline drawn now.
    #[must_use]
    pub fn outline(&self) -> &[u32] {
        &self.outline
    }

    /// Pixels whose color tile state writes changed, since the start (a full paint counts
    /// those it changed too). Only the written tiles' pixels and those beside them are painted
    /// again, so a write that changes no look (a highlight) changes none.
    #[must_use]
    pub fn repainted_pixels(&self) -> u64 {
        self.repainted
    }

    /// Globes of the picture's size (an edit, a hot reload) taken into the shown picture since
    /// the start, in place: only the tiles whose color changed painted again, no picture built.
    #[must_use]
    pub fn recolors(&self) -> u64 {
        self.recolors
    }

    /// Whole-picture paints since the start: each picture built, and a repaint after a change of
    /// the tile states' style or after more writes in a frame than the states keep a list of.
    #[must_use]
    pub fn full_paints(&self) -> u64 {
        self.full_paints
    }
}

/// Sent when the player presses or drags on the globe's minimap: the spot under the pointer,
/// which every [`GlobeCamera`] now looks down on.
#[derive(Message, Debug, Clone, Copy, PartialEq, Reflect)]
pub struct GlobeMinimapNavigate {
    /// The tile under the pointer.
    pub tile: GlobeTile,
    /// Its longitude and latitude under the pointer, radians (east and north positive).
    pub at: Vec2,
}

/// The globe minimap's UI node (spawned by [`HexGlobeMinimapPlugin`], placed by
/// [`HexMinimapSettings`]).
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
#[require(Node, ImageNode, Outline, BackgroundColor)]
pub struct HexGlobeMinimap;

/// The globe's minimap: [`GlobeMinimapPicture`], the [`HexGlobeMinimap`] node and the
/// [`GlobeMinimapNavigate`] message, placed and colored by the [`HexMinimapSettings`] resource
/// (its `size.x` the picture's width, its height half that; a value inserted before the plugin
/// is added is kept). Add it after [`HexGlobePlugin`](super::HexGlobePlugin); it needs a UI
/// camera to be seen. Tiles show their terrain's minimap color (their type's on a globe without
/// a climate), with the [`GlobeTileStates`]: owners' tint and borders, and the fog of war when
/// the [`HexTileStateStyle`] draws it.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexGlobeMinimapPlugin;

impl Plugin for HexGlobeMinimapPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<super::HexGlobePlugin>() {
            panic!("HexGlobeMinimapPlugin needs HexGlobePlugin: add it before");
        }
        app.init_resource::<HexMinimapSettings>()
            .init_resource::<GlobeMinimapPicture>()
            .add_message::<GlobeMinimapNavigate>()
            .register_type::<GlobeMinimapPicture>()
            .register_type::<HexGlobeMinimap>()
            .register_type::<GlobeMinimapNavigate>()
            .add_systems(Startup, spawn_node)
            .add_systems(
                PostUpdate,
                (place_node, build, finish, repaint, draw_outline)
                    .chain()
                    .after(bevy::transform::TransformSystems::Propagate)
                    .before(crate::HexTileStateSystems::Pack),
            );
    }
}

fn spawn_node(mut commands: Commands, mut images: ResMut<Assets<Image>>, mut picture: ResMut<GlobeMinimapPicture>) {
    picture.image = images.add(new_image([1, 1], vec![0, 0, 0, 0]));
    commands
        .spawn((Name::new("hex globe minimap"), HexGlobeMinimap, ImageNode::new(picture.image.clone())))
        .observe(press)
        .observe(drag);
}

fn place_node(
    settings: Res<HexMinimapSettings>,
    picture: Res<GlobeMinimapPicture>,
    mut nodes: Query<(&mut Node, &mut Outline, &mut BackgroundColor), With<HexGlobeMinimap>>,
) {
    if !settings.is_changed() && !picture.is_changed() {
        return;
    }
    let size = picture.picture.as_ref().map_or(Vec2::ZERO, |p| UVec2::from(p.size()).as_vec2());
    for (mut node, mut outline, mut background) in &mut nodes {
        (*node, *outline, *background) = layout(&settings, size);
    }
}

/// The picture's width for the settings: `size.x`, even, at least 8.
fn width(settings: &HexMinimapSettings) -> u32 {
    (settings.size.x.clamp(8, hex_terrain::minimap::MAX_GLOBE_MINIMAP_WIDTH) / 2) * 2
}

/// Starts building a picture when the globe, the width or the colors changed (the owners'
/// colors are the tile states' style's, as on the globe). A new globe of the same size (an
/// edit, a hot reload) is recolored in place instead: only its tiles whose color changed are
/// painted again.
fn build(
    globe: Res<HexGlobe>,
    settings: Res<HexMinimapSettings>,
    (tiles, states): (Res<HexTileStateStyle>, Res<GlobeTileStates>),
    mut picture: ResMut<GlobeMinimapPicture>,
    mut images: ResMut<Assets<Image>>,
) {
    let Some(terrain) = globe.globe() else { return };
    let mut style = settings.style();
    // The owners' colors; whether the fog is drawn is each paint's (`look`), as the style says
    // then, not the picture's.
    let fog = style.fog_of_war;
    match_terrain(&mut style, None, &tiles);
    style.fog_of_war = fog;
    let key = (globe.generation(), width(&settings), (style.kind_colors, style.background, style.owner_colors.clone()));
    if picture.made_for.as_ref() == Some(&key) {
        return;
    }
    let picture = &mut *picture;
    let same_look = picture.made_for.as_ref().is_some_and(|(_, w, s)| (w, s) == (&key.1, &key.2));
    if same_look
        && picture.task.is_none()
        && let Some(shown) = picture.picture.as_mut()
        && let Some(changed) = Arc::make_mut(shown).recolor(terrain)
    {
        picture.made_for = Some(key);
        picture.recolors += 1;
        let changed = shown.repaint(changed, |t| look(&states, &tiles, t), &mut picture.painted);
        picture.repainted += changed as u64;
        if changed > 0
            && let Some(mut image) = images.get_mut(&picture.image)
            && let Some(data) = image.data.as_mut()
        {
            data.copy_from_slice(&picture.painted);
            picture.outline.clear();
        }
        return;
    }
    let w = key.1;
    picture.made_for = Some(key);
    let terrain: Arc<GlobeTerrain> = terrain.clone();
    picture.task = Some(AsyncComputeTaskPool::get().spawn(async move { GlobeMinimap::new(&terrain, w, style) }));
}

/// A tile's look from the tile states: every tile visible while the fog of war is not drawn.
fn look(states: &GlobeTileStates, style: &HexTileStateStyle, tile: GlobeTile) -> TileLook {
    let fog = if style.fog_of_war { states.visibility(tile) } else { FogState::Visible };
    TileLook { fog, owner: states.owner(tile) }
}

/// Shows a finished picture, painted with the tile states.
fn finish(
    mut picture: ResMut<GlobeMinimapPicture>,
    states: Res<GlobeTileStates>,
    style: Res<HexTileStateStyle>,
    mut images: ResMut<Assets<Image>>,
) {
    let Some(task) = picture.task.as_mut() else { return };
    let Some(built) = check_ready(task) else { return };
    picture.task = None;
    let Some(built) = built else { return };
    picture.painted = built.paint(|t| look(&states, &style, t));
    picture.full_paints += 1;
    picture.outline.clear();
    let _ = images.insert(&picture.image, new_image(built.size(), picture.painted.clone()));
    picture.picture = Some(Arc::new(built));
}

/// Paints the shown picture again where the tile states changed: the tiles written this frame
/// (and the pixels beside them); the whole picture when the style changed or the states list no
/// tiles (more writes than they keep a list of, or reset).
fn repaint(
    mut picture: ResMut<GlobeMinimapPicture>,
    states: Res<GlobeTileStates>,
    style: Res<HexTileStateStyle>,
    mut images: ResMut<Assets<Image>>,
) {
    if !(states.is_changed() || style.is_changed()) {
        return;
    }
    let picture = &mut *picture;
    let Some(shown) = &picture.picture else { return };
    let changed = match states.changed_tiles().filter(|_| !style.is_changed()) {
        Some(tiles) => shown.repaint(tiles.iter().copied(), |t| look(&states, &style, t), &mut picture.painted),
        None => {
            let painted = shown.paint(|t| look(&states, &style, t));
            picture.full_paints += 1;
            let changed = painted.chunks_exact(4).zip(picture.painted.chunks_exact(4)).filter(|(a, b)| a != b).count();
            picture.painted = painted;
            changed
        }
    };
    if changed == 0 {
        return;
    }
    picture.repainted += changed as u64;
    if let Some(mut image) = images.get_mut(&picture.image)
        && let Some(data) = image.data.as_mut()
    {
        data.copy_from_slice(&picture.painted);
        // The outline is drawn again over the repainted picture.
        picture.outline.clear();
    }
}

/// Draws the cameras' view over the picture, restoring the pixels under the last outline: for
/// each [`GlobeCamera`], where the rays along the border of its view meet the globe (the limb,
/// where they pass it), joined by great-circle arcs; before its projection is known (no
/// render target yet), the circle of its horizon (the ground streamed for it).
fn draw_outline(
    mut picture: ResMut<GlobeMinimapPicture>,
    settings: Res<HexMinimapSettings>,
    globe: Res<HexGlobe>,
    cameras: Query<(&GlobalTransform, Option<&Camera>), With<GlobeCamera>>,
    mut images: ResMut<Assets<Image>>,
) {
    let (Some(shown), Some(terrain)) = (picture.picture.clone(), globe.globe()) else { return };
    let (radius, max_elevation) = (terrain.radius() as f32, terrain.config().terrain.max_elevation);
    let mut outline: Vec<u32> = cameras
        .iter()
        .flat_map(|(t, camera)| match camera.and_then(|c| view_on_globe(c, t, f64::from(radius))) {
            Some(corners) => shown.polygon_outline(&corners),
            None => {
                let p = t.translation();
                let angle = globe_horizon(radius, max_elevation, p.length());
                shown.view_outline(p.as_dvec3().to_array(), f64::from(angle))
            }
        })
        .collect();
    outline.sort_unstable();
    outline.dedup();
    if outline == picture.outline && !picture.is_changed() {
        return;
    }
    let Some(mut image) = images.get_mut(&picture.image) else { return };
    let Some(data) = image.data.as_mut() else { return };
    if redraw_outline(data, &picture.painted, &picture.outline, &outline, settings.outline_color) {
        picture.outline = outline;
    }
}

fn press(
    press: On<Pointer<Press>>,
    mut picture: ResMut<GlobeMinimapPicture>,
    mut cameras: Query<&mut GlobeCamera>,
    mut go: MessageWriter<GlobeMinimapNavigate>,
) {
    let Some(at) = press.hit.position.map(|p| p.truncate()) else { return };
    picture.pressed_at = Some(at);
    navigate(&picture, at, &mut cameras, &mut go);
}

fn drag(
    drag: On<Pointer<Drag>>,
    picture: Res<GlobeMinimapPicture>,
    nodes: Query<&ComputedNode, With<HexGlobeMinimap>>,
    mut cameras: Query<&mut GlobeCamera>,
    mut go: MessageWriter<GlobeMinimapNavigate>,
) {
    let (Some(start), Ok(node)) = (picture.pressed_at, nodes.get(drag.entity)) else { return };
    let size = node.size() * node.inverse_scale_factor();
    if size.min_element() > 0.0 {
        navigate(&picture, start + drag.distance / size, &mut cameras, &mut go);
    }
}

/// Turns the cameras to look down on the spot at a position on the node (`-0.5..0.5` on each
/// axis, as Bevy's UI picking reports it), keeping their altitude, and says so.
fn navigate(
    picture: &GlobeMinimapPicture,
    at: Vec2,
    cameras: &mut Query<&mut GlobeCamera>,
    go: &mut MessageWriter<GlobeMinimapNavigate>,
) {
    let Some(shown) = picture.picture.as_ref() else { return };
    if let Some(message) = spot(shown, at) {
        for mut camera in cameras.iter_mut() {
            camera.orientation = GlobeCamera::above(message.at.x, message.at.y).orientation;
        }
        go.write(message);
    }
}

/// The spot at a position on the node (`-0.5..0.5`, clamped to the picture).
fn spot(shown: &GlobeMinimap, at: Vec2) -> Option<GlobeMinimapNavigate> {
    let [w, h] = shown.size().map(|v| v as f32);
    let (x, y) = ((at.x + 0.5).clamp(0.0, 1.0) * w, (at.y + 0.5).clamp(0.0, 1.0) * h);
    let tile = shown.tile_at_pixel((x as u32).min(shown.size()[0] - 1), (y as u32).min(shown.size()[1] - 1))?;
    let longitude = (x / w * 2.0 - 1.0) * std::f32::consts::PI;
    let latitude = (0.5 - y / h) * std::f32::consts::PI;
    Some(GlobeMinimapNavigate { tile, at: Vec2::new(longitude, latitude) })
}

/// Where the rays along the border of a camera's view meet a globe of `radius` centered at the
/// origin, going round the view (four points an edge); a ray that passes the globe gives the
/// limb point in its direction. `None` while the camera has no projection.
fn view_on_globe(camera: &Camera, transform: &GlobalTransform, radius: f64) -> Option<Vec<[f64; 3]>> {
    const STEPS: usize = 4;
    let border = (0..4 * STEPS).map(|k| {
        let (edge, t) = (k / STEPS, (k % STEPS) as f32 / STEPS as f32 * 2.0 - 1.0);
        match edge {
            0 => Vec2::new(t, 1.0),
            1 => Vec2::new(1.0, -t),
            2 => Vec2::new(-t, -1.0),
            _ => Vec2::new(-1.0, t),
        }
    });
    border
        .map(|ndc| {
            // Reverse-z: 1 is the near plane; a point a little farther gives the direction.
            let near = camera.ndc_to_world(transform, bevy::math::Vec3A::from(ndc.extend(1.0)))?.as_dvec3();
            let farther = camera.ndc_to_world(transform, bevy::math::Vec3A::from(ndc.extend(0.5)))?.as_dvec3();
            let d = (farther - near).try_normalize()?;
            near.is_finite().then(|| ground_or_limb(near, d, radius).to_array())
        })
        .collect()
}

/// The direction from the globe's center of where a ray from `origin` along unit `d` first
/// meets the sphere of `radius`, or, when it passes it, of the sphere's limb seen from
/// `origin` in the ray's direction.
fn ground_or_limb(origin: bevy::math::DVec3, d: bevy::math::DVec3, radius: f64) -> bevy::math::DVec3 {
    let b = origin.dot(d);
    let disc = b * b - (origin.length_squared() - radius * radius);
    if disc >= 0.0 {
        let t = -b - disc.sqrt();
        if t >= 0.0 {
            return (origin + d * t).normalize();
        }
    }
    let out = origin.normalize();
    let across = (d - out * d.dot(out)).normalize_or_zero();
    let angle = (radius / origin.length()).clamp(-1.0, 1.0).acos();
    (out * angle.cos() + across * angle.sin()).normalize()
}

#[cfg(test)]
mod tests {
    use bevy::math::DVec3;

    use super::ground_or_limb;

    #[test]
    fn rays_meet_the_ground_or_the_limb() {
        let origin = DVec3::new(0.0, 0.0, 10.0);
        // Straight down: the point under the camera.
        assert!((ground_or_limb(origin, DVec3::NEG_Z, 5.0) - DVec3::Z).length() < 1e-12);
        // Past the globe: the limb point, whose ray from the camera grazes the sphere.
        let d = DVec3::new(0.8, 0.0, -0.6).normalize();
        let limb = ground_or_limb(origin, d, 5.0) * 5.0;
        assert!((limb.length() - 5.0).abs() < 1e-9);
        assert!((limb - origin).dot(limb).abs() < 1e-9, "the ray to the limb is tangent");
        assert!(limb.x > 0.0, "on the ray's side");
    }
}
