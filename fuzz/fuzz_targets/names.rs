//! Three body names from arbitrary bytes (split at `\n`), through the scene reader, the
//! check, the still picture and the page: refused naming the field, or drawn with nothing
//! forged and nothing raw; see `exercise_names` in `tests/fuzz_support`.
#![no_main]

mod common;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let mut names = text.splitn(3, '\n');
    let mut next = || names.next().unwrap_or("");
    let (a, b, c) = (next(), next(), next());
    common::support::exercise_names([a, b, c]);
});
