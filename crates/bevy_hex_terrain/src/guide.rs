//! The guide: a chapter a feature, from a map on screen to the thesis behind it. Every Rust
//! snippet in it is compiled (and most run) as a doc test, so what it shows is what the crate
//! does. The chapters are also readable on GitHub, in `crates/bevy_hex_terrain/guide/`.
//!
//! Start with [getting started](crate::guide::getting_started), then [the recipes](crate::guide::recipes): five things every
//! strategy game writes, each a tested plugin.
//!
//! - [Getting started](crate::guide::getting_started)
//! - [Terrain, map files and queries](crate::guide::terrain)
//! - [Streaming](crate::guide::streaming)
//! - [Material and look](crate::guide::look)
//! - [Tile states: fog of war, territory, lenses, highlights, save games](crate::guide::tile_states)
//! - [Picking](crate::guide::picking)
//! - [Minimap](crate::guide::minimap)
//! - [Editing the map](crate::guide::editor)
//! - [Game setup: starts, resources, wonders and a fairness report](crate::guide::setup)
//! - [Round worlds and far worlds](crate::guide::far_worlds)
//! - [Level of detail at strategic zoom](crate::guide::level_of_detail)
//! - [The core without Bevy](crate::guide::core)
//! - [Performance](crate::guide::performance)
//! - [Reliability: hostile input and hours of play](crate::guide::reliability)
//! - [How it works, and where it departs from the thesis](crate::guide::how_it_works)
//! - [Recipes](crate::guide::recipes)
//! - [Rules: movement, paths and sight](crate::guide::rules)
//! - [Your own terrain: rulesets](crate::guide::own_terrain)
//! - [A hex globe](crate::guide::globe)

#![allow(clippy::doc_markdown, reason = "the chapters are prose for people, read on GitHub too")]

pub mod getting_started {
    #![doc = include_str!("../guide/01-getting-started.md")]
}

pub mod terrain {
    #![doc = include_str!("../guide/02-terrain.md")]
}

pub mod streaming {
    #![doc = include_str!("../guide/03-streaming.md")]
}

pub mod look {
    #![doc = include_str!("../guide/04-look.md")]
}

pub mod tile_states {
    #![doc = include_str!("../guide/05-tile-states.md")]
}

pub mod picking {
    #![doc = include_str!("../guide/06-picking.md")]
}

pub mod minimap {
    #![doc = include_str!("../guide/07-minimap.md")]
}

pub mod editor {
    #![doc = include_str!("../guide/08-editor.md")]
}

pub mod setup {
    #![doc = include_str!("../guide/09-setup.md")]
}

pub mod far_worlds {
    #![doc = include_str!("../guide/10-far-worlds.md")]
}

pub mod level_of_detail {
    #![doc = include_str!("../guide/11-level-of-detail.md")]
}

pub mod core {
    #![doc = include_str!("../guide/12-core.md")]
}

pub mod performance {
    #![doc = include_str!("../guide/13-performance.md")]
}

pub mod reliability {
    #![doc = include_str!("../guide/14-reliability.md")]
}

pub mod how_it_works {
    #![doc = include_str!("../guide/15-how-it-works.md")]
}

pub mod recipes {
    #![doc = include_str!("../guide/16-recipes.md")]
}

pub mod rules {
    #![doc = include_str!("../guide/17-rules.md")]
}

pub mod own_terrain {
    #![doc = include_str!("../guide/18-own-terrain.md")]
}

pub mod globe {
    #![doc = include_str!("../guide/19-globe.md")]
}

/// The repository's README, whose snippets are doc tests too.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct Readme;
