//! A minimap (the `minimap` cargo feature): a top-down picture of the map in a Bevy UI node, from
//! the core's [`Minimap`] picture, drawn with the tiles' biome or type colors, rivers and lakes,
//! the owners' tint and borders and fog of war from [`TileStates`] (unexplored black, explored
//! dim), and the camera's view as an outline. A bounded map is shown whole (a wrapping one over
//! one period, so the picture wraps); an unbounded world in a rectangle of tiles around the
//! camera, rebuilt when the camera leaves its middle.
//!
//! The picture is built on the async compute pool when the map or the style changes (the old
//! one stays until the new one is ready) and then only repainted where [`TileStates`] was
//! written this frame ([`TileStates::changed_tiles`]): the tiles written and their neighbors.
//! Pressing or dragging on the node sends a [`MinimapNavigate`] message with the tile and the
//! world position under the pointer; the game's camera code moves there:
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_hex_terrain::minimap::MinimapNavigate;
//!
//! fn follow(mut go: MessageReader<MinimapNavigate>, mut camera: Query<&mut Transform, With<Camera3d>>) {
//!     for go in go.read() {
//!         for mut t in &mut camera {
//!             // Keep the camera's height and angle; look at the new spot.
//!             let offset = t.translation - Vec3::new(go.world.x as f32, 0.0, go.world.y as f32);
//!             t.translation = Vec3::new(go.world.x as f32, t.translation.y, go.world.y as f32 + offset.z);
//!         }
//!     }
//! }
//! # App::new().add_systems(Update, follow);
//! ```

mod view;

use std::sync::Arc;

use bevy::asset::RenderAssetUsages;
use bevy::image::ImageSampler;
use bevy::math::DVec2;
use bevy::picking::events::{Drag, Pointer, Press};
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use bevy::tasks::futures::check_ready;
use bevy::tasks::{AsyncComputeTaskPool, Task};
use bevy::transform::TransformSystems;
use hex_terrain::hexx::Hex;
use hex_terrain::minimap::{Minimap, MinimapStyle, TileLook};
use hex_terrain::{Terrain, TileRect};

use crate::HexMap;
use crate::tiles::{HexTileStateSystems, TileStates};

pub use view::HexMinimapCamera;

/// Which corner of the window the minimap sits in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Reflect)]
pub enum MinimapCorner {
    /// Top left.
    TopLeft,
    /// Top right.
    TopRight,
    /// Bottom left.
    BottomLeft,
    /// Bottom right.
    #[default]
    BottomRight,
}

/// The minimap's settings; change them at run time (a change of the look rebuilds the picture).
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(Resource)]
pub struct MinimapSettings {
    /// Show the minimap.
    pub visible: bool,
    /// The window corner it sits in.
    pub corner: MinimapCorner,
    /// Distance from the corner, in logical pixels.
    pub margin: Vec2,
    /// Largest size of the picture, in logical pixels (one picture pixel each): the map is
    /// fitted inside with square pixels.
    pub size: UVec2,
    /// Tiles around the camera shown on an unbounded map (columns, rows).
    pub region: UVec2,
    /// Colors of sea, land and mountain tiles on maps without climate (the terrain material's
    /// layer colors when the `render` feature has them).
    pub kind_colors: [Color; 3],
    /// Rivers and lakes.
    pub water_color: Color,
    /// Unexplored tiles.
    pub unexplored_color: Color,
    /// Brightness of explored tiles not in sight, `0..=1`.
    pub explored_brightness: f32,
    /// Draw fog of war from [`TileStates::visibility`] (off: every tile in full color).
    pub fog_of_war: bool,
    /// Owner colors: owner `n` takes entry `n - 1` (the terrain material's palette when the
    /// `render` feature has it).
    pub owner_colors: Vec<Color>,
    /// How much an owned tile takes its owner's color, `0..=1`.
    pub territory_tint: f32,
    /// Border line width inside owned tiles, a fraction of the hex radius.
    pub border_width: f32,
    /// River line width, a fraction of the hex radius.
    pub river_width: f32,
    /// Color around the map and of the node's frame.
    pub background: Color,
    /// The camera's view outline.
    pub outline_color: Color,
}

impl Default for MinimapSettings {
    fn default() -> Self {
        let style = MinimapStyle::default();
        let color = |[r, g, b]: [u8; 3]| Color::srgb_u8(r, g, b);
        Self {
            visible: true,
            corner: MinimapCorner::BottomRight,
            margin: Vec2::splat(12.0),
            size: UVec2::new(280, 200),
            region: UVec2::new(96, 64),
            kind_colors: style.kind_colors.map(color),
            water_color: color(style.water_color),
            unexplored_color: Color::BLACK,
            explored_brightness: style.explored_brightness,
            fog_of_war: true,
            owner_colors: style.owner_colors.iter().copied().map(color).collect(),
            territory_tint: style.territory_tint,
            border_width: style.border_width as f32,
            river_width: style.river_width as f32,
            background: Color::srgb_u8(12, 14, 18),
            outline_color: Color::WHITE,
        }
    }
}

impl MinimapSettings {
    /// The core's style for these settings.
    #[must_use]
    pub fn style(&self) -> MinimapStyle {
        let rgb = |c: Color| {
            let [r, g, b, _] = c.to_srgba().to_u8_array();
            [r, g, b]
        };
        let rgba = |c: Color| c.to_srgba().to_u8_array();
        MinimapStyle {
            kind_colors: self.kind_colors.map(rgb),
            water_color: rgb(self.water_color),
            river_width: f64::from(self.river_width),
            background: rgba(self.background),
            fog_of_war: self.fog_of_war,
            unexplored: rgba(self.unexplored_color),
            explored_brightness: self.explored_brightness,
            owner_colors: self.owner_colors.iter().copied().map(rgb).collect(),
            territory_tint: self.territory_tint,
            border_width: f64::from(self.border_width),
        }
    }
}

/// Sent when the player presses or drags on the minimap: where the camera should go.
#[derive(Message, Debug, Clone, Copy, PartialEq, Reflect)]
pub struct MinimapNavigate {
    /// The tile under the pointer (the map's own tile on a wrapping map).
    pub tile: Hex,
    /// World `(x, z)` under the pointer, in f64; on a wrapping map the copy nearest the camera.
    pub world: DVec2,
}

/// The minimap's UI node (spawned by [`HexMinimapPlugin`], placed by [`MinimapSettings`]).
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
#[require(Node, ImageNode, Outline, BackgroundColor)]
pub struct HexMinimap;

/// The picture shown and what it is built from.
#[derive(Resource, Default)]
pub struct MinimapPicture {
    picture: Option<Minimap>,
    /// The painted picture without the outline (RGBA8 sRGB).
    painted: Vec<u8>,
    /// The outline's pixels drawn over it.
    outline: Vec<u32>,
    image: Handle<Image>,
    task: Option<Task<Option<Minimap>>>,
    /// What the shown (or building) picture was made for: the map's generation and the region.
    made_for: Option<(u64, TileRect)>,
    /// Pixels repainted since the start (figures for tests and the stats overlay).
    repainted: u64,
    /// Pictures built since the start.
    builds: u64,
    /// Where on the node the pointer last pressed (`-0.5..0.5`), for drags.
    pressed_at: Option<Vec2>,
}

impl MinimapPicture {
    /// The picture shown, with its pixels' tiles and the world position of every pixel; `None`
    /// until the first is built.
    #[must_use]
    pub fn minimap(&self) -> Option<&Minimap> {
        self.picture.as_ref()
    }

    /// The image the node shows.
    #[must_use]
    pub fn image(&self) -> &Handle<Image> {
        &self.image
    }

    /// Whether a picture is being built.
    #[must_use]
    pub fn is_building(&self) -> bool {
        self.task.is_some()
    }

    /// Pixels repainted from tile state changes since the start (a full paint counts them all).
    #[must_use]
    pub fn repainted_pixels(&self) -> u64 {
        self.repainted
    }

    /// Pictures built since the start (a new map, a hot reload, a change of style, the camera
    /// leaving an unbounded map's region).
    #[must_use]
    pub fn builds(&self) -> u64 {
        self.builds
    }
}

/// The minimap's system sets in `PostUpdate` (after transforms are propagated, before the tile
/// state's list of changes is started again).
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HexMinimapSystems {
    /// Places the node, builds and repaints the picture, draws the camera's outline.
    Draw,
}

/// The minimap: [`MinimapSettings`], the [`HexMinimap`] node, the [`MinimapPicture`] and the
/// [`MinimapNavigate`] message. Not in [`HexTerrainPlugins`](crate::HexTerrainPlugins): add it
/// after them; it needs a UI camera to be seen.
#[derive(Debug, Clone, Default)]
pub struct HexMinimapPlugin {
    /// The minimap's settings (the [`MinimapSettings`] resource).
    pub settings: MinimapSettings,
}

impl Plugin for HexMinimapPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<crate::HexTileStatePlugin>() {
            panic!("HexMinimapPlugin needs HexTileStatePlugin: add HexTerrainPlugins before it");
        }
        app.insert_resource(self.settings.clone())
            .init_resource::<MinimapPicture>()
            .add_message::<MinimapNavigate>()
            .register_type::<MinimapSettings>()
            .register_type::<HexMinimap>()
            .register_type::<HexMinimapCamera>()
            .register_type::<MinimapNavigate>()
            .add_systems(Startup, spawn_node)
            .configure_sets(
                PostUpdate,
                HexMinimapSystems::Draw.after(TransformSystems::Propagate).before(HexTileStateSystems::Pack),
            )
            .add_systems(
                PostUpdate,
                (place_node, build_picture, finish_picture, repaint, view::draw_outline)
                    .chain()
                    .in_set(HexMinimapSystems::Draw),
            );
    }
}

fn spawn_node(mut commands: Commands, mut images: ResMut<Assets<Image>>, mut picture: ResMut<MinimapPicture>) {
    picture.image = images.add(new_image([1, 1], vec![0, 0, 0, 0]));
    commands
        .spawn((Name::new("hex minimap"), HexMinimap, ImageNode::new(picture.image.clone())))
        .observe(press)
        .observe(drag);
}

fn new_image([w, h]: [u32; 2], data: Vec<u8>) -> Image {
    let size = Extent3d { width: w, height: h, depth_or_array_layers: 1 };
    let mut image =
        Image::new(size, TextureDimension::D2, data, TextureFormat::Rgba8UnormSrgb, RenderAssetUsages::default());
    image.sampler = ImageSampler::nearest();
    image
}

/// Places and sizes the node from the settings and the picture.
fn place_node(
    settings: Res<MinimapSettings>,
    picture: Res<MinimapPicture>,
    mut nodes: Query<(&mut Node, &mut Outline, &mut BackgroundColor), With<HexMinimap>>,
) {
    if !settings.is_changed() && !picture.is_changed() {
        return;
    }
    let size = picture.picture.as_ref().map_or(Vec2::ZERO, |p| UVec2::from(p.size()).as_vec2());
    for (mut node, mut outline, mut background) in &mut nodes {
        let m = settings.margin;
        let (top, bottom) = match settings.corner {
            MinimapCorner::TopLeft | MinimapCorner::TopRight => (Val::Px(m.y), Val::Auto),
            _ => (Val::Auto, Val::Px(m.y)),
        };
        let (left, right) = match settings.corner {
            MinimapCorner::TopLeft | MinimapCorner::BottomLeft => (Val::Px(m.x), Val::Auto),
            _ => (Val::Auto, Val::Px(m.x)),
        };
        *node = Node {
            position_type: PositionType::Absolute,
            top,
            bottom,
            left,
            right,
            width: Val::Px(size.x),
            height: Val::Px(size.y),
            display: if settings.visible && size.x > 0.0 { Display::Flex } else { Display::None },
            ..default()
        };
        // A frame outside the node (a border would shrink the picture inside the node, whose
        // whole rectangle the pointer positions are relative to).
        *outline = Outline::new(Val::Px(2.0), Val::ZERO, settings.outline_color.with_alpha(0.6));
        *background = BackgroundColor(settings.background);
    }
}

/// The region a picture shows: a bounded map's tiles, or tiles around the camera's focus on an
/// unbounded world (kept while the focus stays in the middle half).
fn region(terrain: &Terrain, settings: &MinimapSettings, focus: Option<Hex>, current: Option<TileRect>) -> TileRect {
    if let Some(bounds) = terrain.bounds() {
        return bounds;
    }
    let size = settings.region.clamp(UVec2::splat(4), UVec2::splat(1024));
    let [col, row] = focus.map_or([0, 0], |t| terrain.offset_of(t));
    if let Some(r) = current {
        let (w, h) = ((r.max[0] - r.min[0]) / 4, (r.max[1] - r.min[1]) / 4);
        if col >= r.min[0] + w
            && col < r.max[0] - w
            && row >= r.min[1] + h
            && row < r.max[1] - h
            && r.max[0] - r.min[0] == size.x as i32
            && r.max[1] - r.min[1] == size.y as i32
        {
            return r;
        }
    }
    TileRect::new([col - size.x as i32 / 2, row - size.y as i32 / 2], [size.x, size.y])
}

/// Starts building a picture when the map, the style or an unbounded map's region changed.
fn build_picture(
    map: Res<HexMap>,
    settings: Res<MinimapSettings>,
    appearance: Option<Res<crate::TerrainAppearance>>,
    camera: view::MinimapCameraView,
    mut picture: ResMut<MinimapPicture>,
) {
    let terrain: &Arc<Terrain> = map.terrain();
    let focus = camera.focus(&map).and_then(|p| terrain.tile_at(p.x, p.y));
    let current = picture.made_for.map(|(_, r)| r);
    let region = region(terrain, &settings, focus, current);
    let restyled = settings.is_changed() || appearance.as_ref().is_some_and(|a| a.is_changed());
    if !restyled && picture.made_for == Some((map.generation(), region)) {
        return;
    }
    let mut style = settings.style();
    if let Some(appearance) = &appearance {
        style_from_appearance(&mut style, appearance);
    }
    let (terrain, size) = (Arc::clone(terrain), settings.size.to_array());
    picture.made_for = Some((map.generation(), region));
    picture.task = Some(AsyncComputeTaskPool::get().spawn(async move { Minimap::new(&terrain, region, size, style) }));
}

/// The terrain material's colors, so the minimap matches the terrain.
fn style_from_appearance(style: &mut MinimapStyle, appearance: &crate::TerrainAppearance) {
    let rgb = |c: Color| {
        let [r, g, b, _] = c.to_srgba().to_u8_array();
        [r, g, b]
    };
    style.kind_colors = appearance.colors.map(rgb);
    style.fog_of_war &= appearance.fog_of_war;
    let owners = crate::material::owner_colors(appearance);
    style.owner_colors = owners.colors.iter().map(|c| rgb(Color::LinearRgba(LinearRgba::from_vec4(*c)))).collect();
}

/// Shows a finished picture: painted whole with the tiles' state.
fn finish_picture(mut picture: ResMut<MinimapPicture>, states: Res<TileStates>, mut images: ResMut<Assets<Image>>) {
    let Some(task) = picture.task.as_mut() else { return };
    let Some(built) = check_ready(task) else { return };
    let picture = &mut *picture;
    picture.task = None;
    let Some(built) = built else { return };
    let painted = built.paint(|t| look(&states, t));
    picture.repainted += (painted.len() / 4) as u64;
    picture.builds += 1;
    picture.outline.clear();
    if let Some(mut image) = images.get_mut(&picture.image) {
        *image = new_image(built.size(), painted.clone());
    }
    picture.painted = painted;
    picture.picture = Some(built);
}

/// A tile's look from the tile states.
fn look(states: &TileStates, tile: Hex) -> TileLook {
    TileLook { fog: states.visibility(tile), owner: states.owner(tile) }
}

/// Repaints the tiles written this frame (and their neighbors) in the shown picture.
fn repaint(mut picture: ResMut<MinimapPicture>, states: Res<TileStates>, mut images: ResMut<Assets<Image>>) {
    if !states.is_changed() {
        return;
    }
    let picture = &mut *picture;
    let Some(shown) = &picture.picture else { return };
    let written = match states.changed_tiles() {
        None => {
            picture.painted = shown.paint(|t| look(&states, t));
            picture.painted.len() / 4
        }
        Some(tiles) => shown.repaint(tiles, |t| look(&states, t), &mut picture.painted),
    };
    if written == 0 {
        return;
    }
    picture.repainted += written as u64;
    if let Some(mut image) = images.get_mut(&picture.image)
        && let Some(data) = image.data.as_mut()
    {
        data.copy_from_slice(&picture.painted);
        // The outline is drawn again over the repainted picture.
        picture.outline.clear();
    }
}

/// Sends the camera where the pointer pressed.
fn press(
    press: On<Pointer<Press>>,
    mut picture: ResMut<MinimapPicture>,
    camera: view::MinimapCameraView,
    map: Res<HexMap>,
    mut go: MessageWriter<MinimapNavigate>,
) {
    let Some(at) = press.hit.position.map(|p| p.truncate()) else { return };
    // The drag observer goes on from here.
    picture.pressed_at = Some(at);
    if let Some(message) = navigate(&picture, &camera, &map, at) {
        go.write(message);
    }
}

/// Keeps sending the camera under the pointer while it drags.
fn drag(
    drag: On<Pointer<Drag>>,
    picture: Res<MinimapPicture>,
    nodes: Query<&ComputedNode, With<HexMinimap>>,
    camera: view::MinimapCameraView,
    map: Res<HexMap>,
    mut go: MessageWriter<MinimapNavigate>,
) {
    let (Some(start), Ok(node)) = (picture.pressed_at, nodes.get(drag.entity)) else { return };
    let size = node.size() * node.inverse_scale_factor();
    if size.min_element() <= 0.0 {
        return;
    }
    if let Some(message) = navigate(&picture, &camera, &map, start + drag.distance / size) {
        go.write(message);
    }
}

/// Where a position on the node (`-0.5..0.5` on each axis, the center at zero, as Bevy's UI
/// picking reports it) sends the camera.
fn navigate(
    picture: &MinimapPicture,
    camera: &view::MinimapCameraView,
    map: &HexMap,
    at: Vec2,
) -> Option<MinimapNavigate> {
    let shown = picture.picture.as_ref()?;
    let [w, h] = shown.size().map(f64::from);
    let at = at.as_dvec2() + DVec2::splat(0.5);
    let (px, py) = (at.x.clamp(0.0, 1.0) * w, at.y.clamp(0.0, 1.0) * h);
    let tile = shown.tile_at_pixel((px as u32).min(shown.size()[0] - 1), (py as u32).min(shown.size()[1] - 1))?;
    let [mut x, z] = shown.pixel_to_world(px, py);
    if let (Some(wrap), Some(focus)) = (map.terrain().wrap(), camera.focus(map)) {
        // The copy of the spot nearest the camera.
        x += ((focus.x - x) / wrap.width).round() * wrap.width;
    }
    Some(MinimapNavigate { tile, world: DVec2::new(x, z) })
}
