//! Structure-aware: a shipped file (or the feedback cell's result) chosen and mutated by a
//! seed taken from the input, as the stable test `tests/fuzz_inputs.rs` does with fixed seeds.
#![no_main]

mod common;

use common::support::{exercise, mutated, Kind, FEEDBACK_RESULT, SHIPPED};
use rand::SeedableRng;
use std::path::Path;

libfuzzer_sys::fuzz_target!(|input: (u8, u64)| {
    let (which, seed) = input;
    let choice = which as usize % (SHIPPED.len() + 1);
    let (text, kind) = match SHIPPED.get(choice) {
        Some(&(file, kind)) => (
            std::fs::read_to_string(common::cells().join(file)).unwrap(),
            kind,
        ),
        None => (FEEDBACK_RESULT.to_owned(), Kind::Sequences),
    };
    let base: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let case = mutated(&base, &mut rng);
    exercise(kind, &case, Path::new("fuzz.json"), common::feedback());
});
