//! [`HexStreamingStats`]: streaming figures for counters, benchmarks and soak runs.

use std::collections::VecDeque;

use bevy::prelude::*;

/// How many recent chunk latencies are kept.
const LATENCY_WINDOW: usize = 1024;

/// Streaming figures, read through getters.
#[derive(Resource, Debug, Default, Reflect)]
#[reflect(Resource, Debug, Default)]
pub struct HexStreamingStats {
    latencies: VecDeque<f32>,
    tasks_started: u64,
    tasks_cancelled: u64,
    meshes_inserted: u64,
}

impl HexStreamingStats {
    /// Request-to-insert latency of the most recent chunks (up to 1024), in seconds, oldest
    /// first.
    pub fn latencies(&self) -> impl ExactSizeIterator<Item = f32> + '_ {
        self.latencies.iter().copied()
    }

    /// Chunk tasks started so far.
    #[must_use]
    pub fn tasks_started(&self) -> u64 {
        self.tasks_started
    }

    /// Chunk tasks dropped before their mesh was inserted (their chunk was no longer wanted).
    #[must_use]
    pub fn tasks_cancelled(&self) -> u64 {
        self.tasks_cancelled
    }

    /// Chunk meshes inserted so far.
    #[must_use]
    pub fn meshes_inserted(&self) -> u64 {
        self.meshes_inserted
    }

    pub(crate) fn started(&mut self) {
        self.tasks_started += 1;
    }

    pub(crate) fn cancelled(&mut self) {
        self.tasks_cancelled += 1;
    }

    pub(crate) fn inserted(&mut self, latency: f32) {
        if self.latencies.len() == LATENCY_WINDOW {
            self.latencies.pop_front();
        }
        self.latencies.push_back(latency);
        self.meshes_inserted += 1;
    }
}
