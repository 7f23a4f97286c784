//! The Sequences reader on arbitrary bytes, then what follows it; see `tests/fuzz_support`.
#![no_main]

mod common;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    common::exercise_bytes(common::support::Kind::Sequences, data);
});
