//! Light and air for the terrain: a directional sun with cascaded shadows fitted to the view of
//! a strategy camera, and distance fog so far terrain fades into the sky, each switchable in
//! [`HexLightSettings`] (software renderers and weak GPUs turn shadows off). Cameras opt in with
//! [`HexTerrainCamera`], which brings its fog and ambient light as components of its own.

use bevy::light::{CascadeShadowConfig, CascadeShadowConfigBuilder, DirectionalLightShadowMap};
use bevy::pbr::{DistanceFog, FogFalloff};
use bevy::prelude::*;

use crate::HexTerrainSystems;

/// Put on a camera to light and fog the terrain it shows. It requires a [`Camera3d`], a
/// [`DistanceFog`] and an [`AmbientLight`], components of the camera that you see and may
/// override: while [`HexLightSettings::fog`] is on, the plugin fits the fog's falloff to the
/// camera's height above the sea and its color to [`HexLightSettings::fog_color`] (off, it
/// removes the fog); it sets the ambient light's brightness when [`HexLightSettings`] changes.
/// The sun's shadow cascades follow the first such camera's height.
///
/// Screen-space ambient occlusion is the camera's too: add Bevy's
/// `ScreenSpaceAmbientOcclusion` and `Msaa::Off` (which it needs) to it.
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
#[require(Camera3d, DistanceFog = HexTerrainCamera::fog(), AmbientLight = HexTerrainCamera::ambient())]
pub struct HexTerrainCamera;

impl HexTerrainCamera {
    /// The fog a terrain camera starts with: [`HexLightSettings`]'s default color, fitted to a
    /// camera 20 units above the sea (the plugin refits it from the first frame).
    #[must_use]
    pub fn fog() -> DistanceFog {
        HexLightSettings::default().fog_for(20.0)
    }

    /// The ambient light a terrain camera starts with ([`HexLightSettings::ambient_brightness`]'s
    /// default).
    #[must_use]
    pub fn ambient() -> AmbientLight {
        AmbientLight { brightness: HexLightSettings::default().ambient_brightness, ..default() }
    }
}

/// The sun entity the plugin spawns (while [`HexLightSettings::sun`] is on).
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
pub struct HexSun;

/// How the terrain is lit. Changes apply the next frame.
#[derive(Resource, Debug, Clone, PartialEq, Reflect)]
#[reflect(Resource, Default)]
pub struct HexLightSettings {
    /// Spawn and keep a directional sun ([`HexSun`]) once a [`HexTerrainCamera`] exists. Off,
    /// light the scene yourself.
    pub sun: bool,
    /// Sun height above the horizon, degrees (clamped to `[5, 90]`).
    pub sun_elevation: f32,
    /// Sun bearing, degrees clockwise from north (`-z`).
    pub sun_azimuth: f32,
    /// Sun illuminance, lux.
    pub sun_illuminance: f32,
    /// Sun color.
    pub sun_color: Color,
    /// The sun casts shadows.
    pub shadows: bool,
    /// Shadow cascades, `1..=4` (each one more shadow pass a frame).
    pub shadow_cascades: usize,
    /// Width and height of each cascade's shadow map, a power of two in `256..=8192` (Bevy's
    /// `DirectionalLightShadowMap`, set while the sun is on).
    pub shadow_map_size: usize,
    /// Ambient light brightness on terrain cameras.
    pub ambient_brightness: f32,
    /// Distance fog on terrain cameras, fitted to their height: far terrain fades into
    /// `fog_color`. Off, the plugin removes their [`DistanceFog`] and leaves fog to you.
    pub fog: bool,
    /// Fog color, the sky's at the horizon.
    pub fog_color: Color,
    /// Where the fog starts and where it is whole, in multiples of the camera's height above
    /// the ground.
    pub fog_range: Vec2,
}

impl Default for HexLightSettings {
    fn default() -> Self {
        Self {
            sun: true,
            sun_elevation: 38.0,
            sun_azimuth: 225.0,
            sun_illuminance: 9_000.0,
            sun_color: Color::srgb(1.0, 0.96, 0.88),
            shadows: true,
            shadow_cascades: 2,
            shadow_map_size: 1024,
            ambient_brightness: 350.0,
            fog: true,
            fog_color: Color::srgb(0.70, 0.78, 0.86),
            fog_range: Vec2::new(1.5, 4.5),
        }
    }
}

impl HexLightSettings {
    /// The direction the sunlight travels (from the sun down to the ground).
    #[must_use]
    pub fn sun_direction(&self) -> Vec3 {
        let elevation = finite(self.sun_elevation, 38.0).clamp(5.0, 90.0).to_radians();
        let azimuth = finite(self.sun_azimuth, 225.0).to_radians();
        let to_sun = Vec3::new(azimuth.sin() * elevation.cos(), elevation.sin(), -azimuth.cos() * elevation.cos());
        -to_sun
    }

    /// The distance fog for a camera `height` above the sea: it starts and is whole at
    /// [`fog_range`](Self::fog_range) times the height.
    #[must_use]
    pub fn fog_for(&self, height: f32) -> DistanceFog {
        let range = self.fog_range.max(Vec2::ZERO);
        DistanceFog {
            color: self.fog_color,
            directional_light_color: Color::srgba(1.0, 0.95, 0.85, 0.3),
            directional_light_exponent: 20.0,
            falloff: FogFalloff::Linear { start: height * range.x, end: height * range.y.max(range.x + 0.1) },
        }
    }

    /// Shadow cascades for a camera `height` above the ground: the first ends a little past
    /// the point under the middle of the screen, the last where the fog is whole.
    #[must_use]
    pub fn cascades(&self, height: f32) -> CascadeShadowConfig {
        let height = finite(height, 20.0).clamp(1.0, 1e5);
        let far = height * finite(self.fog_range.y, 6.5).clamp(1.0, 50.0);
        let count = self.shadow_cascades.clamp(1, 4);
        CascadeShadowConfigBuilder {
            num_cascades: count,
            minimum_distance: 0.1,
            first_cascade_far_bound: if count == 1 { far } else { (height * 1.6).min(far * 0.5) },
            maximum_distance: far,
            overlap_proportion: 0.2,
        }
        .build()
    }
}

fn finite(v: f32, or: f32) -> f32 {
    if v.is_finite() { v } else { or }
}

/// The sun, shadows, fog and occlusion of [`HexLightSettings`] for [`HexTerrainCamera`]s.
/// Part of [`HexTerrainPlugins`](crate::HexTerrainPlugins) with the `render` feature.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexLightPlugin;

impl Plugin for HexLightPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<HexLightSettings>()
            .register_type::<HexLightSettings>()
            .register_type::<HexTerrainCamera>()
            .register_type::<HexSun>()
            .add_systems(Update, (update_sun, update_cameras).in_set(HexTerrainSystems::Render));
    }
}

/// The height of the first terrain camera above the ground (its `y` above the map's sea level).
fn camera_height(cameras: &Query<&GlobalTransform, With<HexTerrainCamera>>, map: &crate::HexMap) -> Option<f32> {
    let sea = map.terrain().sea_level();
    cameras.iter().next().map(|t| (t.translation().y - sea).max(1.0))
}

fn update_sun(
    mut commands: Commands,
    lighting: Res<HexLightSettings>,
    // Bevy's light plugin's (absent from a headless app).
    shadow_map: Option<ResMut<DirectionalLightShadowMap>>,
    map: Res<crate::HexMap>,
    cameras: Query<&GlobalTransform, With<HexTerrainCamera>>,
    mut suns: Query<(Entity, &mut DirectionalLight, &mut Transform, &mut CascadeShadowConfig), With<HexSun>>,
    mut last_height: Local<f32>,
) {
    if !lighting.sun {
        for (e, ..) in &suns {
            commands.entity(e).despawn();
        }
        return;
    }
    // The sun lights what terrain cameras show: none yet, no sun (a floating-origin scene
    // places its own lights in its grid).
    let Some(height) = camera_height(&cameras, &map) else { return };
    let size = lighting.shadow_map_size.clamp(256, 8192).next_power_of_two().min(8192);
    if let Some(mut shadow_map) = shadow_map.filter(|m| lighting.is_changed() && m.size != size) {
        shadow_map.size = size;
    }
    // Refit the cascades when the camera's height changed by a tenth (zoom), not every frame.
    let refit = (height / last_height.max(1e-3) - 1.0).abs() > 0.1;
    let light = DirectionalLight {
        illuminance: lighting.sun_illuminance.max(0.0),
        color: lighting.sun_color,
        shadow_maps_enabled: lighting.shadows,
        ..default()
    };
    let transform = Transform::default().looking_to(lighting.sun_direction(), Vec3::Y);
    match suns.single_mut() {
        Ok((_, mut sun, mut t, mut cascades)) => {
            if lighting.is_changed() {
                *sun = light;
                *t = transform;
            }
            if refit || lighting.is_changed() {
                *cascades = lighting.cascades(height);
                *last_height = height;
            }
        }
        Err(_) => {
            commands.spawn((Name::new("hex sun"), HexSun, light, transform, lighting.cascades(height)));
            *last_height = height;
        }
    }
}

/// Terrain cameras with the components the plugin fits.
type TerrainCameras<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        Ref<'static, HexTerrainCamera>,
        &'static GlobalTransform,
        Option<&'static DistanceFog>,
        Option<&'static AmbientLight>,
    ),
>;

/// Whether two fogs are the same but for a twentieth of their falloff distances (a camera
/// moving a little does not rewrite its fog every frame).
fn same_fog(a: &DistanceFog, b: &DistanceFog) -> bool {
    let close = |x: f32, y: f32| (x - y).abs() < 0.05 * y.abs().max(1.0);
    a.color == b.color
        && match (&a.falloff, &b.falloff) {
            (FogFalloff::Linear { start: s0, end: e0 }, FogFalloff::Linear { start: s1, end: e1 }) => {
                close(*s0, *s1) && close(*e0, *e1)
            }
            _ => false,
        }
}

/// Fits each terrain camera's fog to its height (or removes it while the fog is off) and sets
/// its ambient brightness when the camera is new or the lighting changes.
fn update_cameras(
    mut commands: Commands,
    lighting: Res<HexLightSettings>,
    map: Res<crate::HexMap>,
    cameras: TerrainCameras,
) {
    let sea = map.terrain().sea_level();
    for (e, camera, transform, fog, ambient) in &cameras {
        let height = (transform.translation().y - sea).max(1.0);
        if lighting.fog {
            let wanted = lighting.fog_for(height);
            if !fog.is_some_and(|f| same_fog(f, &wanted)) {
                commands.entity(e).insert(wanted);
            }
        } else if fog.is_some() {
            commands.entity(e).remove::<DistanceFog>();
        }
        // A new camera, or new lighting: a brightness set on the camera in between is kept.
        let fresh = camera.is_added() || lighting.is_changed();
        if fresh && ambient.is_none_or(|a| a.brightness != lighting.ambient_brightness) {
            commands.entity(e).insert(AmbientLight { brightness: lighting.ambient_brightness, ..default() });
        }
    }
}
