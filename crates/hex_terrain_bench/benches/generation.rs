//! Criterion benchmarks: noise (ours vs `noise`'s Perlin), basic PTG vs full generation, and
//! hexx's column mesh builder, on the Civ6 Duel map (44x26).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use hex_terrain::FastPerlin;
use hex_terrain_bench::{generate, hexx_columns, noise_floor, noise_floor_reference, terrains};
use noise::NoiseFn;

fn perlin(c: &mut Criterion) {
    let fast = FastPerlin::new(1000);
    let reference = noise::Perlin::new(1000);
    let mut group = c.benchmark_group("perlin 2d sample");
    group.bench_function("hex_terrain FastPerlin", |b| {
        let mut x = 0.0;
        b.iter(|| {
            x += 0.013;
            fast.get(black_box(x), black_box(x * 0.7))
        });
    });
    group.bench_function("noise::Perlin", |b| {
        let mut x = 0.0;
        b.iter(|| {
            x += 0.013;
            reference.get(black_box([x, x * 0.7]))
        });
    });
    group.finish();
}

fn generation(c: &mut Criterion) {
    let (full, basic) = terrains(44, 26, 3);
    let reference = noise::Perlin::new(1000);
    let mut group = c.benchmark_group("Civ6 Duel 44x26");
    group.sample_size(20);
    group.bench_function("basic PTG (no manipulation)", |b| b.iter(|| generate(&basic)));
    group.bench_function("full pipeline", |b| b.iter(|| generate(&full)));
    group.bench_function("noise floor (FastPerlin)", |b| b.iter(|| noise_floor(&full)));
    group.bench_function("noise floor (noise::Perlin)", |b| b.iter(|| noise_floor_reference(&full, &reference)));
    group.bench_function("hexx HeightMapMeshBuilder", |b| b.iter(|| hexx_columns(&full)));
    group.finish();
}

criterion_group!(benches, perlin, generation);
criterion_main!(benches);
