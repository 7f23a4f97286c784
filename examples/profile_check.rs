//! Runs `check` on one scene many times, for profilers: `cargo run --release --example
//! profile_check -- SCENE [REPETITIONS]`.

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .expect("usage: profile_check SCENE [REPETITIONS]");
    let reps: usize = args.next().map_or(1000, |s| s.parse().expect("a count"));
    let scene = workcell::cell::load_scene(path.as_ref())
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    let opts = workcell::collision::CheckOptions::default();
    let start = std::time::Instant::now();
    let mut intervals = 0;
    for _ in 0..reps {
        intervals += workcell::collision::check(&scene, &opts).stats.intervals;
    }
    let per = start.elapsed().as_secs_f64() / reps as f64;
    println!(
        "{:.2} us per check ({intervals} intervals in all)",
        per * 1e6
    );
}
