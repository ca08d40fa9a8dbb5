//! What streaming a sweep costs on top of solving it, per drive position.
//!
//! `slider_crank.toml, 10^6 positions: in-process sweep vs streamed outputs` — the scene of
//! `scenes/slider_crank.toml` (offset slider-crank, 8 output columns to second order) swept
//! over 0–360° in 10⁶ steps (the dead-position search of `s` is capped at 2¹⁶ intervals, so
//! at this count it adds ~5 % as in `mechdiff run` of 10⁶–10⁷ positions; at 10⁴ it would add
//! a second sweep):
//! - `sweep rows in process`: `Sweeper::row` at every position (the tracker's walk, the
//!   kinematics to second order and the outputs in SI), rows kept in one buffer: the
//!   in-process solver cost;
//! - `stream table + csv, N threads`: `stream::run` writing the streamed table (fixed-width
//!   scientific) and the CSV to `io::sink()`: everything `mechdiff run --csv` does per
//!   position except the write system calls. With 2 threads the batches are solved in
//!   parallel pieces and formatted in parallel.

use std::hint::black_box;
use std::path::PathBuf;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use mechdiff::scene::{self, Plan, Scene, Setup, Sweeper};
use mechdiff::stream::{self, Options, Sink, Sinks};

const POSITIONS: usize = 1_000_000;

fn slider_crank() -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/slider_crank.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let step = 360.0 / POSITIONS as f64;
    let text = text.replace("step = 5\n", &format!("step = {step}\n"));
    scene::parse("slider_crank.toml", &text).unwrap()
}

fn streaming(c: &mut Criterion) {
    let scene = slider_crank();
    let setup = Setup::of(&scene, &Default::default()).unwrap();
    let plan = Plan::of(&setup);
    let mut group = c
        .benchmark_group("slider_crank.toml, 10^6 positions: in-process sweep vs streamed outputs");
    group.sample_size(10);
    group.measurement_time(std::time::Duration::from_secs(20));
    group.throughput(Throughput::Elements(scene.positions.len() as u64));
    group.bench_function(BenchmarkId::from_parameter("sweep rows in process"), |b| {
        b.iter(|| {
            let mut sweeper = Sweeper::new(&setup, &plan).unwrap();
            let mut row = Vec::new();
            let mut sum = 0.0;
            for phi in scene.positions.iter() {
                sweeper.row(black_box(phi), &mut row).unwrap();
                sum += row[1];
            }
            sum
        });
    });
    for threads in [1, 2] {
        let name = format!("stream table + csv, {threads} threads");
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                let (mut table, mut csv) = (std::io::sink(), std::io::sink());
                let mut sinks = Sinks {
                    table: Some(Sink {
                        path: PathBuf::from("<stdout>"),
                        out: &mut table,
                    }),
                    csv: Some(Sink {
                        path: PathBuf::from("out.csv"),
                        out: &mut csv,
                    }),
                    jsonl: None,
                };
                let options = Options {
                    threads,
                    table_from_values: 0,
                    ..Options::default()
                };
                stream::run(black_box(&scene), &mut sinks, &options).unwrap()
            });
        });
    }
    group.finish();
}

criterion_group!(benches, streaming);
criterion_main!(benches);
