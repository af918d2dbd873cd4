//! `hexterrain gallery`: one contact sheet of a map config over many seeds, each map rendered
//! top-down as `render` draws it (a globe equirectangular) and labelled with its seed and the figures a player judges a
//! map type by, to judge a type by eye.

use std::path::Path;

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use hex_terrain::{Biome, GlobeStats, GlobeTerrain, MapConfig, MapSize, MapStats, Terrain, WaterLevel};
use image::{Rgb, RgbImage};

use crate::CliResult;
use crate::render;

/// Most maps on one sheet.
pub const MAX_MAPS: u32 = 64;

/// The labels' typeface (Fira Mono, SIL Open Font License 1.1: `fonts/FiraMono-LICENSE`).
const FONT: &[u8] = include_bytes!("../fonts/FiraMono-Medium.ttf");

/// The sheet's background and the labels' colors.
const BACKGROUND: Rgb<u8> = Rgb([24, 24, 28]);
const TEXT: [u8; 3] = [235, 235, 235];
const DIM: [u8; 3] = [170, 170, 180];

/// What `gallery` draws.
pub struct Options {
    /// How many seeds (the config's, then the next ones).
    pub seeds: u32,
    /// Maps in a row.
    pub columns: u32,
    /// Each map's width in pixels.
    pub width: u32,
    /// The map's size instead of the config's.
    pub size: Option<(u32, u32)>,
    /// A map type's water level instead of the config's.
    pub water: Option<WaterLevel>,
}

/// Renders `config` over `options.seeds` seeds into one sheet at `output`.
pub fn run(mut config: MapConfig, options: &Options, output: &Path) -> CliResult<()> {
    if !(1..=MAX_MAPS).contains(&options.seeds) {
        return Err(format!("--seeds {}: 1..={MAX_MAPS} are allowed", options.seeds));
    }
    if !(1..=options.seeds).contains(&options.columns) {
        return Err(format!("--columns {}: 1..={} (the seeds) are allowed", options.columns, options.seeds));
    }
    if !(64..=2048).contains(&options.width) {
        return Err(format!("--width {}: 64..=2048 are allowed", options.width));
    }
    if let Some((x, z)) = options.size {
        config.size = MapSize::Bounded { x, z };
    }
    if let Some(water) = options.water {
        let Some(map_type) = config.map_type.as_mut() else {
            return Err("--water needs a map with a map type (its `map_type`)".into());
        };
        map_type.water = water;
    }
    let frequency = config.size.globe();
    let shape = match (frequency, config.size.bounds()) {
        (Some(f), _) => format!("globe f = {f}"),
        (None, Some((x, z))) => format!("{x}x{z}"),
        (None, None) => return Err("a gallery needs a bounded map or a globe; give --size COLUMNSxROWS".into()),
    };
    let font = FontRef::try_from_slice(FONT).map_err(|e| format!("the labels' font: {e}"))?;
    let scale = PxScale::from((options.width as f32 / 30.0).clamp(10.0, 20.0));
    let line = font.as_scaled(scale).height().ceil() as u32 + 2;
    let mut tiles = Vec::with_capacity(options.seeds as usize);
    for k in 0..options.seeds {
        let seed = config.seed.wrapping_add(k);
        let config = MapConfig { seed, ..config.clone() };
        let failed = |e: hex_terrain::ConfigError| format!("seed {seed}: {e}");
        if frequency.is_some() {
            // A globe: its equirectangular map, labelled with its landmasses on the sphere.
            let globe = GlobeTerrain::new(config).map_err(failed)?;
            let picture = crate::globe::render(&globe, crate::globe::View::Equirectangular, options.width, false);
            let met = globe.map_type_report().map(hex_terrain::MapTypeReport::met);
            tiles.push((seed, picture, globe_labels(&GlobeStats::measure(&globe), met)));
            continue;
        }
        let terrain = Terrain::new(config).map_err(failed)?;
        let mesh = crate::whole_map(&terrain)?;
        let picture = render::render(
            &terrain,
            &mesh,
            &render::Options { width: options.width, outlines: false, marks: Vec::new() },
        )?;
        let stats = MapStats::measure(&terrain).ok_or("a bounded map")?;
        let met = terrain.map_type().map(hex_terrain::MapTypeReport::met);
        let (x, z) = terrain.config().size.bounds().ok_or("a bounded map")?;
        tiles.push((seed, picture, labels(&stats, met, (x, z))));
    }
    let (cell_w, map_h) = (options.width, tiles[0].1.height());
    let cell_h = map_h + 3 * line + 8;
    let rows = options.seeds.div_ceil(options.columns);
    let gap = 6;
    let mut sheet = RgbImage::from_pixel(
        options.columns * (cell_w + gap) + gap,
        rows * (cell_h + gap) + gap + line + 4,
        BACKGROUND,
    );
    let title = format!(
        "{} ({shape}{}): {} seeds from {}",
        config.name,
        if config.wrap { ", wrapping" } else { "" },
        options.seeds,
        config.seed
    );
    let width = sheet.width();
    draw_text(&mut sheet, &font, scale, (gap, 2, width), &title, TEXT);
    for (k, (seed, picture, lines)) in tiles.iter().enumerate() {
        let (col, row) = (k as u32 % options.columns, k as u32 / options.columns);
        let (left, top) = (gap + col * (cell_w + gap), line + 4 + gap + row * (cell_h + gap));
        image::imageops::overlay(&mut sheet, picture, i64::from(left), i64::from(top));
        let below = top + map_h + 4;
        let right = left + cell_w;
        draw_text(&mut sheet, &font, scale, (left, below, right), &format!("seed {seed}  {}", lines[0]), TEXT);
        draw_text(&mut sheet, &font, scale, (left, below + line, right), &lines[1], DIM);
        draw_text(&mut sheet, &font, scale, (left, below + 2 * line, right), &lines[2], DIM);
    }
    render::save(&sheet, output)?;
    println!("{}: {} maps of {}", output.display(), options.seeds, config.name);
    Ok(())
}

/// A map's three label lines: its landmasses (and whether its type met its targets), its
/// mountains and poles, its water.
fn labels(stats: &MapStats, met: Option<bool>, (columns, rows): (u32, u32)) -> [String; 3] {
    let largest = stats.landmasses.first();
    let verdict = verdict(met);
    [
        format!("{} cont. {} isl.{verdict}", stats.continents().count(), stats.islands().count()),
        format!(
            "largest {} {}x{}/{columns}x{rows} ridge {} cold {} desert {}",
            percent(stats.largest_landmass_share()),
            largest.map_or(0, |l| l.columns),
            largest.map_or(0, |l| l.rows),
            stats.straight_ridge,
            percent(stats.cold_share()),
            percent(stats.biome_share(Biome::Desert)),
        ),
        format!(
            "rivers on {} of the land, {} long on median; {} lakes",
            percent(stats.river_share()),
            stats.rivers.median,
            stats.lakes
        ),
    ]
}

/// A share as a whole percentage.
fn percent(share: f64) -> String {
    format!("{:.0}%", share * 100.0)
}

/// What a label says of the map type's targets: met, missed, or nothing without a map type.
fn verdict(met: Option<bool>) -> &'static str {
    match met {
        Some(true) => "  targets met",
        Some(false) => "  TARGETS MISSED",
        None => "",
    }
}

/// A globe's three label lines: its landmasses (and whether its type met its targets), its
/// mountains and poles, its water.
fn globe_labels(stats: &GlobeStats, met: Option<bool>) -> [String; 3] {
    let verdict = verdict(met);
    [
        format!("{} cont. {} isl.{verdict}", stats.continents().count(), stats.islands().count()),
        format!(
            "largest {} mountains {} ({:.1} mountain nb.) cold {}",
            percent(stats.largest_landmass_share()),
            percent(stats.mountain_share()),
            stats.mountain_neighbors(),
            percent(stats.cold_share()),
        ),
        format!(
            "sea {} polar land {} strait {}",
            percent(stats.water_share()),
            percent(stats.polar_land_share()),
            stats.narrowest_strait.map_or("-".to_owned(), |s| s.to_string())
        ),
    ]
}

/// Draws `text` with its top left at `(x, y)`, blending each glyph's coverage over the sheet,
/// cut at column `right`.
fn draw_text(
    sheet: &mut RgbImage,
    font: &FontRef<'_>,
    scale: PxScale,
    (x, y, right): (u32, u32, u32),
    text: &str,
    color: [u8; 3],
) {
    let scaled = font.as_scaled(scale);
    let mut caret = x as f32;
    let baseline = y as f32 + scaled.ascent();
    for c in text.chars() {
        let mut glyph = scaled.scaled_glyph(c);
        glyph.position = ab_glyph::point(caret, baseline);
        caret += scaled.h_advance(glyph.id);
        let Some(outline) = font.outline_glyph(glyph) else { continue };
        let bounds = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            let (px, py) = (bounds.min.x as i64 + i64::from(gx), bounds.min.y as i64 + i64::from(gy));
            if px < 0 || py < 0 || px >= i64::from(right.min(sheet.width())) || py >= i64::from(sheet.height()) {
                return;
            }
            let pixel = sheet.get_pixel_mut(px as u32, py as u32);
            for (channel, &c) in pixel.0.iter_mut().zip(&color) {
                *channel = (f32::from(*channel) * (1.0 - coverage) + f32::from(c) * coverage).round() as u8;
            }
        });
    }
}
