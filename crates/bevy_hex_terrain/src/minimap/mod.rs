//! A minimap (the `minimap` cargo feature): a top-down picture of the map in a Bevy UI node, from
//! the core's [`Minimap`](hex_terrain::minimap::Minimap) picture, drawn with the tiles' biome or type colors, rivers and lakes,
//! the owners' tint and borders and fog of war from [`TileStates`](crate::TileStates) (unexplored black, explored
//! dim), and the camera's view as an outline. A bounded map is shown whole (a wrapping one over
//! one period, so the picture wraps); an unbounded world in a rectangle of tiles around the
//! camera, rebuilt when the camera leaves its middle.
//!
//! The picture is built on the async compute pool when the map or the style changes (the old
//! one stays until the new one is ready) and then only repainted where [`TileStates`](crate::TileStates) was
//! written this frame ([`TileStates::changed_tiles`](crate::TileStates::changed_tiles)): the tiles written and their neighbors.
//! Pressing or dragging on the node sends a [`MinimapNavigate`] message with the tile and the
//! world position under the pointer; the game's camera code moves there (see
//! [`HexMinimapPlugin`]).

mod navigate;
mod picture;
mod view;

use bevy::math::DVec2;
use bevy::prelude::*;
use bevy::transform::TransformSystems;
use hex_terrain::hexx::Hex;
use hex_terrain::minimap::MinimapStyle;

use crate::tiles::HexTileStateSystems;

pub use picture::MinimapPicture;
pub(crate) use picture::{match_terrain, new_image};
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
#[derive(Resource, Debug, Clone, PartialEq, Reflect)]
#[reflect(Resource)]
pub struct HexMinimapSettings {
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
    /// Draw fog of war from [`TileStates::visibility`](crate::TileStates::visibility) while
    /// [`HexTileStateStyle::fog_of_war`](crate::HexTileStateStyle::fog_of_war) draws it on the terrain
    /// (off: every tile in full color).
    pub fog_of_war: bool,
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

impl Default for HexMinimapSettings {
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
            territory_tint: style.territory_tint,
            border_width: style.border_width as f32,
            river_width: style.river_width as f32,
            background: Color::srgb_u8(12, 14, 18),
            outline_color: Color::WHITE,
        }
    }
}

impl HexMinimapSettings {
    /// The core's style for these settings (owner colors come from the
    /// [`HexTileStateStyle`](crate::HexTileStateStyle), which the picture's systems add).
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
            owner_colors: Vec::new(),
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

/// The minimap's UI node (spawned by [`HexMinimapPlugin`], placed by [`HexMinimapSettings`]).
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
#[require(Node, ImageNode, Outline, BackgroundColor)]
pub struct HexMinimap;

/// The minimap's system sets in `PostUpdate` (after transforms are propagated, before the tile
/// state's list of changes is started again).
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HexMinimapSystems {
    /// Places the node, builds and repaints the picture, draws the camera's outline.
    Draw,
}

/// The minimap: [`HexMinimapSettings`], the [`HexMinimap`] node, the [`MinimapPicture`] and the
/// [`MinimapNavigate`] message. Not in [`HexTerrainPlugins`](crate::HexTerrainPlugins): add it
/// after them; it needs a UI camera to be seen. The picture shows the tiles' biome or type
/// colors, rivers and lakes, the owners and fog of war of [`TileStates`](crate::TileStates) (as
/// [`HexTileStateStyle`](crate::HexTileStateStyle) draws them) and the camera's view; pressing or
/// dragging on it sends [`MinimapNavigate`], which the game's camera code follows:
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_hex_terrain::MinimapNavigate;
///
/// fn follow(mut go: MessageReader<MinimapNavigate>, mut camera: Query<&mut Transform, With<Camera3d>>) {
///     for go in go.read() {
///         for mut t in &mut camera {
///             // Keep the camera's height and angle; look at the new spot.
///             let offset = t.translation - Vec3::new(go.world.x as f32, 0.0, go.world.y as f32);
///             t.translation = Vec3::new(go.world.x as f32, t.translation.y, go.world.y as f32 + offset.z);
///         }
///     }
/// }
/// # App::new().add_systems(Update, follow);
/// ```
///
/// Its settings are the [`HexMinimapSettings`] resource: a value inserted before the plugin is
/// added is kept.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexMinimapPlugin;

impl Plugin for HexMinimapPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<crate::HexTileStatePlugin>() {
            panic!("HexMinimapPlugin needs HexTileStatePlugin: add HexTerrainPlugins before it");
        }
        app.init_resource::<HexMinimapSettings>()
            .init_resource::<MinimapPicture>()
            .add_message::<MinimapNavigate>()
            .register_type::<HexMinimapSettings>()
            .register_type::<MinimapPicture>()
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
                (place_node, picture::build_picture, picture::finish_picture, picture::repaint, view::draw_outline)
                    .chain()
                    .in_set(HexMinimapSystems::Draw),
            );
    }
}

fn spawn_node(mut commands: Commands, mut images: ResMut<Assets<Image>>, mut picture: ResMut<MinimapPicture>) {
    picture.image = images.add(picture::new_image([1, 1], vec![0, 0, 0, 0]));
    commands
        .spawn((Name::new("hex minimap"), HexMinimap, ImageNode::new(picture.image.clone())))
        .observe(navigate::press)
        .observe(navigate::drag);
}

/// Places and sizes the node from the settings and the picture.
fn place_node(
    settings: Res<HexMinimapSettings>,
    picture: Res<MinimapPicture>,
    mut nodes: Query<(&mut Node, &mut Outline, &mut BackgroundColor), With<HexMinimap>>,
) {
    if !settings.is_changed() && !picture.is_changed() {
        return;
    }
    let size = picture.picture.as_ref().map_or(Vec2::ZERO, |p| UVec2::from(p.size()).as_vec2());
    for (mut node, mut outline, mut background) in &mut nodes {
        (*node, *outline, *background) = layout(&settings, size);
    }
}

/// A minimap node's place, size, frame and background, from the settings and its picture's
/// size (a flat map's and a globe's alike).
pub(crate) fn layout(settings: &HexMinimapSettings, size: Vec2) -> (Node, Outline, BackgroundColor) {
    let m = settings.margin;
    let (top, bottom) = match settings.corner {
        MinimapCorner::TopLeft | MinimapCorner::TopRight => (Val::Px(m.y), Val::Auto),
        _ => (Val::Auto, Val::Px(m.y)),
    };
    let (left, right) = match settings.corner {
        MinimapCorner::TopLeft | MinimapCorner::BottomLeft => (Val::Px(m.x), Val::Auto),
        _ => (Val::Auto, Val::Px(m.x)),
    };
    let node = Node {
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
    // A frame outside the node (a border would shrink the picture inside the node, whose whole
    // rectangle the pointer positions are relative to).
    let outline = Outline::new(Val::Px(2.0), Val::ZERO, settings.outline_color.with_alpha(0.6));
    (node, outline, BackgroundColor(settings.background))
}

/// Draws an outline (`new`, row-major pixels) over a minimap's image `data` in `color`, first
/// giving the pixels of the last one (`old`) back their `painted` colors (the picture without
/// an outline); `false`, drawing nothing, when `data` is not the painted picture's size. A flat
/// map's minimap and a globe's alike.
pub(crate) fn redraw_outline(data: &mut [u8], painted: &[u8], old: &[u32], new: &[u32], color: Color) -> bool {
    if data.len() != painted.len() {
        return false;
    }
    for &i in old {
        let i = i as usize * 4;
        data[i..i + 4].copy_from_slice(&painted[i..i + 4]);
    }
    let color = color.to_srgba().to_u8_array();
    for &i in new {
        let i = i as usize * 4;
        data[i..i + 4].copy_from_slice(&color);
    }
    true
}
