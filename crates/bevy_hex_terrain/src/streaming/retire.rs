//! Retiring dropped chunks: a chunk leaving the world is hidden and forgotten at once (its task
//! cancelled, its mesh released, no system sees it as a chunk any more), and its children (the
//! props, hundreds on a wooded chunk, and the water surface) are despawned a few at a time, at
//! most [`HexStreamingSettings::max_despawns_per_frame`] a frame, the chunk with its last child.
//! Despawning an entity costs the main thread a few microseconds, so a chunk despawned whole
//! with its props was the slowest frame of a walk.

use std::collections::VecDeque;

use bevy::prelude::*;

use super::build::ChunkTask;
use super::content::ChunkContent;
use super::{ChunkStreamer, HexChunk, HexStreamingSettings};

/// Chunks with at most this many children are despawned at once: retiring them saves nothing.
const FEW_CHILDREN: usize = 8;

/// Retired chunks kept at most: beyond them the oldest is despawned whole, so an agent outrunning
/// the budget cannot pile up hidden entities. Hidden from the docs: public so the tests can
/// bound the entities streaming keeps.
#[doc(hidden)]
pub const MAX_RETIRED_CHUNKS: usize = 16;

/// A dropped chunk whose children are being despawned.
#[derive(Component, Debug, Clone, Copy, Default)]
pub(crate) struct Retired;

/// Dropped chunks, oldest first, whose children are being despawned.
#[derive(Debug, Default)]
pub(crate) struct Retiring(VecDeque<Entity>);

impl Retiring {
    pub(crate) fn len(&self) -> usize {
        self.0.len()
    }
}

/// Takes a dropped chunk out of the world: despawned at once when it has few children, else
/// hidden, stripped of what makes it a chunk and queued for [`reap`].
pub(crate) fn retire(commands: &mut Commands, streamer: &mut ChunkStreamer, chunk: Entity, children: usize) {
    if children <= FEW_CHILDREN {
        commands.entity(chunk).despawn();
        return;
    }
    let mut e = commands.entity(chunk);
    e.remove::<(HexChunk, ChunkTask, Mesh3d, ChunkContent)>().insert(Retired);
    #[cfg(feature = "render")]
    e.insert(Visibility::Hidden);
    streamer.retiring.0.push_back(chunk);
}

/// Despawns retired chunks' children, at most the settings' budget a frame, oldest chunk first,
/// each chunk with its last child.
pub(crate) fn reap(
    mut commands: Commands,
    mut streamer: ResMut<ChunkStreamer>,
    settings: Res<HexStreamingSettings>,
    children: Query<&Children, With<Retired>>,
) {
    if streamer.retiring.0.is_empty() {
        return;
    }
    let retiring = &mut streamer.retiring.0;
    while retiring.len() > MAX_RETIRED_CHUNKS {
        if let Some(oldest) = retiring.pop_front() {
            commands.entity(oldest).try_despawn();
        }
    }
    let mut budget = settings.max_despawns_per_frame.max(1);
    while budget > 0 {
        let Some(&chunk) = retiring.front() else { break };
        let kids: &[Entity] = children.get(chunk).map_or(&[], |c| c);
        let take = kids.len().min(budget);
        for &kid in &kids[kids.len() - take..] {
            commands.entity(kid).try_despawn();
        }
        budget -= take;
        if take < kids.len() {
            break;
        }
        commands.entity(chunk).try_despawn();
        retiring.pop_front();
    }
}
