//! Picking benchmark: the cost of one pointer's pick a frame, ours (the core's exact ray cast on
//! the surface, what `HexPickingPlugin` runs per pointer) beside Bevy's own `MeshPickingPlugin`
//! ray cast (a bounding-box test per chunk mesh, then every triangle of the meshes the ray
//! enters) on the same chunk meshes, in one process, with the ratio. Rays come from a strategy
//! camera 40 units above the map, 55 degrees down, aimed at points all over the map; both
//! answers are compared (the same surface point within 1e-3 units).
//!
//! ```text
//! cargo bench --workspace --profile dev --bench picking [-- --rays 2000]
//! ```

use std::hint::black_box;
use std::time::Instant;

use bevy::math::{Affine3A, Dir3, Ray3d, Vec3, bounding::Aabb3d};
use bevy::picking::mesh_picking::ray_cast::{Backfaces, ray_aabb_intersection_3d, ray_mesh_intersection};
use hex_terrain::{ChunkMesh, MapConfig, MapSize, Terrain};

/// A chunk as Bevy's mesh ray cast sees it: its transform, box and buffers.
struct Chunk {
    transform: Affine3A,
    aabb: Aabb3d,
    mesh: ChunkMesh,
}

fn chunks(terrain: &Terrain, coords: &[hex_terrain::ChunkCoord]) -> Vec<Chunk> {
    coords
        .iter()
        .filter_map(|&c| terrain.generate_chunk(c))
        .map(|mesh| {
            let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
            for p in &mesh.buffers.positions {
                lo = lo.min(Vec3::from_array(*p));
                hi = hi.max(Vec3::from_array(*p));
            }
            let o = mesh.origin;
            let transform = Affine3A::from_translation(Vec3::new(o[0] as f32, o[1] as f32, o[2] as f32));
            Chunk { transform, aabb: Aabb3d { min: lo.into(), max: hi.into() }, mesh }
        })
        .collect()
}

/// Bevy's mesh picking on the chunks: the nearest hit's distance.
fn mesh_pick(chunks: &[Chunk], ray: Ray3d) -> Option<f32> {
    let mut best: Option<f32> = None;
    for c in chunks {
        let Some(d) = ray_aabb_intersection_3d(ray, &c.aabb, &c.transform) else { continue };
        if best.is_some_and(|b| d > b) {
            continue;
        }
        let b = &c.mesh.buffers;
        let hit = ray_mesh_intersection(
            ray,
            &c.transform,
            &b.positions,
            Some(&b.normals),
            Some(&b.indices),
            None,
            Backfaces::Cull,
        );
        if let Some(hit) = hit {
            best = Some(best.map_or(hit.distance, |b| b.min(hit.distance)));
        }
    }
    best
}

/// Rays of a strategy camera over points spread across `[x0, x1] x [z0, z1]`.
fn rays(n: usize, [x0, x1, z0, z1]: [f32; 4]) -> Vec<Ray3d> {
    let mut s = 0x9e37_79b9_u32;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        s as f32 / u32::MAX as f32
    };
    let dir = Dir3::new(Vec3::new(0.0, -55f32.to_radians().sin(), 55f32.to_radians().cos())).unwrap();
    (0..n)
        .map(|_| {
            let target = Vec3::new(x0 + (x1 - x0) * next(), 2.0, z0 + (z1 - z0) * next());
            Ray3d::new(target - *dir * (40.0 / 55f32.to_radians().sin()), dir)
        })
        .collect()
}

fn run(name: &str, terrain: &Terrain, coords: &[hex_terrain::ChunkCoord], area: [f32; 4], n: usize) {
    let chunks = chunks(terrain, coords);
    let rays = rays(n, area);
    let ours = |ray: &Ray3d| {
        let o = ray.origin.as_dvec3().to_array();
        terrain.raycast(o, ray.direction.as_dvec3().to_array(), 1e5).map(|h| h.distance as f32)
    };
    // Agreement first (and warm caches).
    let (mut both, mut agree) = (0, 0);
    for ray in &rays {
        if let (Some(a), Some(b)) = (ours(ray), mesh_pick(&chunks, *ray)) {
            both += 1;
            agree += usize::from((a - b).abs() < 1e-3);
        }
    }
    let time = |f: &dyn Fn(&Ray3d) -> Option<f32>| {
        let mut best = f64::MAX;
        for _ in 0..5 {
            let start = Instant::now();
            for ray in &rays {
                black_box(f(black_box(ray)));
            }
            best = best.min(start.elapsed().as_secs_f64() / rays.len() as f64);
        }
        best * 1e6
    };
    let (t_ours, t_mesh) = (time(&ours), time(&|r: &Ray3d| mesh_pick(&chunks, *r)));
    let triangles: usize = chunks.iter().map(|c| c.mesh.buffers.indices.len() / 3).sum();
    println!(
        "| {name} | {} chunks, {triangles} triangles | {t_ours:.1} µs | {t_mesh:.1} µs | {:.2} | {agree} of {both} |",
        chunks.len(),
        t_mesh / t_ours
    );
}

/// The whole backend in a headless app (`HexPickingStats`): the streaming example's 7x7 chunks of
/// the default unbounded map with their props (unit boxes: a headless app has no prop meshes)
/// and water, one ray a frame from the strategy camera; µs a pick, and the props on the map.
fn backend(n: usize) -> (f64, usize) {
    use bevy::asset::AssetPlugin;
    use bevy::picking::backend::ray::{RayId, RayMap};
    use bevy::picking::pointer::PointerId;
    use bevy::picking::{InteractionPlugin, PickingPlugin, PickingSystems};
    use bevy::prelude::*;
    use bevy_hex_terrain::prelude::*;
    use bevy_hex_terrain::{HexPickingStats, HexTerrainMaterialPlugin};

    #[derive(Resource)]
    struct Rays(Vec<Ray3d>, usize);
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), TransformPlugin, PickingPlugin, InteractionPlugin));
    let settings = HexStreamingSettings { load_radius: 3, max_inserts_per_frame: 64, ..default() };
    let map = MapConfig { size: MapSize::Unbounded, ..MapConfig::default() };
    app.insert_resource(settings);
    app.add_plugins(HexTerrainPlugins::new(map).build().disable::<HexTerrainMaterialPlugin>());
    app.insert_resource(Rays(rays(n, [-30.0, 30.0, -30.0, 30.0]), 0));
    app.add_systems(
        PreUpdate,
        (|mut rays: ResMut<Rays>, cameras: Query<Entity, With<Camera>>, mut map: ResMut<RayMap>| {
            let Some(camera) = cameras.iter().next() else { return };
            if rays.1 < rays.0.len() {
                map.map.insert(RayId::new(camera, PointerId::Mouse), rays.0[rays.1]);
                rays.1 += 1;
            }
        })
        .after(PickingSystems::ProcessInput)
        .before(PickingSystems::Backend),
    );
    app.world_mut().spawn((Camera::default(), HexTerrainAgent::default(), Transform::default()));
    app.world_mut().spawn(PointerId::Mouse);
    // Until the chunks are in (the rays wait).
    for _ in 0..2000 {
        let streamer = app.world().resource::<ChunkStreamer>();
        if streamer.wanted().next().is_some() && streamer.wanted().all(|(c, _)| streamer.is_chunk_loaded(c)) {
            break;
        }
        app.world_mut().resource_mut::<Rays>().1 = 0;
        app.update();
    }
    app.update();
    app.world_mut().resource_mut::<Rays>().1 = 0;
    *app.world_mut().resource_mut::<HexPickingStats>() = HexPickingStats::default();
    for _ in 0..n {
        app.update();
    }
    let stats = app.world().resource::<HexPickingStats>().clone();
    let props = app.world_mut().query::<&HexProp>().iter(app.world()).count();
    (stats.time.as_secs_f64() / stats.picks.max(1) as f64 * 1e6, props)
}

fn main() {
    let n = std::env::args().skip_while(|a| a != "--rays").nth(1).and_then(|s| s.parse().ok()).unwrap_or(2000);
    println!("one pick a pointer a frame, best of 5 runs over {n} rays (median-free: the machine is shared)");
    println!(
        "| map | loaded | ours (HexPickingPlugin) | Bevy's mesh ray cast | Bevy's time / ours | same hit (1e-3) |"
    );
    println!("|---|---|---|---|---|---|");
    let huge = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/civ6/huge.map.ron"))
        .expect("the Civ6 Huge map file");
    let huge = Terrain::new(MapConfig::from_ron(&huge).expect("a valid map")).expect("a valid config");
    let b = huge.bounds().unwrap();
    let far = huge.tile_center(huge.tile_from_offset([b.max[0] - 1, b.max[1] - 1])).unwrap();
    run("Civ6 Huge, whole", &huge, &huge.chunks(), [0.0, far[0] as f32, 0.0, far[2] as f32], n);
    // The streaming demo's window: 7x7 chunks of the default unbounded map around the origin.
    let world = Terrain::new(MapConfig { size: MapSize::Unbounded, ..MapConfig::default() }).unwrap();
    let coords: Vec<_> = (-3..=3).flat_map(|z| (-3..=3).map(move |x| hex_terrain::ChunkCoord::new(x, z))).collect();
    run("unbounded, 7x7 chunks streamed", &world, &coords, [-30.0, 30.0, -30.0, 30.0], n);
    let (us, props) = backend(n);
    println!();
    println!(
        "the whole backend in a headless app, 7x7 chunks streamed with {props} props and the water surface: {us:.1} µs a pick"
    );
}
