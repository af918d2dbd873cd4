//! `hexterrain`: previews, heightmap tiling, export, statistics and the thesis' experiments for
//! `hex_terrain` maps, without writing code or opening a window.

mod edit;
mod experiments;
mod export;
mod gallery;
mod globe;
mod globe_stats;
mod render;
mod setup;
mod stats;
mod survey;
mod terrains;
mod textures;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use hex_terrain::{ChunkMesh, HeightSourceConfig, ManipulationConfig, MapConfig, MapSize, Terrain, WaterLevel};

/// Generate, preview, export and measure 3D hexagonal tiled terrain.
#[derive(Parser)]
#[command(name = "hexterrain", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a top-down picture of a map as a player would see it (PNG).
    Render {
        /// Map config (RON), e.g. assets/maps/thesis/map00.map.ron.
        map: PathBuf,
        /// Output PNG.
        #[arg(short, long)]
        output: PathBuf,
        /// Render the raw noise map (every manipulation off), for before/after pairs.
        #[arg(long)]
        raw: bool,
        /// Draw tile outlines (thesis figure 47).
        #[arg(long)]
        outlines: bool,
        /// Image width in pixels; the height follows the map's aspect ratio.
        #[arg(long, default_value_t = 1024)]
        width: u32,
        /// Override the config's blend value of Algorithm 5, in [0, 1].
        #[arg(long)]
        blend: Option<f32>,
        /// Draw the map under a terrain ruleset (`*.terrain.ron`): its terrains' and features'
        /// colors, in place of the config's own ruleset.
        #[arg(long)]
        ruleset: Option<PathBuf>,
        /// A globe seen from above `LON,LAT` (degrees) in an orthographic view, instead of its
        /// equirectangular map (globe configs only).
        #[arg(long, value_name = "LON,LAT", allow_hyphen_values = true)]
        from: Option<String>,
    },
    /// Tile an existing greyscale heightmap (8 or 16 bit PNG) onto the hex lattice, with the same
    /// classification and manipulation as noise maps (the thesis' filter use).
    TileImage {
        /// The heightmap PNG.
        heightmap: PathBuf,
        /// Image value in [0, 1] of sea level: darker pixels become sea.
        #[arg(long)]
        sea_level: f32,
        /// Output: a map config (.ron) using the image as its height source, or a rendered
        /// preview (.png).
        #[arg(short, long)]
        output: PathBuf,
        /// Map size in hexes, `XxZ` (e.g. `60x40`); defaults to one hex per 8 by 8 pixels.
        #[arg(long, value_parser = parse_size)]
        size: Option<(u32, u32)>,
        /// Mountain threshold in [0, 1] (normalised height, after the sea level remap).
        #[arg(long)]
        mountain_threshold: Option<f32>,
        /// Maximum elevation in world units.
        #[arg(long)]
        max_elevation: Option<f32>,
        /// Width of the preview when the output is a PNG.
        #[arg(long, default_value_t = 1024)]
        width: u32,
        /// Draw tile outlines in the preview.
        #[arg(long)]
        outlines: bool,
    },
    /// Export the map's mesh as glTF binary (.glb, with normals, UVs and a `_TILE` attribute:
    /// tile kind and distance to the tile center) or Wavefront OBJ (.obj).
    Export {
        /// Map config (RON).
        map: PathBuf,
        /// Output file: .glb or .obj.
        #[arg(short, long)]
        output: PathBuf,
        /// Export the raw map (every manipulation off).
        #[arg(long)]
        raw: bool,
    },
    /// Print tile counts per type, mesh size, sharpness raw vs manipulated, generation time.
    Stats {
        /// Map config (RON).
        map: PathBuf,
        /// Count the tiles by this terrain ruleset's terrains and features (`*.terrain.ron`,
        /// e.g. assets/rulesets/civ5.terrain.ron).
        #[arg(long)]
        ruleset: Option<PathBuf>,
    },
    /// Apply the world builder's strokes to a map and write the edited map file (the seed's
    /// config plus its `edits`); prints each stroke's changed tiles and chunks.
    Edit {
        /// Map config (RON).
        map: PathBuf,
        /// The strokes: a RON list of `(tool: .., brush: .., at: (column, row))` (on a globe
        /// `at: (id, 0)`), e.g.
        /// `[(tool: SetKind(Mountain), brush: Range(1), at: (20, 12)), (tool: AddRiver, brush: Range(0), at: (21, 12))]`.
        #[arg(long)]
        strokes: PathBuf,
        /// The edited map file to write (.map.ron).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Place a game on the map (start positions, resources, natural wonders) and print the
    /// fairness report; with --output, render the map with them marked.
    Setup {
        /// Map config (RON); its `setup` section, or the default setup when it has none.
        map: PathBuf,
        /// Number of players (overrides the map's setup).
        #[arg(long)]
        players: Option<u32>,
        /// Render the map with starts (white), resources (bonus green, strategic red, luxury
        /// violet) and wonders (gold) marked (PNG).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Image width in pixels.
        #[arg(long, default_value_t = 1024)]
        width: u32,
    },
    /// Generate a map config over many seeds and print each statistic's minimum, median and
    /// maximum (water, landmasses, coast, mountains, rivers, lakes, straits) and the time taken;
    /// for a map type, how many maps met every target, each target's spread and the tries.
    Survey {
        /// Map config (RON), or a map type's name for its preset (pangaea, continents,
        /// small-continents, archipelago, fractal, inland-sea); its seed is the first surveyed.
        map: PathBuf,
        /// How many seeds (the config's, then the next ones).
        #[arg(long, default_value_t = 50)]
        seeds: u32,
        /// The map's size instead of the config's, as `COLUMNSxROWS` (e.g. `84x54`).
        #[arg(long, value_parser = parse_size)]
        size: Option<(u32, u32)>,
        /// The water level of a map type instead of the config's: low, normal or high.
        #[arg(long, value_parser = parse_water)]
        water: Option<WaterLevel>,
    },
    /// Render a map config over many seeds into one contact sheet (PNG): each map top-down,
    /// labelled with its seed and the figures a map type is judged by, to judge a type by eye.
    Gallery {
        /// Map config (RON), or a map type's name for its preset (as `survey`).
        map: PathBuf,
        /// How many seeds (the first, then the next ones).
        #[arg(long, default_value_t = 12)]
        seeds: u32,
        /// The first seed (default: the config's).
        #[arg(long)]
        first: Option<u32>,
        /// Maps in a row.
        #[arg(long, default_value_t = 4)]
        columns: u32,
        /// Each map's width in pixels.
        #[arg(long, default_value_t = 480)]
        width: u32,
        /// The map's size instead of the config's, as `COLUMNSxROWS` (e.g. `84x54`).
        #[arg(long, value_parser = parse_size)]
        size: Option<(u32, u32)>,
        /// The water level of a map type instead of the config's: low, normal or high.
        #[arg(long, value_parser = parse_water)]
        water: Option<WaterLevel>,
        /// Output PNG (default: `gallery_NAME.png`, after the map's name).
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Write the tileable textures of the material's texture array (sea, grass, mountain, sand, snow, forest, ash).
    Textures {
        /// Output folder.
        #[arg(long, default_value = "assets/textures")]
        out: PathBuf,
        /// Side in pixels, a power of two.
        #[arg(long, default_value_t = 256)]
        size: u32,
    },
    /// Rerun the thesis' chapter 7 (Map0-Map15, table 7/8/9 sizes) and write markdown tables
    /// with the thesis' numbers beside ours, plus before/after PNGs.
    Experiments {
        /// Output folder.
        #[arg(long, default_value = "docs/experiments")]
        out: PathBuf,
        /// Folder holding map00.ron ... map15.ron.
        #[arg(long, default_value = "assets/maps/thesis")]
        maps: PathBuf,
        /// Inner rings for the timing tables (3 gives 48 vertices a hex, the thesis has ~32).
        #[arg(long, default_value_t = 3)]
        rings: u32,
        /// Timing runs per measurement (the median is reported).
        #[arg(long, default_value_t = 5)]
        runs: usize,
        /// Skip the maps above this many hexes in the timing tables.
        #[arg(long, default_value_t = 500_000)]
        max_hexes: u64,
        /// Width of the before/after PNGs.
        #[arg(long, default_value_t = 400)]
        width: u32,
    },
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (x, z) = s.split_once(['x', 'X']).ok_or_else(|| format!("expected XxZ, e.g. 60x40, got {s:?}"))?;
    let x: u32 = x.trim().parse().map_err(|e| format!("size x {x:?}: {e}"))?;
    let z: u32 = z.trim().parse().map_err(|e| format!("size z {z:?}: {e}"))?;
    if x == 0 || z == 0 {
        return Err(format!("size must be at least 1x1, got {x}x{z}"));
    }
    Ok((x, z))
}

fn parse_water(s: &str) -> Result<WaterLevel, String> {
    match s.to_ascii_lowercase().as_str() {
        "low" => Ok(WaterLevel::Low),
        "normal" => Ok(WaterLevel::Normal),
        "high" => Ok(WaterLevel::High),
        _ => Err(format!("expected low, normal or high, got {s:?}")),
    }
}

/// An error for the user: printed after `error:`, exit code 1.
pub(crate) type CliResult<T> = Result<T, String>;

pub(crate) fn load(path: &Path) -> CliResult<MapConfig> {
    MapConfig::load(path).map_err(|e| format!("{}: {e}", path.display()))
}

fn terrain(config: MapConfig, raw: bool) -> CliResult<Terrain> {
    // The raw map: every manipulation off and river channels not carved.
    let config = if raw {
        let rivers = hex_terrain::RiverConfig { carve: 0.0, ..config.rivers.clone() };
        MapConfig { manipulation: ManipulationConfig::raw(), rivers, ..config }
    } else {
        config
    };
    Terrain::new(config).map_err(|e| e.to_string())
}

pub(crate) fn whole_map(terrain: &Terrain) -> CliResult<ChunkMesh> {
    let (x, z) = terrain.config().size.bounds().ok_or_else(|| {
        "this command needs a bounded map; the config is Unbounded (set size: Bounded(x: .., z: ..))".to_string()
    })?;
    // Large maps take more than a second: show that something is happening.
    let spinner = (u64::from(x) * u64::from(z) * u64::from(terrain.lattice().subdivisions().pow(2)) > 400_000)
        .then(|| busy(format!("generating {x}x{z} hexes")));
    let mesh = terrain
        .bounds()
        .map(|rect| terrain.generate(rect, hex_terrain::GenerateOptions::DIAGNOSTICS))
        .ok_or("this command needs a bounded map")?;
    if let Some(s) = spinner {
        s.finish_and_clear();
    }
    Ok(mesh)
}

/// A spinner for work that may take more than a second (hidden when stderr is not a terminal).
pub(crate) fn busy(message: String) -> indicatif::ProgressBar {
    let s = indicatif::ProgressBar::new_spinner().with_message(message);
    s.enable_steady_tick(std::time::Duration::from_millis(100));
    s
}

fn check_width(width: u32) -> CliResult<()> {
    if (1..=16384).contains(&width) { Ok(()) } else { Err(format!("--width {width}: allowed 1..=16384")) }
}

fn run(cli: Cli) -> CliResult<()> {
    match cli.command {
        Command::Render { map, output, raw, outlines, width, blend, ruleset, from } => {
            check_width(width)?;
            let mut config = load(&map)?;
            if config.size.globe().is_some() {
                if ruleset.is_some() {
                    return Err("--ruleset: terrain rulesets are not on globes yet".into());
                }
                let view = match from {
                    None => globe::View::Equirectangular,
                    Some(text) => globe::View::from_lon_lat(&text)?,
                };
                if raw {
                    config.manipulation = ManipulationConfig::raw();
                }
                let globe = hex_terrain::GlobeTerrain::new(config).map_err(|e| format!("{}: {e}", map.display()))?;
                return render::save(&globe::render(&globe, view, width, outlines), &output);
            }
            if from.is_some() {
                return Err("--from: only for a globe config (size: Globe(frequency: ...))".into());
            }
            if let Some(path) = ruleset {
                config.ruleset = Some(path.display().to_string());
            }
            if let Some(b) = blend {
                config.appearance.blend = b;
            }
            let t = terrain(config, raw)?;
            let mesh = whole_map(&t)?;
            let spinner = (mesh.buffers.triangle_count() > 2_000_000).then(|| busy("rendering".into()));
            let img = render::render(&t, &mesh, &render::Options { width, outlines, marks: Vec::new() })?;
            if let Some(s) = spinner {
                s.finish_and_clear();
            }
            render::save(&img, &output)
        }
        Command::TileImage {
            heightmap,
            sea_level,
            output,
            size,
            mountain_threshold,
            max_elevation,
            width,
            outlines,
        } => {
            check_width(width)?;
            if !(0.0..=1.0).contains(&sea_level) {
                return Err(format!("--sea-level {sea_level}: allowed [0, 1]"));
            }
            let image =
                hex_terrain::HeightImage::load(&heightmap).map_err(|e| format!("{}: {e}", heightmap.display()))?;
            let (w, h) = image.size();
            let (x, z) = size.unwrap_or(((w as u32 / 8).max(1), (h as u32 / 8).max(1)));
            let path = std::fs::canonicalize(&heightmap).unwrap_or(heightmap.clone());
            let mut config = MapConfig {
                name: heightmap.file_stem().map_or("heightmap".into(), |s| s.to_string_lossy().into_owned()),
                source: HeightSourceConfig::Image { path: path.display().to_string(), sea_level },
                size: MapSize::Bounded { x, z },
                ..MapConfig::default()
            };
            if let Some(m) = mountain_threshold {
                config.terrain.mountain_threshold = m;
            }
            if let Some(e) = max_elevation {
                config.terrain.max_elevation = e;
            }
            let t = Terrain::with_sources(config.clone(), Some(std::sync::Arc::new(image)), None)
                .map_err(|e| e.to_string())?;
            match output.extension().and_then(|e| e.to_str()) {
                Some("ron") => {
                    std::fs::write(&output, format!("// Tiled from {}\n{}\n", heightmap.display(), config.to_ron()))
                        .map_err(|e| format!("{}: {e}", output.display()))
                }
                Some("png") => {
                    let mesh = whole_map(&t)?;
                    let img = render::render(&t, &mesh, &render::Options { width, outlines, marks: Vec::new() })?;
                    render::save(&img, &output)
                }
                _ => Err(format!("{}: the output must end in .ron or .png", output.display())),
            }
        }
        Command::Export { map, output, raw } => {
            let t = terrain(load(&map)?, raw)?;
            let mesh = whole_map(&t)?;
            let spinner =
                (mesh.buffers.vertex_count() > 2_000_000).then(|| busy(format!("writing {}", output.display())));
            let result = match output.extension().and_then(|e| e.to_str()) {
                Some("glb") => export::write_glb(&mesh, &output),
                Some("obj") => export::write_obj(&mesh, &output),
                _ => Err(format!("{}: the output must end in .glb or .obj", output.display())),
            };
            if let Some(s) = spinner {
                s.finish_and_clear();
            }
            result
        }
        Command::Stats { map, ruleset } => stats::stats(&map, ruleset.as_deref()),
        Command::Edit { map, strokes, output } => edit::run(&load(&map)?, &strokes, &output),
        Command::Setup { map, players, output, width } => {
            check_width(width)?;
            setup::setup(&map, players, output.as_deref(), width)
        }
        Command::Survey { map, seeds, size, water } => {
            let mut config = survey::map_or_type(&map)?;
            if config.size.globe().is_some() {
                if size.is_some() {
                    return Err("--size: a globe's size is its frequency (size: Globe(frequency: ...))".into());
                }
                if let (Some(water), Some(map_type)) = (water, config.map_type.as_mut()) {
                    map_type.water = water;
                }
                return globe_stats::survey(&map, config, seeds);
            }
            survey::run(&map, config, &survey::Options { seeds, size, water })
        }
        Command::Gallery { map, seeds, first, columns, width, size, water, output } => {
            let mut config = survey::map_or_type(&map)?;
            config.seed = first.unwrap_or(config.seed);
            let output = output.unwrap_or_else(|| {
                PathBuf::from(format!("gallery_{}.png", config.name.to_ascii_lowercase().replace(' ', "_")))
            });
            gallery::run(config, &gallery::Options { seeds, columns, width, size, water }, &output)
        }
        Command::Textures { out, size } => textures::write(&out, size),
        Command::Experiments { out, maps, rings, runs, max_hexes, width } => {
            check_width(width)?;
            experiments::run(&experiments::Options { out, maps, rings, runs: runs.max(1), max_hexes, width })
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
