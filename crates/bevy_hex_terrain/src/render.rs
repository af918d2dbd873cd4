//! Rendering hook: every chunk mesh gets a PBR material showing the height-blended vertex
//! colours. Inert in an app without `PbrPlugin`.

use bevy::prelude::*;

use crate::streaming::HexChunk;

/// The material every chunk uses.
#[derive(Resource, Debug, Clone)]
pub struct HexTerrainMaterial(pub Handle<StandardMaterial>);

/// Gives chunk meshes their material.
pub struct HexTerrainRenderPlugin;

impl Plugin for HexTerrainRenderPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(Startup, create_material).add_systems(
            Update,
            attach_material.in_set(crate::HexTerrainSystems::Render).run_if(resource_exists::<HexTerrainMaterial>),
        );
    }
}

fn create_material(mut commands: Commands, materials: Option<ResMut<Assets<StandardMaterial>>>) {
    let Some(mut materials) = materials else { return };
    let handle = materials.add(StandardMaterial {
        base_color: Color::WHITE,
        perceptual_roughness: 0.92,
        reflectance: 0.2,
        ..default()
    });
    commands.insert_resource(HexTerrainMaterial(handle));
}

/// Chunks with a mesh and no material yet.
type Unpainted = (With<HexChunk>, With<Mesh3d>, Without<MeshMaterial3d<StandardMaterial>>);

fn attach_material(mut commands: Commands, material: Res<HexTerrainMaterial>, chunks: Query<Entity, Unpainted>) {
    for e in &chunks {
        commands.entity(e).insert(MeshMaterial3d(material.0.clone()));
    }
}
